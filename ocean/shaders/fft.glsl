// fft.glsl: FftOcean's surface for the ocean shaders (SurfaceGpu contract, ocean/src/gpu/SurfaceGpu.h),
// sampling the maps FftGpu computes (fft_finalize.comp). Texel (i, j) holds the field at the grid point
// (i, j) L / N of the tile; the tile coordinate of a camera-relative point is uv = rel / L + uFftUvOffset,
// with uFftUvOffset = fract(camera.xy / L) formed in double on the CPU, so only [0, 1) offsets and
// camera-relative metres are ever floats.
//   modelDisplacement: exact path — texelFetch and bilinear weights between grid points formed here, so a
//     CPU implementation of the same formula reproduces it (at grid points: the FFT values themselves).
//   modelLighting: hardware trilinear filtering of the mipmapped slope map (GL's texel centres sit at
//     (i + 0.5) / N, hence the half-texel shift) and, in .z, the slope variance the filtering averaged
//     away, E[|g|^2] - |E[g]|^2 (LEAN mapping, Olano & Baker 2010), as ocean_common.glsl does for octaves.

// GRID_TEXTURE(s, p, scale): the lighting's mipmapped lookup at p = rel * scale + offset. The fragment stage
// takes its footprint from the pixel quad; compute shading (shade_compute.glsl) defines it with the
// G-buffer's derivatives of rel.
#ifndef GRID_TEXTURE
#define GRID_TEXTURE(s, p, scale) texture(s, p)
#endif

// Cascades (FftCascades): uFftCascades tiles, each with its own maps, tile and offset; the displacement and
// the lighting are sums over them (independent draws: the slope variances add too). FFT_MAX_CASCADES
// elements per array (OceanConstants.h; FFT_CASCADE_SUM below is written for 4). The maps of the cascades
// of one grid size are one 2D array (FftGpu's groups): cascade c's draws are its layers uFftLayer[c] and
// uFftLayer[c] + 1, and cascades of a group name the same texture units. With two draws per cascade
// (FftDesc::aperiodic) a cascade is w.x A + w.y B, w = (cos theta, sin theta),
// theta = FFT_MIX_AMPLITUDE sum_j sin(psi_j + k_j . rel) (FftCascades::mixWeights; psi_j formed in double
// about the camera); the lighting takes w.x m_A + w.y m_B for the mean slope and w.x^2 v_A + w.y^2 v_B for
// the unresolved variance (the draws are independent).
uniform int uFftCascades;
uniform int uFftDraws;                                     // 1, or 2 (aperiodic)
uniform sampler2DArray uFftDisplacement[FFT_MAX_CASCADES]; // RGBA32F (lambda Dx, lambda Dy, h, J), 1 level
uniform sampler2DArray uFftSlope[FFT_MAX_CASCADES];        // RGBA32F (g_x, g_y, g_x^2, g_y^2), mipmapped
uniform vec2 uFftUvOffset[FFT_MAX_CASCADES];               // fract(camera.xy / L)
uniform float uFftInvTile[FFT_MAX_CASCADES];               // 1 / L
uniform int uFftSize[FFT_MAX_CASCADES];                    // N (power of two)
uniform int uFftLayer[FFT_MAX_CASCADES];                   // the cascade's draw A in its maps (B: + 1)
uniform vec3 uFftMix[FFT_MAX_CASCADES * FFT_MIX_TERMS];    // (k_x, k_y, psi) per cascade and term
uniform float uFftFadeEnd[FFT_MAX_CASCADES]; // FftCascades::displacementFadeEnd (1e30: no fade)

vec2 fftMixWeights(int c, vec2 rel) {
    if (uFftDraws < 2)
        return vec2(1.0, 0.0);
    float theta = APERIODIC_MIX_THETA(uFftMix, c * FFT_MIX_TERMS, rel);
    return vec2(cos(theta), sin(theta));
}

// Cascade c's texels around rel: bilinear weights in a, the four texel indices.
struct FftCell {
    vec2 a;
    ivec2 t00, t10, t01, t11;
};
FftCell fftCell(int c, vec2 rel) {
    int n = uFftSize[c];
    vec2 p = fract(rel * uFftInvTile[c] + uFftUvOffset[c]) * float(n); // grid units, [0, N]
    vec2 p0 = floor(p);
    ivec2 t0 = ivec2(p0);
    FftCell cell;
    cell.a = p - p0;
    cell.t00 = t0 & (n - 1);
    cell.t10 = (t0 + ivec2(1, 0)) & (n - 1);
    cell.t01 = (t0 + ivec2(0, 1)) & (n - 1);
    cell.t11 = (t0 + ivec2(1, 1)) & (n - 1);
    return cell;
}

// Bilinear (exact path) of layer `layer` of a one-level array map.
vec4 fftBilinear(sampler2DArray map, FftCell cell, int layer) {
    vec4 d00 = texelFetch(map, ivec3(cell.t00, layer), 0);
    vec4 d10 = texelFetch(map, ivec3(cell.t10, layer), 0);
    vec4 d01 = texelFetch(map, ivec3(cell.t01, layer), 0);
    vec4 d11 = texelFetch(map, ivec3(cell.t11, layer), 0);
    vec4 bottom = d00 + (d10 - d00) * cell.a.x;
    vec4 top = d01 + (d11 - d01) * cell.a.x;
    return bottom + (top - bottom) * cell.a.y;
}

// The displacement's distance fade (FftCascades::displacementFadeEnd; GerstnerWaves::fade):
// s^2 (3 - 2 s), s = clamp((R - r) / (R / 2), 0, 1).
float fftFade(float r, float fadeEnd) {
    float s = clamp((fadeEnd - r) / (0.5 * fadeEnd), 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
}

vec3 fftDisplacement(sampler2DArray map, int c, vec2 rel) {
    float fade = fftFade(length(rel), uFftFadeEnd[c]);
    if (fade == 0.0)
        return vec3(0.0);
    FftCell cell = fftCell(c, rel);
    vec3 d = fftBilinear(map, cell, uFftLayer[c]).xyz;
    if (uFftDraws < 2)
        return fade * d;
    vec2 w = fade * fftMixWeights(c, rel);
    return w.x * d + w.y * fftBilinear(map, cell, uFftLayer[c] + 1).xyz;
}

// FFT_CASCADE_SUM(f, maps): f(maps[c], c, rel) summed over the cascades, each array element named by a
// constant index (llvmpipe's compiler crashes on a dynamically indexed sampler under textureGrad).
#define FFT_CASCADE_SUM(T, f, maps)                                                                          \
    T sum = f(maps[0], 0, rel);                                                                              \
    if (uFftCascades > 1) sum += f(maps[1], 1, rel);                                                         \
    if (uFftCascades > 2) sum += f(maps[2], 2, rel);                                                         \
    if (uFftCascades > 3) sum += f(maps[3], 3, rel);                                                         \
    return sum;

vec3 modelDisplacement(vec2 rel) { FFT_CASCADE_SUM(vec3, fftDisplacement, uFftDisplacement) }

// Foam inputs (ocean.frag): (h, J) of cascade 0 (h plus cascade 1's height), bilinear from the same texels
// as modelDisplacement — J is
// the Jacobian determinant of the choppy map, computed with the displacement (fft_finalize.comp; Tessendorf
// 2001 §4.4); the whitecaps follow the largest waves (FftCascades::foamHeightAt). With the living whitecaps
// (uFftFoamMemory, FftDesc::foamMemory) h is the remembered crest height, max(h, decay * M) with M the
// memory map bilinear from the same texels (FftOcean::foamHeightAt, the CPU twin): foam stays where a crest
// passed and fades. The crests' glow then takes the displaced height. Two draws: h = w.x h_A + w.y h_B,
// J ~ 1 + w.x (J_A - 1) + w.y (J_B - 1) (first order in the displacement's derivatives), and M = |w.x| times
// A's memory of the crests of sign(w.x) h_A, plus the same of B.
#define MODEL_HAS_FOAM_INPUTS
#define MODEL_FOAM_REMEMBERS
uniform sampler2DArray uFftFoam; // RG32F memory maps M_j (crests of +h, of -h), a layer per draw
uniform bool uFftFoamMemory;
uniform float uFftFoamDecay;     // e^(-(t - t_j) / FOAM_DECAY_TIME), formed in double
vec2 modelFoamInputs(vec2 rel) {
    FftCell cell = fftCell(0, rel);
    vec2 w = fftMixWeights(0, rel);
    vec2 a = fftBilinear(uFftDisplacement[0], cell, uFftLayer[0]).zw;
    vec2 hj = a;
    if (uFftDraws > 1) {
        vec2 b = fftBilinear(uFftDisplacement[0], cell, uFftLayer[0] + 1).zw;
        hj = vec2(w.x * a.x + w.y * b.x, 1.0 + w.x * (a.y - 1.0) + w.y * (b.y - 1.0));
    }
    if (uFftFoamMemory) {
        vec2 ma = fftBilinear(uFftFoam, cell, 0).rg;
        float m = w.x >= 0.0 ? w.x * ma.r : -w.x * ma.g;
        if (uFftDraws > 1) {
            vec2 mb = fftBilinear(uFftFoam, cell, 1).rg;
            m += w.y >= 0.0 ? w.y * mb.r : -w.y * mb.g;
        }
        hj.x = max(hj.x, uFftFoamDecay * m);
    }
    // Cascade 1's shorter waves riding on the crests (FftCascades::foamHeightAt): ragged whitecaps of many
    // sizes instead of the long crests' smooth caps. Bilinear from its texels, unfaded.
    if (uFftCascades > 1) {
        FftCell cell1 = fftCell(1, rel);
        float h1 = fftBilinear(uFftDisplacement[1], cell1, uFftLayer[1]).z;
        if (uFftDraws > 1) {
            vec2 w1 = fftMixWeights(1, rel);
            h1 = w1.x * h1 + w1.y * fftBilinear(uFftDisplacement[1], cell1, uFftLayer[1] + 1).z;
        }
        hj.x += h1;
    }
    return hj;
}

vec3 fftLighting(sampler2DArray slopes, int c, vec2 rel) {
    vec2 uv = rel * uFftInvTile[c] + uFftUvOffset[c] + 0.5 / float(uFftSize[c]);
    vec4 s = GRID_TEXTURE(slopes, vec3(uv, float(uFftLayer[c])), uFftInvTile[c]);
    vec3 a = vec3(s.xy, max(s.z + s.w - dot(s.xy, s.xy), 0.0));
    if (uFftDraws < 2)
        return a;
    vec4 t = GRID_TEXTURE(slopes, vec3(uv, float(uFftLayer[c] + 1)), uFftInvTile[c]);
    vec3 b = vec3(t.xy, max(t.z + t.w - dot(t.xy, t.xy), 0.0));
    vec2 w = fftMixWeights(c, rel);
    return vec3(w.x * a.xy + w.y * b.xy, w.x * w.x * a.z + w.y * w.y * b.z);
}

vec3 modelLighting(vec2 rel) { FFT_CASCADE_SUM(vec3, fftLighting, uFftSlope) }
