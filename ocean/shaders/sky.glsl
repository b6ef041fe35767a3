// sky.glsl: the procedural scene-linear HDR sky used for the background and for sea reflections.
// A zenith-to-horizon gradient (Rayleigh-like blue overhead, brighter haze at the horizon), a darker
// hemisphere below the horizon, a sun glow and a sun disk. Radiance units are arbitrary scene-linear;
// 0.18 ~ mid grey after the tonemap.

uniform vec3 uSunDir;       // towards the sun, world ENU, normalised
uniform float uSkyIntensity;
uniform float uSunIntensity;

vec3 skyRadiance(vec3 dir) {
    const vec3 zenith = vec3(0.060, 0.150, 0.420);
    const vec3 horizon = vec3(0.480, 0.580, 0.720);
    const vec3 below = vec3(0.090, 0.120, 0.160);
    float z = dir.z;
    vec3 sky;
    if (z >= 0.0) {
        float t = pow(1.0 - z, 5.0);
        sky = mix(zenith, horizon, t);
    } else {
        sky = mix(horizon, below, clamp(-z * 8.0, 0.0, 1.0));
    }
    float c = max(dot(dir, uSunDir), 0.0);
    vec3 sunColor = vec3(1.0, 0.92, 0.80);
    sky += sunColor * (0.35 * pow(c, 32.0) + 0.12 * pow(c, 4.0));
    // Sun disk (~0.5 degree): cos(0.27 deg) = 0.999989
    sky += sunColor * uSunIntensity * 25.0 * smoothstep(0.99997, 0.99999, c);
    return sky * uSkyIntensity;
}
