// effects_sample.glsl: reading the effects field (Effects.h EffectFieldLayout; written by
// effects_field.comp). Every grid that draws the sea with effects present (the base grid, the secondary
// grids) and the shading read it here: the height per vertex, the slope and foam per pixel. The twin on the
// CPU is sampleEffectField() (Effects.cpp); the bilinear weights are computed here, not by the texture unit
// (whose weights have as few as 8 fractional bits), so the two agree to float rounding.

uniform sampler2DArray uEffectField;                       // (E, dE/dx, dE/dy, foam) per level
uniform vec3 uEffectFieldLevels[EFFECT_FIELD_MAX_LEVELS]; // (level centre - camera, texel)
uniform int uEffectFieldLevelCount;
// Per level, camera-relative (min, max) of the texel centres of its tiles with effects this frame: every texel
// outside is 0, so a point more than a texel outside reads 0 without a fetch (the same value).
uniform vec4 uEffectFieldBoxes[EFFECT_FIELD_MAX_LEVELS];
// Their union, each widened by its level's texel: a point outside reads 0 from every level.
uniform vec4 uEffectFieldBounds;
uniform float uEffectFieldSize;
// The secondary grids drawn this frame (explosions' first, then wakes'): (centre - camera, radius, 0).
layout(std430, binding = EFFECT_GRIDS_BINDING) readonly buffer EffectGrids { vec4 uEffectGrids[]; };
uniform int uEffectGridCount;

// Level l read bilinearly at rel (camera-relative): Effects.cpp bilinear().
vec4 effectFieldLevel(int l, vec2 rel) {
    vec3 level = uEffectFieldLevels[l];
    vec4 box = uEffectFieldBoxes[l];
    if (any(lessThan(rel, box.xy - level.z)) || any(greaterThan(rel, box.zw + level.z)))
        return vec4(0.0);
    vec2 u = (rel - level.xy) / level.z + 0.5 * uEffectFieldSize - 0.5;
    vec2 f = floor(u);
    vec2 w = u - f;
    ivec2 i = clamp(ivec2(f), ivec2(0), ivec2(int(uEffectFieldSize) - 2));
    vec4 a = texelFetch(uEffectField, ivec3(i, l), 0);
    vec4 b = texelFetch(uEffectField, ivec3(i + ivec2(1, 0), l), 0);
    vec4 c = texelFetch(uEffectField, ivec3(i + ivec2(0, 1), l), 0);
    vec4 d = texelFetch(uEffectField, ivec3(i + ivec2(1, 1), l), 0);
    return mix(mix(a, b, w.x), mix(c, d, w.x), w.y);
}

// (E, dE/dx, dE/dy, foam) at a camera-relative point: the finest level that holds it, blended into the next
// over the level's outer eighth (EffectFieldLayout::pick), 0 outside the field.
vec4 effectFieldAt(vec2 rel) {
    if (any(lessThan(rel, uEffectFieldBounds.xy)) || any(greaterThan(rel, uEffectFieldBounds.zw)))
        return vec4(0.0); // most of the sea in most frames: no level walk, no fetch
    for (int l = 0; l < uEffectFieldLevelCount; ++l) {
        vec3 level = uEffectFieldLevels[l];
        vec2 d = abs(rel - level.xy);
        float a = max(d.x, d.y);
        float inner = (0.5 * uEffectFieldSize - 2.0) * level.z;
        if (a < inner) {
            float band = uEffectFieldSize / 8.0 * level.z;
            float t = clamp((a - (inner - band)) / band, 0.0, 1.0);
            vec4 v = effectFieldLevel(l, rel);
            if (t > 0.0)
                v = mix(v, l + 1 < uEffectFieldLevelCount ? effectFieldLevel(l + 1, rel) : vec4(0.0), t);
            return v;
        }
    }
    return vec4(0.0);
}

// True where a secondary grid draws the sea instead of the base grid: inside 0.98 of a drawn grid's radius
// (the rims overlap by 2% so no crack opens between the grids).
bool insideEffectGrid(vec2 rel) {
    for (int i = 0; i < uEffectGridCount; ++i) {
        vec2 q = rel - uEffectGrids[i].xy;
        float R = 0.98 * uEffectGrids[i].z;
        if (dot(q, q) < R * R)
            return true;
    }
    return false;
}

#ifdef EFFECT_GRID_CLIP
// Vertex stages only. The hole of the base grid (and of a later grid under an earlier one) cut by the
// clipper instead of the fragment stage: clip distance i is the distance of the undisplaced point from drawn
// grid i's disc of 0.98 of its radius, for the grids with index < first (the base grid: all of them; grid k:
// those drawn before it), 1 for the rest. The clipper interpolates each distance linearly over a triangle,
// and |q| - R is convex, so the interpolated value is never below the true one: it removes only points inside
// the disc, never a point the disc's grid does not draw. The base grid's fragment test (insideEffectGrid)
// stays exact; this spares the fragments in the holes, which on a GPU whose graphics run on few units cost
// about as much as drawing them (docs/EFFECTS_BENCH.md "Holes cut by the clipper").
out float gl_ClipDistance[EFFECT_GRID_CLIPS];
void clipEffectGrids(vec2 rel, int first) {
    int n = min(first, uEffectGridCount);
    for (int i = 0; i < EFFECT_GRID_CLIPS; ++i) {
        float c = 1.0;
        if (i < n)
            c = length(rel - uEffectGrids[i].xy) - 0.98 * uEffectGrids[i].z;
        gl_ClipDistance[i] = c;
    }
}
#endif
