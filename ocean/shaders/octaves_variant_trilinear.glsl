// octaves_variant_trilinear.glsl: selects VertexFilter::Trilinear in octaves.glsl
// (OctavesGpu::glslFiles() lists it before octaves.glsl).
#define OCTAVE_VERTEX_FILTER OCTAVE_FILTER_TRILINEAR
