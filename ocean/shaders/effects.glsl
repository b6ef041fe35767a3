// effects.glsl: the GLSL twin of ocean/src/Effects.cpp — the field of each explosion and ship trail (GPU
// Gems 2 §18.3 local perturbations), band-limited at a wave number kMax. effects_field.comp sums them into
// the effects field's texels; the grids read the field (effects_sample.glsl). Compiled in only when the
// scene has effects (EFFECTS_EXPLOSIONS / EFFECTS_WAKES name the kinds present); constants come from the C++
// side as #defines (EFFECT_HEIGHT_LIMIT, MAX_WAKE_POINTS, EFFECT_K_MAX). Coordinates are camera-relative
// metres.

// The buffers' structs are declared in C++ (ocean/src/gpu/GpuInterface.h, with what each member means); these
// declare the same members in the same order, and test_gpu_interface_gl checks the driver's offsets against
// the C++ ones. The binding slots are #defines of the same header's enum.
struct ExplosionGpu { // explosionState() of each explosion, camera-relative
    vec2 centre;
    float gridRadius;
    float amplitude;
    float wavenumber;
    float phase;
    float coreRadius;
    float front;
    float frontWidth;
    float crownFoam;
    float crownRadius;
    float peakAmplitude;
    float slick;
    float slickRadius;
};
// Its points at [wake * MAX_WAKE_POINTS * 2 ...]: (offset from ship x, y; sigma; age), (amplitude, k0, 0, 0).
struct WakeGpu {
    vec2 ship;
    float gridRadius;
    float points;
    float shipLength;
    float beam;
    float waveLife;
    float foamLife;
    vec2 boxMin; // the box outside which the wake is 0, relative to the ship
    vec2 boxMax;
};
layout(std430, binding = EFFECT_EXPLOSIONS_BINDING) readonly buffer EffectExplosions { ExplosionGpu uExplosions[]; };
layout(std430, binding = EFFECT_WAKES_BINDING) readonly buffer EffectWakes { WakeGpu uWakes[]; };
layout(std430, binding = EFFECT_WAKE_POINTS_BINDING) readonly buffer EffectWakePoints { vec4 uWakePoints[]; };

const float EFFECT_TWO_PI = 6.28318530717958647;

// effectBandFade() in Effects.cpp: 1 - smoothstep(kMax / 2, kMax, k).
float effectBandFade(float k, float kMax) {
    return 1.0 - smoothstep(0.5 * kMax, kMax, k);
}

float effectSmoothstepDerivative(float e0, float e1, float x) {
    float t = (x - e0) / (e1 - e0);
    if (t <= 0.0 || t >= 1.0)
        return 0.0;
    return 6.0 * t * (1.0 - t) / (e1 - e0);
}

// (h, dh/dx, dh/dy) of explosion i at offset q from its centre: explosionWave() in Effects.cpp.
vec3 explosionWave(int i, vec2 q, float kMax) {
    ExplosionGpu e = uExplosions[i];
    float R = e.gridRadius, k = e.wavenumber, phase = e.phase, r0 = e.coreRadius, front = e.front;
    float width = e.frontWidth;
    float amplitude = e.amplitude * effectBandFade(k, kMax);
    if (R <= 0.0 || amplitude == 0.0)
        return vec3(0.0);
    float s = sqrt(dot(q, q) + r0 * r0);
    float rim = sqrt(R * R + r0 * r0);
    if (s >= rim)
        return vec3(0.0);
    float spread = r0 / s;
    float arg = k * (s - r0) - phase;
    float c = cos(arg);
    float w = 1.0 - smoothstep(front - width, front + width, s);
    float taper = 1.0 - smoothstep(0.8 * rim, rim, s);
    float h = amplitude * spread * w * c * taper;
    float dSpread = -r0 / (s * s);
    float dc = -k * sin(arg);
    float dw = -effectSmoothstepDerivative(front - width, front + width, s);
    float dTaper = -effectSmoothstepDerivative(0.8 * rim, rim, s);
    float dh = amplitude * (dSpread * w * c * taper + spread * dw * c * taper + spread * w * dc * taper +
                            spread * w * c * dTaper);
    return vec3(h, dh * q / s);
}

// filter2: the field level's foam prefilter (Effects.cpp explosionFoam()).
float explosionFoam(int i, vec2 q, float h, float filter2) {
    ExplosionGpu e = uExplosions[i];
    if (e.gridRadius <= 0.0 || dot(q, q) >= e.gridRadius * e.gridRadius)
        return 0.0;
    float r2 = e.crownRadius * e.crownRadius + filter2;
    float crown = e.crownFoam * (e.crownRadius * e.crownRadius / r2) * exp(-dot(q, q) / r2);
    float sr2 = e.slickRadius * e.slickRadius + filter2;
    float slick = e.slick * (e.slickRadius * e.slickRadius / sr2) * exp(-dot(q, q) / sr2);
    float h0 = 0.35 * e.peakAmplitude, hMax = 0.8 * e.peakAmplitude; // GPU Gems 2 §18.3: (H - H0) / (Hmax - H0)
    float crest = clamp((h - h0) / (hMax - h0), 0.0, 1.0);
    return clamp(max(max(crown, slick), crest), 0.0, 1.0);
}

// Path coordinates of q (relative to the ship) for wake i: wakeCoords() in Effects.cpp.
struct WakeCoords {
    float behind, lateral, age, amplitude, k0;
    vec2 direction;
};

// Only segments first..last (clamped to the path) are walked: effects_field.comp's tile lists give each tile
// the segments that can be nearest to one of its texels (EffectsGpu.cpp wakeEntry), so the walk finds what
// the whole walk finds.
WakeCoords wakeCoords(int i, vec2 q, int first, int last) {
    WakeCoords best = WakeCoords(0.0, 0.0, 0.0, 0.0, 0.0, vec2(1.0, 0.0));
    float bestDist2 = 3.4e38;
    int n = int(uWakes[i].points);
    int base = i * MAX_WAKE_POINTS * 2;
    for (int j = first; j <= last && j + 1 < n; ++j) {
        vec4 pa = uWakePoints[base + 2 * j], pb = uWakePoints[base + 2 * j + 2];
        vec2 ab = pb.xy - pa.xy;
        float len2 = dot(ab, ab);
        float u = len2 > 0.0 ? dot(q - pa.xy, ab) / len2 : 0.0;
        float uc = j == 0 ? min(u, 1.0) : clamp(u, 0.0, 1.0);
        vec2 c = pa.xy + uc * ab;
        float d2 = dot(q - c, q - c);
        if (d2 < bestDist2 * (1.0 - 1e-4)) { // Effects.cpp wakeCoords(): the newer segment wins ties
            bestDist2 = d2;
            float len = sqrt(len2);
            vec2 dir = len > 0.0 ? -ab / len : vec2(1.0, 0.0);
            float w = clamp(uc, 0.0, 1.0);
            vec4 qa = uWakePoints[base + 2 * j + 1], qb = uWakePoints[base + 2 * j + 3];
            vec2 r = q - c;
            best = WakeCoords(pa.z + uc * len, dir.x * r.y - dir.y * r.x, mix(pa.w, pb.w, w), mix(qa.x, qb.x, w),
                              mix(qa.y, qb.y, w), dir);
        }
    }
    return best;
}

// (h, dh/dbehind, dh/dlateral) of the Kelvin pattern: kelvinWave() in Effects.cpp, the derivatives carried
// forward through each factor (x = behind, y = |lateral|); the phase's gradient at a stationary root is its
// wave vector k0 sqrt(1 + T^2) (1, -T).
vec3 kelvinWave(int i, WakeCoords c, float behind, float lateral, float kMax) {
    float x = behind;
    int n = int(uWakes[i].points);
    if (!(x > 0.0) || c.amplitude <= 0.0 || n < 2)
        return vec3(0.0);
    float y = abs(lateral);
    float ta = y / x;
    vec2 dta = vec2(-ta / x, 1.0 / x);
    float u = 8.0 * ta * ta;
    if (u >= 1.0)
        return vec3(0.0);
    vec2 du = 16.0 * ta * dta;
    float sd = sqrt(1.0 - u);
    float t2raw = (1.0 + sd) / (4.0 * max(ta, 1e-6));
    float roots[2] = float[2](2.0 * ta / (1.0 + sd), min(t2raw, 1000.0));
    float guard = max(sd, 1e-9);
    float dRoots[2] = float[2]((2.0 * roots[0] * roots[0] + 1.0) / guard,
                               t2raw < 1000.0 && ta > 1e-6 ? -(2.0 * roots[1] * roots[1] + 1.0) / guard : 0.0);
    float weights[2] = float[2](1.0, 0.6);
    const float decay = EFFECT_TWO_PI * KELVIN_DECAY_WAVELENGTHS;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < 2; ++j) {
        float tt = roots[j];
        vec2 dt = dRoots[j] * dta;
        float k = c.k0 * (1.0 + tt * tt);
        vec2 dk = 2.0 * c.k0 * tt * dt;
        float e = exp(-x * k / decay);
        float fade = effectBandFade(k, kMax) * e;
        if (fade <= 0.0)
            continue;
        vec2 dFade = -effectSmoothstepDerivative(0.5 * kMax, kMax, k) * dk * e - fade * (vec2(k, 0.0) + x * dk) / decay;
        float kk = c.k0 * sqrt(1.0 + tt * tt);
        float phase = kk * (x - y * tt); // kelvinPhase() in Effects.cpp
        float cp = cos(phase), sp = sin(phase);
        sum += weights[j] * vec3(fade * cp, dFade * cp - fade * sp * vec2(kk, -kk * tt));
    }
    float lambda0 = EFFECT_TWO_PI / c.k0;
    float start = smoothstep(0.0, 0.5 * lambda0, x);
    float dStart = effectSmoothstepDerivative(0.0, 0.5 * lambda0, x);
    float cusp = 1.0 - smoothstep(0.8, 1.0, u);
    vec2 dCusp = -effectSmoothstepDerivative(0.8, 1.0, u) * du;
    float sigmaMax = uWakePoints[i * MAX_WAKE_POINTS * 2 + 2 * (n - 1)].z;
    float end = 1.0 - smoothstep(0.85 * sigmaMax, sigmaMax, x);
    float dEnd = -effectSmoothstepDerivative(0.85 * sigmaMax, sigmaMax, x);
    WakeGpu wake = uWakes[i];
    float a = c.amplitude * exp(-c.age / wake.waveLife) / sqrt(1.0 + x / wake.shipLength);
    float dA = -a / (2.0 * (wake.shipLength + x));
    float env = a * start * cusp * end;
    vec2 dEnv = vec2((dA * start * end + a * dStart * end + a * start * dEnd) * cusp, 0.0) + a * start * end * dCusp;
    vec2 dH = dEnv * sum.x + env * sum.yz;
    return vec3(env * sum.x, dH.x, sign(lateral) * dH.y);
}

// Effects.cpp foamBand(): a band exp(-(d / w)^2) across a line, prefiltered by filter2, cut at 3 widths.
float foamBand(float d, float w, float filter2) {
    float width2 = w * w + filter2;
    return d * d < 9.0 * width2 ? sqrt(w * w / width2) * exp(-(d * d) / width2) : 0.0;
}

// (h, dh/dx, dh/dy, foam) of wake i at q (relative to the ship), its path walked over segments first..last.
vec4 wakeWave(int i, vec2 q, float kMax, int first, int last, float filter2) {
    float R = uWakes[i].gridRadius;
    vec2 boxMin = uWakes[i].boxMin, boxMax = uWakes[i].boxMax;
    // insideWakeBox() in Effects.cpp
    if (R <= 0.0 || dot(q, q) >= R * R || q.x <= boxMin.x || q.y <= boxMin.y || q.x >= boxMax.x || q.y >= boxMax.y)
        return vec4(0.0);
    WakeCoords c = wakeCoords(i, q, first, last);
    vec3 kelvin = kelvinWave(i, c, c.behind, c.lateral, kMax);
    float h = kelvin.x, dx = kelvin.y, dy = kelvin.z;
    vec2 left = vec2(-c.direction.y, c.direction.x);
    vec2 g = -dx * c.direction + dy * left;
    // wakeFoam(): the propeller wash, the turbulent strip, the stern foam and the bow wave.
    WakeGpu wake = uWakes[i];
    int n = int(wake.points);
    float foam = 0.0;
    if (n >= 2 && c.amplitude > 0.0) {
        float L = wake.shipLength, B = wake.beam;
        float strength = min(1.0, c.amplitude / 0.2) * exp(-c.age / wake.foamLife);
        float sigmaMax = uWakePoints[i * MAX_WAKE_POINTS * 2 + 2 * (n - 1)].z;
        float end = 1.0 - smoothstep(0.85 * sigmaMax, sigmaMax, c.behind);
        float xs = c.behind - 0.5 * L;
        float aft = smoothstep(-0.05 * L, 0.05 * L, xs);
        float past = max(xs, 0.0);
        float wash = foamBand(c.lateral, WAKE_WASH_WIDTH * B * sqrt(1.0 + past / (2.0 * L)), filter2);
        float strip = WAKE_STRIP_SHARE * foamBand(c.lateral, B * (1.0 + past / 400.0), filter2);
        float stern = exp(-past / (WAKE_STERN_LENGTH * L)) * foamBand(c.lateral, WAKE_STERN_WIDTH * B, filter2);
        float xb = c.behind + 0.5 * L;
        float froude = 1.0 / sqrt(max(c.k0, 1e-9) * L);
        float bowPast = max(xb, 0.0);
        float bow = smoothstep(WAKE_BOW_FROUDE_START, WAKE_BOW_FROUDE_FULL, froude) *
                    smoothstep(-0.02 * L, 0.02 * L, xb) * exp(-bowPast / (WAKE_BOW_LENGTH * L)) *
                    (1.0 - smoothstep(0.6 * WAKE_BOW_END * L, WAKE_BOW_END * L, bowPast)) *
                    foamBand(abs(c.lateral) - (0.5 * B + sqrt(KELVIN_TAN2) * bowPast),
                             WAKE_BOW_WIDTH * B + WAKE_BOW_WIDTH_GROWTH * bowPast, filter2);
        float white = max(aft * max(max(wash, strip), stern), bow);
        foam = clamp(strength * white * end, 0.0, 1.0);
    }
    return vec4(h, g, foam);
}
