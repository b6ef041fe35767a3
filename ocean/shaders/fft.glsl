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

uniform sampler2D uFftDisplacement; // RGBA32F (lambda Dx, lambda Dy, h, J), one level
uniform sampler2D uFftSlope;        // RGBA32F (g_x, g_y, g_x^2, g_y^2), full mip chain, repeat
uniform vec2 uFftUvOffset;          // fract(camera.xy / L)
uniform float uFftInvTile;          // 1 / L
uniform int uFftSize;               // N (power of two)

vec3 fftFetch(ivec2 t) { return texelFetch(uFftDisplacement, t & (uFftSize - 1), 0).xyz; }

vec3 modelDisplacement(vec2 rel) {
    vec2 p = fract(rel * uFftInvTile + uFftUvOffset) * float(uFftSize); // grid units, [0, N]
    vec2 p0 = floor(p);
    vec2 a = p - p0;
    ivec2 t0 = ivec2(p0);
    vec3 d00 = fftFetch(t0);
    vec3 d10 = fftFetch(t0 + ivec2(1, 0));
    vec3 d01 = fftFetch(t0 + ivec2(0, 1));
    vec3 d11 = fftFetch(t0 + ivec2(1, 1));
    vec3 bottom = d00 + (d10 - d00) * a.x;
    vec3 top = d01 + (d11 - d01) * a.x;
    return bottom + (top - bottom) * a.y;
}

// Foam inputs (ocean.frag): (h, J) bilinear from the same texels as modelDisplacement — J is the Jacobian
// determinant of the choppy map, computed with the displacement (fft_finalize.comp; Tessendorf 2001 §4.4).
// With the living whitecaps (uFftFoamMemory, FftDesc::foamMemory) h is the remembered crest height,
// max(h, decay * M) with M the memory map bilinear from the same texels (FftOcean::foamHeightAt, the CPU
// twin): foam stays where a crest passed and fades. The crests' glow then takes the displaced height.
#define MODEL_HAS_FOAM_INPUTS
#define MODEL_FOAM_REMEMBERS
uniform sampler2D uFftFoam;  // R32F memory map M_j (fft_foam.comp), one level
uniform bool uFftFoamMemory;
uniform float uFftFoamDecay; // e^(-(t - t_j) / FOAM_DECAY_TIME), formed in double
vec2 modelFoamInputs(vec2 rel) {
    vec2 p = fract(rel * uFftInvTile + uFftUvOffset) * float(uFftSize);
    vec2 p0 = floor(p);
    vec2 a = p - p0;
    ivec2 t0 = ivec2(p0);
    ivec2 t00 = t0 & (uFftSize - 1), t10 = (t0 + ivec2(1, 0)) & (uFftSize - 1);
    ivec2 t01 = (t0 + ivec2(0, 1)) & (uFftSize - 1), t11 = (t0 + ivec2(1, 1)) & (uFftSize - 1);
    vec2 d00 = texelFetch(uFftDisplacement, t00, 0).zw;
    vec2 d10 = texelFetch(uFftDisplacement, t10, 0).zw;
    vec2 d01 = texelFetch(uFftDisplacement, t01, 0).zw;
    vec2 d11 = texelFetch(uFftDisplacement, t11, 0).zw;
    vec2 bottom = d00 + (d10 - d00) * a.x;
    vec2 top = d01 + (d11 - d01) * a.x;
    vec2 hj = bottom + (top - bottom) * a.y;
    if (uFftFoamMemory) {
        float m00 = texelFetch(uFftFoam, t00, 0).r, m10 = texelFetch(uFftFoam, t10, 0).r;
        float m01 = texelFetch(uFftFoam, t01, 0).r, m11 = texelFetch(uFftFoam, t11, 0).r;
        float mb = m00 + (m10 - m00) * a.x;
        float mt = m01 + (m11 - m01) * a.x;
        hj.x = max(hj.x, uFftFoamDecay * (mb + (mt - mb) * a.y));
    }
    return hj;
}

vec3 modelLighting(vec2 rel) {
    vec2 uv = rel * uFftInvTile + uFftUvOffset + 0.5 / float(uFftSize);
    vec4 s = GRID_TEXTURE(uFftSlope, uv, uFftInvTile);
    return vec3(s.xy, max(s.z + s.w - dot(s.xy, s.xy), 0.0));
}
