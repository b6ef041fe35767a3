// spot.glsl: spot lights (Lighting.h SpotLight; OceanScene::spots) -- their light on the sea and their beams
// in the fog. Compiled in only for a frame that has any (SPOT_LIGHTS). After sky.glsl (lightSpecular,
// waterBodyLit, the fog), before sky.frag and ocean.frag.
#ifdef SPOT_LIGHTS
uniform int uSpotCount;
uniform vec3 uSpotPosition[MAX_SPOT_LIGHTS]; // camera-relative, metres
uniform vec4 uSpotAxis[MAX_SPOT_LIGHTS];     // (unit axis, frustum half-angle theta_f in radians)
uniform vec4 uSpotLight[MAX_SPOT_LIGHTS];    // (colour x intensity, range in metres)
// The default LightingDesc's sun on a flat sea: (its diffuse irradiance SUN_DIFFUSE_SCALE sunIntensity
// sin(elevation), sin(elevation)). Daylight is that plus the default sky's irradiance (waterLightReference).
uniform vec2 uDaylightSun;
uniform int uSpotScatterSamples; // LightingDesc::spotScatterSamples: quadrature points per beam, 0 = no beams
uniform float uSpotFogPhaseG;    // SPOT_FOG_PHASE_G: the fog's Henyey-Greenstein asymmetry
// The largest radiance a frame lit by lamps keeps: half float's largest finite value. A pre-exposed lamp's
// glitter or glare near it can exceed it, and an RGBA16F target would hold Inf (NaN after a view transform).
const float SPOT_RADIANCE_MAX = 65504.0;

// spotFalloff and spotIrradiance in Lighting.h, expression for expression: the seed's saturate(|theta_f /
// theta| - 1), finite on the axis. l: the unit direction from p toward the spot.
float spotFalloff(float theta, float frustum) {
    return clamp(frustum / max(theta, 0.5 * frustum) - 1.0, 0.0, 1.0);
}
// Karis' range window (1 - (d / range)^4)^2.
float spotWindow(float d, float range) {
    float q = d / range, q2 = q * q;
    float w = max(1.0 - q2 * q2, 0.0);
    return w * w;
}
vec3 spotIrradiance(int i, vec3 p, out vec3 l) {
    vec3 toPoint = p - uSpotPosition[i];
    float d = length(toPoint);
    l = d > 0.0 ? -toPoint / d : vec3(0.0, 0.0, 1.0);
    float range = uSpotLight[i].w;
    if (!(d < range))
        return vec3(0.0);
    float c = d > 0.0 ? dot(uSpotAxis[i].xyz, -l) : 1.0;
    float theta = acos(clamp(c, -1.0, 1.0));
    float r = max(d, SPOT_MIN_DISTANCE);
    return uSpotLight[i].rgb * (spotFalloff(theta, uSpotAxis[i].w) * spotWindow(d, range) / (r * r));
}
// The spots' light at surface point p with normal n: their glitter (the sun's lobe, lightSpecular) and the
// diffuse irradiance they put on the surface, SUN_DIFFUSE_SCALE sum E max(n.l, 0), which lights the water
// body and the foam. A spot's intensity is in the sun's units, which are calibrated for the glitter: its
// diffuse light is scaled as the sun's is.
void spotLighting(vec3 p, vec3 n, vec3 v, float m2, out vec3 specular, out vec3 irradiance) {
    specular = vec3(0.0);
    irradiance = vec3(0.0);
    for (int i = 0; i < uSpotCount; ++i) {
        vec3 l;
        vec3 e = spotIrradiance(i, p, l);
        if (e == vec3(0.0))
            continue;
        specular += lightSpecular(n, v, l, m2, e);
        irradiance += e * (SUN_DIFFUSE_SCALE * max(dot(n, l), 0.0));
    }
}
// The water body under the spots' diffuse irradiance: relative to daylight's (the default sky's plus the
// default sun's), so a lamp that puts daylight's irradiance on the sea lights the water body as daylight does.
vec3 spotWaterBody(vec3 v, vec3 n, vec3 irradiance) {
    float daylight = waterLightReference() + uDaylightSun.x;
    return waterBodyLit(v, n, dot(irradiance, vec3(0.2126, 0.7152, 0.0722)) / daylight, uDaylightSun.y);
}

// ---- beams: the spots' light scattered toward the eye by the fog (Lighting.h spotInScatter) ----------------

// Narrows [t0, t1] to the part of the ray w + t dir (w: the ray's origin relative to the spot, dir unit) that
// lies in the spot's cone (axis unit, cos of the half-angle cosF, half-angle <= 90 degrees: a convex set) and
// within its range; false when none is. Lighting.h spotConeInterval, step for step: the cone's boundary
// crossings are the roots of (p.a)^2 - cosF^2 |p|^2 and of p.a (p = w + t dir), so between consecutive
// crossings the ray is wholly in or out, and one point each decides. Named variables, not an array: Mesa's
// llvmpipe 15 lost the roots of an array filled with cut[n++] and sorted in a loop.
bool spotConeInterval(vec3 w, vec3 dir, vec3 axis, float cosF, float range, inout float t0, inout float t1) {
    // From the ray's point nearest the apex (t = shift): there the quadric's terms are of the size of the
    // ray's distance from the apex, not of the camera's (in float, a beam crossed near its lamp 160 m away
    // lost its two crossings to cancellation).
    float shift = -dot(w, dir);
    w += shift * dir;
    float disc = range * range - dot(w, w);
    if (disc <= 0.0)
        return false;
    float s = sqrt(disc);
    t0 = max(t0 - shift, -s);
    t1 = min(t1 - shift, s);
    if (!(t0 < t1))
        return false;
    float da = dot(dir, axis), wa = dot(w, axis), k2 = cosF * cosF;
    float A = da * da - k2, B = 2.0 * da * wa, C = wa * wa - k2 * dot(w, w);
    // The crossings (t1 where there is none), clamped into [t0, t1] and sorted by three compare-swaps: the
    // ray between consecutive ones is wholly in or out.
    float r1 = t1, r2 = t1, r3 = t1;
    float qd = B * B - 4.0 * A * C;
    if (abs(A) > 1e-6 && qd >= 0.0) { // Numerical Recipes' form: no cancellation
        float q = -0.5 * (B + (B < 0.0 ? -sqrt(qd) : sqrt(qd)));
        if (q != 0.0) {
            r1 = q / A;
            r2 = C / q;
        }
    } else if (abs(A) <= 1e-6 && B != 0.0) {
        r1 = -C / B;
    }
    if (da != 0.0)
        r3 = -wa / da;
    r1 = clamp(r1, t0, t1);
    r2 = clamp(r2, t0, t1);
    r3 = clamp(r3, t0, t1);
    vec2 o = vec2(min(r1, r2), max(r1, r2));
    r1 = o.x;
    r2 = o.y;
    o = vec2(min(r2, r3), max(r2, r3));
    r2 = o.x;
    r3 = o.y;
    o = vec2(min(r1, r2), max(r1, r2));
    r1 = o.x;
    r2 = o.y;
    float lo = t1, hi = t0;
    vec4 from = vec4(t0, r1, r2, r3), to = vec4(r1, r2, r3, t1);
    for (int j = 0; j < 4; ++j) {
        if (!(to[j] > from[j]))
            continue;
        vec3 p = w + (0.5 * (from[j] + to[j])) * dir;
        float pa = dot(p, axis);
        if (pa >= 0.0 && pa * pa >= k2 * dot(p, p)) {
            lo = min(lo, from[j]);
            hi = max(hi, to[j]);
        }
    }
    t0 = lo + shift;
    t1 = hi + shift;
    return lo < hi;
}

// The fog's extinction (= its scattering: fog droplets absorb little) at a camera-relative point: rho0
// e^(-z/H) and De Sylva's noise factor (read at the finest level: a beam lies within its range of the lamp).
float spotFogDensity(vec3 rel) {
    float z = uCameraHeight + rel.z;
    float rho = uFogHeightFalloff > 0.0 ? uFogDensity * exp(-z / uFogHeightFalloff) : uFogDensity;
    const vec3 scale1 = vec3(1.0 / FOG_NOISE_TILE, 1.0 / FOG_NOISE_TILE, 1.0 / FOG_NOISE_TILE_VERTICAL);
    float n = textureLod(uFogNoiseMap, rel * scale1 + uFogNoiseOffset, 0.0).r;
    return rho * (1.0 + uFogNoise * (2.0 * n - 1.0));
}

// The spots' light scattered once toward the eye along the view ray dir (unit, from the camera) out to tMax:
//   L = sum_i SUN_DIFFUSE_SCALE I_i c_i int sigma(x) p(l . -dir) falloff(theta) window(d) T_eye T_lamp / d^2 dt
// over the part of the ray in the cone (spotConeInterval), p Henyey-Greenstein (1941), T the fog's
// transmittance to the eye and from the lamp. The 1/d^2 peak is integrated exactly by equiangular sampling
// (Kulla & Fajardo 2012, "Importance Sampling Techniques for Path Tracing in Participating Media", sec. 4.1:
// t = delta + D tan(a), dt = (D^2 + (t - delta)^2) / D da, D the lamp's distance from the ray's line), the
// rest by the midpoint rule in a over uSpotScatterSamples points. The diffuse scale is the foam's: the
// fog is lit as a diffuse medium is.
vec3 spotScatter(vec3 dir, float tMax) {
    vec3 total = vec3(0.0);
    if (uSpotScatterSamples <= 0 || uFogDensity <= 0.0)
        return total;
    float g = uSpotFogPhaseG;
    for (int i = 0; i < uSpotCount; ++i) {
        vec3 c = uSpotPosition[i];
        float t0 = 0.0, t1 = tMax;
        if (!spotConeInterval(-c, dir, uSpotAxis[i].xyz, cos(uSpotAxis[i].w), uSpotLight[i].w, t0, t1))
            continue;
        float delta = dot(c, dir);
        float D = max(length(c - delta * dir), SPOT_MIN_DISTANCE);
        float a0 = atan((t0 - delta) / D), a1 = atan((t1 - delta) / D);
        float zLamp = uCameraHeight + c.z;
        float sum = 0.0;
        for (int k = 0; k < uSpotScatterSamples; ++k) {
            float a = mix(a0, a1, (float(k) + 0.5) / float(uSpotScatterSamples));
            float t = delta + D * tan(a);
            vec3 x = t * dir;
            vec3 toX = x - c;
            float d = length(toX);
            vec3 l = d > 0.0 ? toX / d : uSpotAxis[i].xyz; // the light's direction of travel
            float theta = acos(clamp(dot(uSpotAxis[i].xyz, l), -1.0, 1.0));
            float r = max(d, SPOT_MIN_DISTANCE);
            float jacobian = (D * D + (t - delta) * (t - delta)) / (D * r * r);
            float hg = 1.0 + g * g - 2.0 * g * dot(l, -dir);
            float phase = (1.0 - g * g) / (4.0 * PI * hg * sqrt(hg));
            float z = uCameraHeight + x.z;
            float tau = fogOpticalDepth(uCameraHeight, z, t) + fogOpticalDepth(zLamp, z, d);
            sum += spotFogDensity(x) * phase * spotFalloff(theta, uSpotAxis[i].w) *
                   spotWindow(d, uSpotLight[i].w) * exp(-tau) * jacobian;
        }
        total += uSpotLight[i].rgb * (SUN_DIFFUSE_SCALE * sum * (a1 - a0) / float(uSpotScatterSamples));
    }
    return total;
}
#endif
