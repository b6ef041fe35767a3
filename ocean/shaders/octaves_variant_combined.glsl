// octaves_variant_combined.glsl: selects the combined two-pass displacement (GPU Gems 2 §18.2.5) in
// octaves.glsl: the vertex shader reads the texture octaves_combine.comp wrote, whatever the vertex filter.
#define OCTAVES_COMBINED
