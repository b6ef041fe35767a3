// gerstner.glsl: the Gerstner-sum surface model (GPU side of GerstnerWaves, ocean/src/GerstnerWaves.cpp) for
// the sea shaders. Same formulas, line by line, as the double-precision CPU twin:
//   displacement (GPU Gems 1 ch.1 eq. 9, Tessendorf 2001 §3.1):
//     d = ( sum_i Q_i a_i D_i cos(theta_i),  sum_i a_i sin(theta_i) )
//   theta_i = k_i D_i . rel + theta0_i, with theta0_i = wrap(k_i D_i . camera - w_i t + phi_i, 2 pi) computed
//   in double on the CPU (GerstnerWaves::phaseOffsets), so the float argument stays small;
//   a_i = A_i f(|rel|, R_i), the distance fade of GerstnerWaves.h (R_i = 40 L_i for the displacement,
//   400 L_i for the lighting), keeps k_i |rel| <= 2 pi 400 where float phases are accurate to ~1e-4 rad.
// CPU twins: modelDisplacement = GerstnerWaves::displacementSeenFrom, modelLighting = lightingSeenFrom.

#define GERSTNER_MAX_WAVES 64

uniform int uGerstnerCount;
uniform vec4 uGerstnerWave[GERSTNER_MAX_WAVES];  // (D.x, D.y, k, A): D (east, north), wavenumber, amplitude
uniform vec4 uGerstnerExtra[GERSTNER_MAX_WAVES]; // (Q, theta0, displacement fade end, lighting fade end)
uniform float uGerstnerMinJacobian;              // GerstnerWaves::MIN_LIGHTING_JACOBIAN

// f(r, R) = s^2 (3 - 2 s), s = clamp((R - r) / (R / 2), 0, 1) (GerstnerWaves::fade).
float gerstnerFade(float r, float fadeEnd) {
    float s = clamp((fadeEnd - r) / (0.5 * fadeEnd), 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
}

// (dx, dy, dz) of the camera-relative grid point rel: GPU Gems 1 ch.1 eq. 9 with faded amplitudes.
vec3 gerstnerDisplacement(vec2 rel) {
    float r = length(rel);
    vec3 d = vec3(0.0);
    for (int i = 0; i < uGerstnerCount; ++i) {
        vec4 w = uGerstnerWave[i];
        vec4 e = uGerstnerExtra[i];
        if (r >= e.z)
            continue; // faded out entirely
        float a = w.w * gerstnerFade(r, e.z);
        float theta = w.z * dot(w.xy, rel) + e.y;
        float c = cos(theta);
        float s = sin(theta);
        d.xy += (e.x * a * c) * w.xy;
        d.z += a * s;
    }
    return d;
}

// (dH/dx, dH/dy, unresolved slope variance). With J = I - sum_i Q_i a_i k_i sin(theta_i) D_i D_i^T (the
// columns of GPU Gems 1 ch.1 eq. 10-11) and g = sum_i a_i k_i cos(theta_i) D_i the gradient of dz over the
// grid, the Eulerian slope at the displaced point is J^-T g = adj(J) g / det J — the exact normal B x T,
// not Finch's eq. 12, which drops products of different waves. det J is floored at uGerstnerMinJacobian so
// a cusp (the clamped sum may touch J = 0) gives a steep but finite slope. The variance is what the
// lighting fade removed, sum_i ((1 - f_i) k_i A_i)^2 / 2, which the fragment shader adds to the specular
// roughness.
vec3 gerstnerLighting(vec2 rel) {
    float r = length(rel);
    float sxx = 0.0, sxy = 0.0, syy = 0.0, variance = 0.0;
    vec2 g = vec2(0.0);
    for (int i = 0; i < uGerstnerCount; ++i) {
        vec4 w = uGerstnerWave[i];
        vec4 e = uGerstnerExtra[i];
        float f = gerstnerFade(r, e.w);
        float lostSlope = (1.0 - f) * w.z * w.w;
        variance += 0.5 * lostSlope * lostSlope;
        if (f == 0.0)
            continue;
        float a = w.w * f;
        float theta = w.z * dot(w.xy, rel) + e.y;
        float qaks = e.x * a * w.z * sin(theta);
        sxx += qaks * w.x * w.x;
        sxy += qaks * w.x * w.y;
        syy += qaks * w.y * w.y;
        g += (a * w.z * cos(theta)) * w.xy;
    }
    float det = max((1.0 - sxx) * (1.0 - syy) - sxy * sxy, uGerstnerMinJacobian);
    return vec3(((1.0 - syy) * g.x + sxy * g.y) / det, (sxy * g.x + (1.0 - sxx) * g.y) / det, variance);
}

// Foam inputs (ocean.frag): (H, det J) with the displacement fade — Tessendorf 2001 §4.4: the surface folds
// where det J -> 0, so foam where J falls under the threshold. CPU twin: GerstnerWaves::foamInputsSeenFrom.
// With the living whitecaps (uGerstnerFoamMemory, GerstnerDesc::foamMemory) H is the remembered crest
// height max(h(t), decay * max_k w^k max(h(t_j - k s), 0)) over the FOAM_MEMORY_WINDOW lattice times
// (GerstnerWaves::foamHeightAt): each wave's phase at t_j (uGerstnerMemory.x, wrapped in double) is rotated
// back one step at a time by w_i s (cos, sin in .yz), so the window costs one sin/cos per wave and
// multiply-adds. The crests' glow then takes the displaced height (MODEL_FOAM_REMEMBERS).
#define MODEL_HAS_FOAM_INPUTS
#define MODEL_FOAM_REMEMBERS
uniform vec4 uGerstnerMemory[GERSTNER_MAX_WAVES]; // (theta0 at t_j, cos(w_i s), sin(w_i s), 0)
uniform bool uGerstnerFoamMemory;
uniform float uGerstnerFoamDecay; // e^(-(t - t_j) / FOAM_DECAY_TIME), formed in double
vec2 modelFoamInputs(vec2 rel) {
    float r = length(rel);
    float h = 0.0, sxx = 0.0, sxy = 0.0, syy = 0.0;
    float past[FOAM_MEMORY_WINDOW];
    for (int k = 0; k < FOAM_MEMORY_WINDOW; ++k)
        past[k] = 0.0;
    for (int i = 0; i < uGerstnerCount; ++i) {
        vec4 w = uGerstnerWave[i];
        vec4 e = uGerstnerExtra[i];
        if (r >= e.z)
            continue;
        float a = w.w * gerstnerFade(r, e.z);
        float s = sin(w.z * dot(w.xy, rel) + e.y);
        h += a * s;
        float qaks = e.x * a * w.z * s;
        sxx += qaks * w.x * w.x;
        sxy += qaks * w.x * w.y;
        syy += qaks * w.y * w.y;
        if (uGerstnerFoamMemory) {
            vec4 m = uGerstnerMemory[i];
            float theta = w.z * dot(w.xy, rel) + m.x;
            float sn = sin(theta), cs = cos(theta);
            for (int k = 0; k < FOAM_MEMORY_WINDOW; ++k) {
                past[k] += a * sn;
                float next = sn * m.y + cs * m.z; // sin(theta + w s): one step back in time
                cs = cs * m.y - sn * m.z;
                sn = next;
            }
        }
    }
    if (uGerstnerFoamMemory) {
        const float stepDecay = exp(-FOAM_MEMORY_STEP / FOAM_DECAY_TIME);
        float weight = 1.0, memory = 0.0;
        for (int k = 0; k < FOAM_MEMORY_WINDOW; ++k) {
            memory = max(memory, weight * max(past[k], 0.0));
            weight *= stepDecay;
        }
        h = max(h, uGerstnerFoamDecay * memory);
    }
    return vec2(h, (1.0 - sxx) * (1.0 - syy) - sxy * sxy);
}

// The surface-model contract (ocean/src/gpu/SurfaceGpu.h).
vec3 modelDisplacement(vec2 rel) { return gerstnerDisplacement(rel); }
vec3 modelLighting(vec2 rel) { return gerstnerLighting(rel); }
