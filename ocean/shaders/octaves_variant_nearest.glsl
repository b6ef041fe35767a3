// octaves_variant_nearest.glsl: selects VertexFilter::Nearest in octaves.glsl
// (OctavesGpu::glslFiles() lists it before octaves.glsl).
#define OCTAVE_VERTEX_FILTER OCTAVE_FILTER_NEAREST
