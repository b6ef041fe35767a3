// octaves_variant_hwbilinear.glsl: selects VertexFilter::HardwareBilinear in octaves.glsl
// (OctavesGpu::glslFiles() lists it before octaves.glsl).
#define OCTAVE_VERTEX_FILTER OCTAVE_FILTER_HARDWARE_BILINEAR
