// shade_compute.glsl: the first file of the compute-shading program (OceanDesc::computeShading,
// ocean_shade.comp). The lighting code (the model's modelLighting, sky.glsl, ocean.frag) reads textures
// with a footprint that the fragment stage takes from its 2x2 pixel quad (implicit derivatives, dFdx). A
// compute pass has no quads: ocean_shade.comp puts the footprints here (from the G-buffer's quad
// derivatives) before it calls the lighting, which samples with textureGrad.
vec2 gGridDx = vec2(0.0), gGridDy = vec2(0.0); // screen derivatives of the camera-relative grid point (vGrid)
vec3 gRelDx = vec3(0.0), gRelDy = vec3(0.0); // and of the camera-relative surface point (vRel)
#define GRID_TEXTURE(s, p, scale) textureGrad(s, p, gGridDx * (scale), gGridDy * (scale))
