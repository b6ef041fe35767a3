// octaves_light_mix.comp: the lighting maps at this frame's time, once per frame instead of once per pixel.
// Every octave's map is looped in time as `frames` slices (layer = octave * frames + frame of uLightMaps);
// ocean.frag's lighting used to sample two slices per octave and mix them (HeightOctaves::sampleHeight's
// linear interpolation in time). Filtering is linear, so filter(mix(a, b)) = mix(filter(a), filter(b)):
// this pass mixes the two slices texel by texel at every mip level (level uLevel per dispatch) into
// uLightNow (one layer per octave), and the lighting does one trilinear fetch per octave. The only change
// is one rounding of the mix to half (RGBA16F, 2^-11 relative). Sources: the ocean constants, this file.

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(rgba16f, binding = OCTAVE_LIGHT_IMAGE_UNIT) writeonly uniform image2DArray uLightNowImage;
uniform sampler2DArray uLightMaps; // the slices, mipmapped
uniform int uLevel;
uniform int uFrames;
uniform int uOctaveCount;
uniform float uFramePos[MAX_OCTAVES]; // wrap(t, T_i) / T_i * frames, computed in double on the CPU

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    int size = textureSize(uLightMaps, uLevel).x;
    if (id.x >= size || id.y >= size || id.z >= uOctaveCount)
        return;
    float fp = uFramePos[id.z];
    float f0 = floor(fp);
    float at = fp - f0;
    int base = id.z * uFrames;
    int l0 = base + int(mod(f0, float(uFrames)));
    int l1 = base + int(mod(f0 + 1.0, float(uFrames)));
    vec4 a = texelFetch(uLightMaps, ivec3(id.xy, l0), uLevel);
    vec4 b = texelFetch(uLightMaps, ivec3(id.xy, l1), uLevel);
    imageStore(uLightNowImage, id, a + (b - a) * at);
}
