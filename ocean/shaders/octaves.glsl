// octaves.glsl: the height-map octave surface model (GPU side of HeightOctaves) for the sea shaders.
// The exact (texelFetch) path mirrors HeightOctaves::sampleMap() on the CPU line by line
// (GPU Gems 2 §18.2.1: H(x,t) = sum A_i h_i(B_i x, t)); the filtered path uses hardware trilinear
// filtering with mipmaps for lighting normals, where aliasing matters more than exactness.

uniform sampler2DArray uMaps[MAX_OCTAVES];
uniform int uOctaveCount;     // octaves used for lighting normals
uniform int uDisplacedCount;  // leading octaves that displace vertices
uniform int uMapSize;
uniform int uFrames;
uniform vec2 uUvOffset[MAX_OCTAVES];   // fract(camera.xy * B_i), computed in double on the CPU
uniform float uInvTile[MAX_OCTAVES];   // B_i
uniform float uAmplitude[MAX_OCTAVES]; // A_i
uniform float uFramePos[MAX_OCTAVES];  // wrap(t, T_i) / T_i * frames, computed in double on the CPU

// Tile coordinate of a camera-relative horizontal position for octave i.
vec2 octaveUv(int i, vec2 rel) { return rel * uInvTile[i] + uUvOffset[i]; }

vec3 fetchBilinear(int i, ivec2 t0, vec2 a, int frame) {
    int m = uMapSize - 1; // power-of-two size: & wraps negatives too
    ivec2 t1 = t0 + ivec2(1);
    vec3 h00 = texelFetch(uMaps[i], ivec3(t0.x & m, t0.y & m, frame), 0).xyz;
    vec3 h10 = texelFetch(uMaps[i], ivec3(t1.x & m, t0.y & m, frame), 0).xyz;
    vec3 h01 = texelFetch(uMaps[i], ivec3(t0.x & m, t1.y & m, frame), 0).xyz;
    vec3 h11 = texelFetch(uMaps[i], ivec3(t1.x & m, t1.y & m, frame), 0).xyz;
    vec3 bottom = h00 + (h10 - h00) * a.x;
    vec3 top = h01 + (h11 - h01) * a.x;
    return bottom + (top - bottom) * a.y;
}

// (h, dh/du, dh/dv) of octave i: bilinear in space between texel centres, linear in time between slices.
vec3 sampleOctaveExact(int i, vec2 rel) {
    vec2 p = fract(octaveUv(i, rel)) * float(uMapSize) - 0.5;
    vec2 p0 = floor(p);
    vec2 a = p - p0;
    float fp = uFramePos[i];
    float f0 = floor(fp);
    float at = fp - f0;
    int frame0 = int(f0) % uFrames;
    int frame1 = (frame0 + 1) % uFrames;
    vec3 s0 = fetchBilinear(i, ivec2(p0), a, frame0);
    vec3 s1 = fetchBilinear(i, ivec2(p0), a, frame1);
    return s0 + (s1 - s0) * at;
}

// Displacement height of the surface (the displaced octaves), metres above mean sea level.
float displacedHeight(vec2 rel) {
    float h = 0.0;
    for (int i = 0; i < uDisplacedCount; ++i)
        h += uAmplitude[i] * sampleOctaveExact(i, rel).x;
    return h;
}

// World-space gradient (dH/dx, dH/dy) from every lighting octave, with hardware trilinear filtering, and
// in .z the slope variance the mip filtering averaged away: sum_i (A_i B_i)^2 (E[|s|^2] - |E[s]|^2)
// (LEAN mapping, Olano & Baker 2010), which the lighting adds to the specular roughness.
vec3 filteredGradient(vec2 rel) {
    vec3 g = vec3(0.0);
    for (int i = 0; i < uOctaveCount; ++i) {
        vec2 uv = octaveUv(i, rel);
        float f0 = floor(uFramePos[i]);
        float at = uFramePos[i] - f0;
        float l0 = mod(f0, float(uFrames));
        float l1 = mod(f0 + 1.0, float(uFrames));
        vec3 d = mix(texture(uMaps[i], vec3(uv, l0)).yzw, texture(uMaps[i], vec3(uv, l1)).yzw, at);
        float scale = uAmplitude[i] * uInvTile[i];
        g.xy += scale * d.xy;
        g.z += scale * scale * max(d.z - dot(d.xy, d.xy), 0.0);
    }
    return g;
}

// The surface-model contract (ocean/src/gpu/SurfaceGpu.h).
vec3 modelDisplacement(vec2 rel) { return vec3(0.0, 0.0, displacedHeight(rel)); }
vec3 modelLighting(vec2 rel) { return filteredGradient(rel); }
