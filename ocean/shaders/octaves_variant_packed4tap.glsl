// octaves_variant_packed4tap.glsl: selects VertexFilter::Packed4Tap in octaves.glsl
// (OctavesGpu::glslFiles() lists it before octaves.glsl).
#define OCTAVE_VERTEX_FILTER OCTAVE_FILTER_PACKED_4TAP
