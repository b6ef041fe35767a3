// effects_field.comp: the effects field (Effects.h, EffectFieldLayout) for one frame. One work group per
// tile of 8 x 8 texels that an effect touches (EffectsGpu.cpp bins them on the CPU); each texel sums the
// effects of its tile's list at its centre, band-limited to its level (4 texels per wavelength at the
// shortest), saturates the height (E = L tanh(sum / L)) and stores (E, dE/dx, dE/dy, foam). A tile written
// last frame that no effect touches now is in the list with no effects: it is cleared. The cost is the
// texels the effects touch, whatever the grids that read them. effects.glsl comes before this file.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f, binding = EFFECT_FIELD_IMAGE_UNIT) writeonly uniform image2DArray uFieldImage;

struct EffectTileGpu { // GpuInterface.h
    int level;
    int tileX;
    int tileY;
    int first;
    int explosions;
    int wakes;
    int pad0;
    int pad1;
};
layout(std430, binding = EFFECT_FIELD_TILES_BINDING) readonly buffer EffectFieldTiles { EffectTileGpu uTiles[]; };
layout(std430, binding = EFFECT_FIELD_LISTS_BINDING) readonly buffer EffectFieldLists { int uTileEffects[]; };

uniform int uTileCount;
uniform int uTileGroupsX;                                  // work groups along x (the list wraps onto y)
uniform vec3 uEffectFieldLevels[EFFECT_FIELD_MAX_LEVELS]; // (level centre - camera, texel)
uniform float uEffectFieldSize;                            // texels per side

void main() {
    int index = int(gl_WorkGroupID.x) + int(gl_WorkGroupID.y) * uTileGroupsX;
    if (index >= uTileCount)
        return;
    EffectTileGpu tile = uTiles[index];
    ivec2 texel = ivec2(tile.tileX, tile.tileY) * 8 + ivec2(gl_LocalInvocationID.xy);
    vec3 level = uEffectFieldLevels[tile.level];
    // EffectFieldLayout::texelCentre(): a texel centre, camera-relative.
    vec2 rel = level.xy + (vec2(texel) + 0.5 - 0.5 * uEffectFieldSize) * level.z;
    float kMax = min(EFFECT_K_MAX, EFFECT_TWO_PI / (4.0 * level.z));
    float filter2 = level.z * level.z / 6.0; // EffectFieldLevel::foamFilter2
    vec3 sum = vec3(0.0);
    float foam = 0.0;
#ifdef EFFECTS_EXPLOSIONS
    for (int k = 0; k < tile.explosions; ++k) {
        int i = uTileEffects[tile.first + k];
        vec2 q = rel - uExplosions[i].centre;
        float R = uExplosions[i].gridRadius;
        if (dot(q, q) >= R * R)
            continue;
        vec3 w = explosionWave(i, q, kMax);
        sum += w;
        foam = max(foam, explosionFoam(i, q, w.x, filter2));
    }
#endif
#ifdef EFFECTS_WAKES
    for (int k = 0; k < tile.wakes; ++k) {
        // (wake, first segment, last segment) packed: EffectsGpu.cpp wakeEntry().
        int entry = uTileEffects[tile.first + tile.explosions + k];
        int i = entry & 0xFFFF;
        vec4 w = wakeWave(i, rel - uWakes[i].ship, kMax, (entry >> 16) & 0x7F, (entry >> 23) & 0x7F, filter2);
        sum += w.xyz;
        foam = max(foam, w.w);
    }
#endif
    // Effects.cpp saturate(); the argument clamped where tanh is 1 in float (a thousand explosions in one
    // spot must not overflow an exp inside tanh).
    float th = tanh(clamp(sum.x / EFFECT_HEIGHT_LIMIT, -10.0, 10.0));
    imageStore(uFieldImage, ivec3(texel, tile.level), vec4(EFFECT_HEIGHT_LIMIT * th, sum.yz * (1.0 - th * th), foam));
}
