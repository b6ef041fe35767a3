// octaves.glsl: the height-map octave surface model (GPU side of HeightOctaves) for the sea shaders and the
// combine pass (octaves_combine.comp). Every vertex displacement path mirrors its HeightOctaves twin on the
// CPU line by line (GPU Gems 2 §18.2.1: H(x,t) = sum A_i h_i(B_i x, t); filters §18.2.4, listings 18-2 and
// 18-3; the combined two-pass path §18.2.5). The lighting path uses hardware trilinear filtering with
// mipmaps, where aliasing matters more than exactness.
//
// Variant selection (an absent feature costs no shader work): OctavesGpu::glslFiles() puts one of the
// octaves_variant_*.glsl files before this one, which defines OCTAVE_VERTEX_FILTER (default: Bilinear)
// and/or OCTAVES_COMBINED.

// GRID_TEXTURE(s, p, scale): the lighting's mipmapped lookup at p = rel * scale + offset. The fragment stage
// takes its footprint from the pixel quad; compute shading (shade_compute.glsl) defines it with the
// G-buffer's derivatives of rel.
#ifndef GRID_TEXTURE
#define GRID_TEXTURE(s, p, scale) texture(s, p)
#endif

#define OCTAVE_FILTER_NEAREST 0
#define OCTAVE_FILTER_BILINEAR 1
#define OCTAVE_FILTER_HARDWARE_BILINEAR 2
#define OCTAVE_FILTER_PACKED_4TAP 3
#define OCTAVE_FILTER_TRILINEAR 4
#ifndef OCTAVE_VERTEX_FILTER
#define OCTAVE_VERTEX_FILTER OCTAVE_FILTER_BILINEAR
#endif
// HeightOctaves::MAX_COMBINED_LEVELS (OctavesGpu checks that the two agree).
#define OCTAVES_MAX_COMBINED_LEVELS 16

// Every octave's map (h, dh/du, dh/dv, |grad h|^2) at this frame's time, mipmapped, one layer per octave:
// the two time slices mixed once per frame by octaves_light_mix.comp (OctavesGpu::update), not per pixel.
uniform sampler2DArray uLightNow;
uniform int uOctaveCount;     // octaves used for lighting normals
uniform int uDisplacedCount;  // leading octaves that displace vertices
uniform int uMapSize;
uniform int uFrames;
uniform vec2 uUvOffset[MAX_OCTAVES];   // fract(camera.xy * B_i), computed in double on the CPU
uniform float uInvTile[MAX_OCTAVES];   // B_i
uniform float uAmplitude[MAX_OCTAVES]; // A_i
uniform float uFramePos[MAX_OCTAVES];  // wrap(t, T_i) / T_i * frames, computed in double on the CPU

// The displaced octaves' heights for the vertex filters, one array for all of them, layer = octave * frames
// + frame (one sampler: with a sampler array indexed dynamically llvmpipe was 1.3-3.6x slower per lookup): an
// R16F copy of h (Nearest, Bilinear via texelFetch; HardwareBilinear with GL_LINEAR and GL_REPEAT), or the
// RGBA16F packed texels of listing 18-2 (HeightOctaves::packedTexel; Packed4Tap: level 0, Trilinear: the
// whole mip chain).
uniform sampler2DArray uFilterMaps;
#if OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_TRILINEAR
uniform float uLodTexels;     // HeightOctavesDesc.trilinearLodTexels
uniform int uMaxLevel;        // HeightOctaves::mipLevels() - 1
uniform vec2 uTrilinearBand;  // (TRILINEAR_BAND_LOW, TRILINEAR_BAND_HIGH) = (0.3, 0.7), listing 18-3
#endif

// Tile coordinate of a camera-relative horizontal position for octave i.
vec2 octaveUv(int i, vec2 rel) { return rel * uInvTile[i] + uUvOffset[i]; }

// Listing 18-2 (tex2D_bilinear4x): one fetch of the packed texel holding the 2x2 footprint. The lower-left
// texel is fetched by index with the texel-centre convention of the exact path.
float packedBilinear(int i, vec2 uv, int level, int frame) {
#if OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_PACKED_4TAP || OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_TRILINEAR
    int s = uMapSize >> level;
    vec2 p = fract(uv) * float(s) - 0.5;
    vec2 p0 = floor(p);
    vec2 a = p - p0;
    vec4 t = texelFetch(uFilterMaps, ivec3(ivec2(p0) & (s - 1), i * uFrames + frame), level);
    vec2 ab = t.xz + (t.yw - t.xz) * a.x; // lerp(tAB0.xz, tAB0.yw, f.x)
    return ab.x + (ab.y - ab.x) * a.y;    // lerp(tAB.x, tAB.y, f.y)
#else
    return 0.0;
#endif
}

// One time slice of octave i's height at tile coordinate uv with the selected vertex filter.
float octaveSlice(int i, vec2 uv, int frame, float lod) {
    int m = uMapSize - 1; // power-of-two size: & wraps negatives too
    int layer = i * uFrames + frame;
#if OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_NEAREST
    ivec2 t = ivec2(floor(fract(uv) * float(uMapSize))) & m;
    return texelFetch(uFilterMaps, ivec3(t, layer), 0).x;
#elif OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_BILINEAR
    vec2 p = fract(uv) * float(uMapSize) - 0.5;
    vec2 p0 = floor(p);
    vec2 a = p - p0;
    ivec2 t0 = ivec2(p0);
    ivec2 t1 = t0 + ivec2(1);
    float h00 = texelFetch(uFilterMaps, ivec3(t0.x & m, t0.y & m, layer), 0).x;
    float h10 = texelFetch(uFilterMaps, ivec3(t1.x & m, t0.y & m, layer), 0).x;
    float h01 = texelFetch(uFilterMaps, ivec3(t0.x & m, t1.y & m, layer), 0).x;
    float h11 = texelFetch(uFilterMaps, ivec3(t1.x & m, t1.y & m, layer), 0).x;
    float bottom = h00 + (h10 - h00) * a.x;
    float top = h01 + (h11 - h01) * a.x;
    return bottom + (top - bottom) * a.y;
#elif OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_HARDWARE_BILINEAR
    return texture(uFilterMaps, vec3(fract(uv), float(layer))).x;
#elif OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_PACKED_4TAP
    return packedBilinear(i, uv, 0, frame);
#else
    // Listing 18-3 (tex2D_trilinear): snap to the nearer level outside the band, blend inside it.
    float base = floor(lod);
    float fr = lod - base;
    int level = int(base);
    if (fr < uTrilinearBand.x)
        return packedBilinear(i, uv, level, frame);
    if (fr > uTrilinearBand.y)
        return packedBilinear(i, uv, level + 1, frame);
    float r0 = packedBilinear(i, uv, level, frame);
    float r1 = packedBilinear(i, uv, level + 1, frame);
    float w = (fr - uTrilinearBand.x) / (uTrilinearBand.y - uTrilinearBand.x);
    return r0 + (r1 - r0) * w;
#endif
}

// Height of octave i (unit RMS map) at camera-relative rel: the selected filter in space, linear in time
// between slices (HeightOctaves::sampleHeight).
float octaveHeight(int i, vec2 rel) {
    vec2 uv = octaveUv(i, rel);
    float lod = 0.0;
#if OCTAVE_VERTEX_FILTER == OCTAVE_FILTER_TRILINEAR
    // HeightOctaves::trilinearLod: lambda = log2(d B_i size / trilinearLodTexels), clamped to the chain.
    float rho = length(rel) * uInvTile[i] * float(uMapSize) / uLodTexels;
    lod = clamp(log2(max(rho, 1.0)), 0.0, float(uMaxLevel));
#endif
    float fp = uFramePos[i];
    float f0 = floor(fp);
    float at = fp - f0;
    int frame0 = int(f0) % uFrames;
    int frame1 = (frame0 + 1) % uFrames;
    float s0 = octaveSlice(i, uv, frame0, lod);
    float s1 = octaveSlice(i, uv, frame1, lod);
    return s0 + (s1 - s0) * at;
}

// The per-vertex path: displacement height of the displaced octaves, metres above mean sea level
// (HeightOctaves::filteredHeight).
float displacedHeight(vec2 rel) {
    float h = 0.0;
    for (int i = 0; i < uDisplacedCount; ++i)
        h += uAmplitude[i] * octaveHeight(i, rel);
    return h;
}

// The combined levels (HeightOctaves::combined*): level k has texel uCombinedTexel0 * 2^k and its node
// (i, j) at camera-relative uCombinedOrigin[k] + ((i, j) + 0.5 - size / 2) * texel.
uniform int uCombinedSize;
uniform int uCombinedLevels;
uniform float uCombinedTexel0;
uniform vec2 uCombinedOrigin[OCTAVES_MAX_COMBINED_LEVELS]; // floor(camera / texel_k) * texel_k - camera

float combinedTexel(int k) { return ldexp(uCombinedTexel0, k); }
// Chebyshev distance up to which a point's bilinear footprint lies inside level k.
float combinedReach(int k) { return float(uCombinedSize / 2 - 2) * combinedTexel(k); }
vec2 combinedNodeRel(ivec2 node, int k) {
    return uCombinedOrigin[k] + (vec2(node) + 0.5 - 0.5 * float(uCombinedSize)) * combinedTexel(k);
}

#ifdef OCTAVES_COMBINED
uniform sampler2DArray uCombined; // R32F, uCombinedSize^2 x uCombinedLevels, written by the combine pass

// §18.2.5: one fetch of the combined texture instead of the per-octave filtered lookups. textureGather at
// the shared corner of the 2x2 footprint returns exactly those texels (0.5 texel away from any footprint
// change, so the GPU's fixed-point coordinates cannot pick another), weights computed in float.
float combinedHeight(vec2 rel) {
    float r = max(abs(rel.x), abs(rel.y));
    int k = 0;
    while (k < uCombinedLevels - 1 && r > combinedReach(k))
        ++k;
    float n = float(uCombinedSize);
    vec2 p = clamp((rel - uCombinedOrigin[k]) / combinedTexel(k) + (0.5 * n - 0.5), vec2(0.0), vec2(n - 1.0));
    vec2 p0 = min(floor(p), vec2(n - 2.0));
    vec2 a = p - p0;
    vec4 g = textureGather(uCombined, vec3((p0 + 1.0) / n, float(k))); // (i0,j1) (i1,j1) (i1,j0) (i0,j0)
    float bottom = g.w + (g.z - g.w) * a.x;
    float top = g.x + (g.y - g.x) * a.x;
    return bottom + (top - bottom) * a.y;
}
#endif

// World-space gradient (dH/dx, dH/dy) from every lighting octave, with hardware trilinear filtering, and
// in .z the slope variance the mip filtering averaged away: sum_i (A_i B_i)^2 (E[|s|^2] - |E[s]|^2)
// (LEAN mapping, Olano & Baker 2010), which the lighting adds to the specular roughness. The same fetches
// give the living whitecaps' foam height: a displaced octave's map carries its foam memory in the channel the
// lighting does not read (OctaveMap::foam, HeightOctaves::foamHeightAt), summed into gOctaveFoam.
// The lighting-only octaves' aperiodic mix (HeightOctavesDesc::aperiodic): w = (cos theta, sin theta),
// theta = FFT_MIX_AMPLITUDE sum_j sin(psi_j + k_j . rel) with psi_j formed in double about the camera
// (aperiodicMixWeights, SurfaceModel.h); B is the map shifted by OCTAVE_MIX_SHIFT tiles.
uniform bool uOctaveAperiodic;
uniform vec3 uOctaveMix[MAX_OCTAVES * FFT_MIX_TERMS]; // (k_x, k_y, psi) per octave and term
vec2 octaveMixWeights(int i, vec2 rel) {
    float theta = APERIODIC_MIX_THETA(uOctaveMix, i * FFT_MIX_TERMS, rel);
    return vec2(cos(theta), sin(theta));
}

float gOctaveFoam = 0.0;
vec3 filteredGradient(vec2 rel) {
    vec3 g = vec3(0.0);
    float foam = 0.0;
    for (int i = 0; i < uOctaveCount; ++i) {
        vec2 uv = octaveUv(i, rel);
        vec4 d = GRID_TEXTURE(uLightNow, vec3(uv, float(i)), uInvTile[i]);
        float scale = uAmplitude[i] * uInvTile[i];
        if (uOctaveAperiodic && i >= uDisplacedCount) {
            vec4 e = GRID_TEXTURE(uLightNow, vec3(uv + vec2(OCTAVE_MIX_SHIFT_U, OCTAVE_MIX_SHIFT_V), float(i)),
                                  uInvTile[i]);
            vec2 w = octaveMixWeights(i, rel);
            g.xy += scale * (w.x * d.yz + w.y * e.yz);
            g.z += scale * scale *
                   (w.x * w.x * max(d.w - dot(d.yz, d.yz), 0.0) + w.y * w.y * max(e.w - dot(e.yz, e.yz), 0.0));
            continue; // a lighting-only octave carries no foam
        }
        g.xy += scale * d.yz;
        g.z += scale * scale * max(d.w - dot(d.yz, d.yz), 0.0);
        foam += i < uDisplacedCount ? uAmplitude[i] * d.x : 0.0;
    }
    gOctaveFoam = foam;
    return g;
}

// The surface-model contract (ocean/src/gpu/SurfaceGpu.h).
#ifdef OCTAVES_COMBINED
vec3 modelDisplacement(vec2 rel) { return vec3(0.0, 0.0, combinedHeight(rel)); }
#else
vec3 modelDisplacement(vec2 rel) { return vec3(0.0, 0.0, displacedHeight(rel)); }
#endif
vec3 modelLighting(vec2 rel) { return filteredGradient(rel); }
// Foam inputs: (foam height, J = 1). The foam height comes with the lighting fetches, so this must follow
// modelLighting() at the same point (ocean.frag calls them in that order). It is a memory of crests, not the
// surface's height: the crests' glow takes the displaced height instead (MODEL_FOAM_REMEMBERS).
#define MODEL_HAS_FOAM_INPUTS
#define MODEL_FOAM_REMEMBERS
vec2 modelFoamInputs(vec2 rel) { return vec2(gOctaveFoam, 1.0); }
