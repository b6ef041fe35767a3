// sky.glsl: the scene-linear HDR sky and the shading both the sky pass and the sea use, so they agree at the
// horizon: the procedural sky or an HDR lat-long environment map, Perlin fog with height falloff, the water
// body colour and the sun highlight. Included by the sky program (sky.frag) and the sea program (before
// ocean.frag). Radiance units are arbitrary scene-linear; 0.18 ~ mid grey after the tonemap. The C++ twins
// of the fog and foam formulas are in ocean/include/ocean/Lighting.h (fogOpticalDepth, foamAlpha).

uniform vec3 uSunDir; // towards the sun, world ENU, normalised
uniform vec3 uWaterColor; // LightingDesc::waterColor: the water body straight down under the default sky
uniform float uSkyIntensity;
uniform float uSunIntensity;
// The sunlight's colour at the sea: reddened through the air for the physical sky (ClearSky::sunlight),
// SUN_COLOR (OceanConstants.h) above the haze for the gradient sky and environment maps.
uniform vec3 uSunColor;
// The environment map is the physical clear sky (ClearSky::skyMap): it holds no sun, so the sky pass draws
// the sun's disc on it, and it holds every ray that misses the sea (below the horizontal too).
uniform bool uPhysicalSky;
// ... and it holds the fog's haze layer (scattered by the sunlight and the sky, the Mie phase function's
// bright aureole included), and so does uSunColor: neither is fogged again. Not for a uniform fog or one
// of a given colour (LightingGpu.cpp skyHoldsFog), which are mixed over the sky as for the other skies.
uniform bool uSkyHoldsFog;
uniform float uWaterLightReference; // see waterBody()

// Environment map (LightingDesc::environment): lat-long, rows top-down, u = heading clockwise from north
// with north at u = 0.5 (south on the seam u = 0), v = elevation from +90 deg (top) to -90 deg.
uniform bool uHasEnvironment;
uniform bool uEnvironmentBackground; // the sky pass shows the map (else the procedural sky)
uniform sampler2D uEnvironment;
uniform float uEnvironmentIntensity;
uniform float uEnvironmentMaxLod;    // log2(width): the 1-texel-wide level
uniform vec3 uEnvironmentIrradiance; // environmentIrradiance(): sky irradiance without the sun (CPU)
// environmentHorizonBand(): the fog colour per heading, and its mean.
uniform vec3 uEnvironmentHorizon[ENVIRONMENT_HORIZON_BINS];
uniform vec3 uEnvironmentHorizonMean;

// Camera altitude (metres above mean sea level) and Earth curvature 1 / (2 R) (0 = flat). The sea's vertex
// stage declares the same uniforms, so in the sea program they are one.
uniform float uCameraHeight;
uniform float uCurvature;

// Fog (the Intel projected-grid ocean's fog, C. De Sylva, with height falloff): rho(z) = uFogDensity e^(-z / uFogHeightFalloff), modulated by a
// tileable 3D noise n in [1 - uFogNoise, 1 + uFogNoise]; transmittance f = e^(-tau n).
uniform float uFogDensity;
uniform float uFogHeightFalloff; // H, metres; 0 = uniform fog on the sea, clear sky
uniform float uFogNoise;
uniform sampler3D uFogNoiseMap;
uniform vec3 uFogNoiseOffset; // fract((camera - wind t) / tile), wrapped in double on the CPU
uniform vec3 uFogNoiseOffset2; // the same for FOG_NOISE_TILE_2 / FOG_NOISE_TILE_VERTICAL_2
uniform bool uHasFogColor;
uniform vec3 uFogColor;

const float PI = 3.14159265;
const vec3 SKY_ZENITH = vec3(0.036, 0.115, 0.400);
const vec3 SKY_HORIZON = vec3(0.480, 0.580, 0.720);
const vec3 SKY_BELOW = vec3(0.090, 0.120, 0.160);

// ---- sky radiance --------------------------------------------------------------------------------------

// The sun's disc (~0.5 degree: cos(0.27 deg) = 0.999989), in the sunlight's colour.
vec3 sunDiscRadiance(vec3 dir) {
    return uSunColor * uSunIntensity * 25.0 * smoothstep(0.99997, 0.99999, dot(dir, uSunDir));
}

// A zenith-to-horizon gradient (Rayleigh-like blue overhead, brighter toward the horizon), a darker
// hemisphere below the horizon, a sun glow and (optionally) the sun disk. This is the sky above the haze:
// the fog (LightingDesc::fogDensity, default a light marine haze) adds the milky band near the horizon, so
// the gradient is tighter and the zenith deeper than a sea-level sky, and from 15 km the sky is bluer.
vec3 proceduralSky(vec3 dir, bool sunDisk) {
    float z = dir.z;
    vec3 sky;
    if (z >= 0.0) {
        // (1 - z)^7 by multiplies: pow() is exp2(y log2 x), two transcendentals a call, and this sky is
        // evaluated up to three times a sea pixel (llvmpipe 640x360, low: shading pass -4 ms with the glow's
        // powers below). max(): a normalised direction straight up can have z a rounding above 1.
        float t1 = max(1.0 - z, 0.0);
        float t2 = t1 * t1;
        float t = t1 * t2 * t2 * t2;
        sky = mix(SKY_ZENITH, SKY_HORIZON, t);
    } else {
        sky = mix(SKY_HORIZON, SKY_BELOW, clamp(-z * 8.0, 0.0, 1.0));
    }
    float c = max(dot(dir, uSunDir), 0.0);
    float c4 = (c * c) * (c * c);
    float c16 = (c4 * c4) * (c4 * c4);
    sky += uSunColor * (0.35 * c16 * c16 + 0.12 * c4); // c^32 and c^4
    if (sunDisk)
        sky += sunDiscRadiance(dir);
    return sky * uSkyIntensity;
}

// Lat-long coordinate of a direction (the C++ twin: environmentUv in Lighting.h).
vec2 environmentUv(vec3 d) {
    float heading = abs(d.x) + abs(d.y) < 1e-12 ? 0.0 : atan(d.x, d.y);
    return vec2(heading * (0.5 / PI) + 0.5, 0.5 - asin(clamp(d.z, -1.0, 1.0)) / PI);
}

// The map at an explicit mip level (textureLod: the u seam has no derivative jump, and the level comes
// from the reflection lobe, not from the screen).
vec3 environmentRadiance(vec3 dir, float lod) {
    return textureLod(uEnvironment, environmentUv(dir), clamp(lod, 0.0, uEnvironmentMaxLod)).rgb *
           uEnvironmentIntensity;
}

// The sky seen in direction dir (sharp): the environment map when there is one, else the procedural sky.
vec3 skyRadiance(vec3 dir) {
    if (!uHasEnvironment)
        return proceduralSky(dir, true);
    vec3 sky = environmentRadiance(dir, 0.0);
    return uPhysicalSky ? sky + sunDiscRadiance(dir) : sky;
}

// The sky averaged over a reflection lobe of mean-square slope m2 (Beckmann): the reflected directions
// spread by about sqrt(2 m2) radians (twice the slope angle per axis), so the map is read at the level
// whose texels (2 pi / width radians at level 0) are that wide.
vec3 skyRadianceLobe(vec3 dir, float m2) {
    if (!uHasEnvironment) // without the sun's disk: its reflection is the glitter, sunSpecular()
        return proceduralSky(dir, false);
    float spread = sqrt(2.0 * m2);
    float texel = 2.0 * PI / exp2(uEnvironmentMaxLod);
    // Toward the poles a lat-long texel spans only cos(elevation) of its width in angle, so neighbouring
    // pixels would pick scattered headings (a star pinched at the zenith): blur by that factor too.
    float pole = -log2(max(sqrt(max(1.0 - dir.z * dir.z, 0.0)), 1.0 / 1024.0));
    return environmentRadiance(dir, log2(max(spread / texel, 1.0)) + pole);
}

// What the sky pass draws above the horizon (the procedural sky when the map lights the sea only).
vec3 backgroundRadiance(vec3 dir) {
    return uHasEnvironment && uEnvironmentBackground ? skyRadiance(dir) : proceduralSky(dir, true);
}

// Irradiance of a horizontal surface from the sky (no sun), for diffuse foam and the water body's light.
// Procedural: the cosine-weighted mean of mix(zenith, horizon, (1 - mu)^7) is zenith + (horizon - zenith)
// * integral_0^1 (1 - mu)^7 2 mu dmu = ... * 2 / 72.
const float SKY_HORIZON_WEIGHT = 2.0 / 72.0;
vec3 skyIrradiance() {
    if (uHasEnvironment)
        return uEnvironmentIrradiance * uEnvironmentIntensity;
    return PI * mix(SKY_ZENITH, SKY_HORIZON, SKY_HORIZON_WEIGHT) * uSkyIntensity;
}

// ---- fog ----------------------------------------------------------------------------------------------

// The colour the fog scatters toward the eye for a view direction: the sky's own radiance just above the
// horizon in that azimuth (blurred for a map), so fully fogged sea and sky meet the horizon without a seam;
// or LightingDesc::fogColor.
vec3 fogColor(vec3 viewDir) {
    if (uHasFogColor)
        return uFogColor;
    vec2 h = viewDir.xy;
    float len = length(h);
    h = len > 1e-5 ? h / len : vec2(0.0, 1.0);
    // Looking steeply up or down the heading loses its meaning (it is undefined at the zenith and nadir,
    // where it would draw a star): there the fog takes the band's mean colour.
    float azimuthal = smoothstep(0.2, 0.7, len);
    if (uHasEnvironment && uEnvironmentBackground) { // the map's horizon band, interpolated in heading
        float b = (atan(h.x, h.y) * (0.5 / PI) + 0.5) * float(ENVIRONMENT_HORIZON_BINS) - 0.5;
        float b0 = floor(b);
        int i0 = int(mod(b0, float(ENVIRONMENT_HORIZON_BINS)));
        int i1 = int(mod(b0 + 1.0, float(ENVIRONMENT_HORIZON_BINS)));
        vec3 band = mix(uEnvironmentHorizon[i0], uEnvironmentHorizon[i1], b - b0);
        return mix(uEnvironmentHorizonMean, band, azimuthal) * uEnvironmentIntensity;
    }
    return mix(SKY_HORIZON * uSkyIntensity, proceduralSky(vec3(h, 0.0), false), azimuthal);
}

// Optical depth of the fog between altitudes z0 and z1 (metres above mean sea level) over a straight path
// of length dist, for rho(z) = rho0 e^(-z/H):  rho0 H (e^(-z0/H) - e^(-z1/H)) / ((z1 - z0) / dist),
// evaluated as rho0 dist e^(-min(z0,z1)/H) (1 - e^(-delta)) / delta, delta = |z1 - z0| / H, so no factor
// overflows or cancels; delta -> 0 is the horizontal limit rho0 e^(-z0/H) dist. Same expression as
// fogOpticalDepth() in Lighting.h (which the unit test checks against a numerical integral).
float fogOpticalDepth(float z0, float z1, float dist) {
    float H = uFogHeightFalloff;
    if (H <= 0.0)
        return uFogDensity * dist;
    float delta = abs(z1 - z0) / H;
    float shape = delta < 1e-3 ? 1.0 - delta * (0.5 - delta / 6.0) : (1.0 - exp(-delta)) / delta;
    return uFogDensity * dist * exp(-min(z0, z1) / H) * shape;
}

// Optical depth from altitude z0 along dir out of the fog (to the sky). Steep rays: the limit of
// fogOpticalDepth as dist -> infinity, rho0 H e^(-z0/H) / mu. Near the horizon a spherical Earth keeps
// the air mass finite (Chapman): a tangent ray sees rho0 e^(-z/H) sqrt(pi R H / 2), which the grazing term
// sqrt(2 H / (pi R)) in the denominator reproduces at mu = 0. A ray dipping below the horizontal without
// hitting the sea passes its lowest altitude zmin = z0 - mu^2 / (4 k c^2) (k = 1/(2R), c^2 = 1 - mu^2) and
// climbs out again: both halves counted. Uniform fog (H = 0) never reaches the sky.
float fogOpticalDepthToSky(float z0, vec3 dir) {
    float H = uFogHeightFalloff;
    if (H <= 0.0 || uFogDensity <= 0.0)
        return 0.0;
    float grazing = uCurvature > 0.0 ? sqrt(4.0 * H * uCurvature / PI) : 0.0;
    float mu = dir.z;
    if (mu >= 0.0 || uCurvature <= 0.0)
        return uFogDensity * H * exp(-z0 / H) / max(max(mu, 0.0) + grazing, 1e-6);
    float c2 = max(1.0 - mu * mu, 1e-6);
    float zmin = z0 - mu * mu / (4.0 * uCurvature * c2);
    return uFogDensity * H * (2.0 * exp(-zmin / H) - exp(-z0 / H)) / grazing;
}

// The tileable noise (mean 0.5) at a camera-relative point, read at one pair of tiles (scale = 1 / tile),
// shifted by `shift` tiles. The footprint is the unshifted point's in both stages (the warp's own
// derivatives are left out), so compute and forward shading filter alike.
float fogNoiseSample(vec3 rel, float along, vec3 scale, vec3 offset, vec3 shift) {
    vec3 p = rel * scale + offset;
#ifdef SHADE_COMPUTE
    return textureGrad(uFogNoiseMap, p + shift, gRelDx * scale * along, gRelDy * scale * along).r;
#else
    return textureGrad(uFogNoiseMap, p + shift, dFdx(p), dFdy(p)).r;
#endif
}

// The domain warp of the fog noise at a camera-relative point (Perlin's domain distortion): a read of the
// noise at the incommensurate FOG_NOISE_TILE_2 moves the main read FOG_NOISE_WARP tiles per unit, so neither
// tile repeats in the result (at a lag of one tile the other read differs, and with it the pattern).
vec3 fogNoiseWarp(vec3 rel, float along) {
    const vec3 scale2 = vec3(1.0 / FOG_NOISE_TILE_2, 1.0 / FOG_NOISE_TILE_2, 1.0 / FOG_NOISE_TILE_VERTICAL_2);
    float w = fogNoiseSample(rel, along, scale2, uFogNoiseOffset2, vec3(0.0));
    return vec3(FOG_NOISE_WARP * (w - 0.5), FOG_NOISE_WARP * (0.5 - w), 0.0);
}

// De Sylva's fog noise factor n at a camera-relative point: 1 + uFogNoise (2 N - 1), N the tileable noise
// (mean 0.5) scrolled with the wind, read at FOG_NOISE_TILE moved by `warp` (fogNoiseWarp). Mipmapped, so
// far away it averages to n = 1.
// `along` scales the pixel's footprint: the point is rel * along of the way from the eye (compute shading
// takes the texture's screen derivatives from the G-buffer's, gRelDx/gRelDy; the fragment stage from the quad).
float fogNoiseFactor(vec3 rel, float along, vec3 warp) {
    const vec3 scale1 = vec3(1.0 / FOG_NOISE_TILE, 1.0 / FOG_NOISE_TILE, 1.0 / FOG_NOISE_TILE_VERTICAL);
    float n = fogNoiseSample(rel, along, scale1, uFogNoiseOffset, warp);
    return 1.0 + uFogNoise * (2.0 * n - 1.0);
}

// The noise factor of the whole path from a sea point (camera-relative rel, altitude zSurface) to the eye at
// zCamera: tau = integral rho(z) n ds over the path, rho = rho0 e^(-z/H), by the two-point Gauss-Legendre
// rule in optical depth -- n at the points where the path's optical depth from the sea is 1/2 -+ 1/(2 sqrt 3)
// of its total, tau = tau_plain * mean(n). De Sylva evaluates n at the surface alone, which "gave fog which
// appeared glued to the geometry surface" (its words): from altitude the noise then reads as blotches
// printed on the sea, repeating at the noise tile. Along the path the noise moves through the air and a long
// path through the layer averages it, as a real one does. The quantile q's height above the surface is
// -H ln(1 - q (1 - e^(-dz/H))), dz = zCamera - zSurface (uniform fog, H = 0, or a level path: q of the way).
// Two points, not three: on an H200 at 1080p, high preset, the frame grew 6.0% with two and 9.0% with
// three (docs/LOOK.md), and the third changed the 12 km repetition of test_look_gl little.
float fogNoiseAlongPath(vec3 rel, float zCamera, float zSurface) {
    float H = uFogHeightFalloff;
    float dz = zCamera - zSurface;
    bool layered = H > 0.0 && abs(dz) > 1e-3 * H;
    float decay = layered ? 1.0 - exp(-dz / H) : 0.0;
    // One warp for the path, read at the sea point: the warp field is smooth on the scale of a path's
    // horizontal extent through the layer, and a read saved per pixel (on an H200 at 1080p, high preset,
    // the shading pass took 0.102 ms with a warp read per point, docs/LOOK.md).
    vec3 warp = fogNoiseWarp(rel, 1.0);
    float n = 0.0;
    for (int k = 0; k < 2; ++k) {
        float q = k == 0 ? 0.21132487 : 0.78867513; // 1/2 -+ 1/(2 sqrt 3)
        float s = layered ? -H * log(1.0 - q * decay) / dz : q; // fraction of the way to the eye
        n += fogNoiseFactor(rel * (1.0 - s), 1.0 - s, warp);
    }
    return 0.5 * n;
}

// Fog seen along dir out to the sky from altitude z0: the transmittance of the fog between.
float skyTransmittance(float z0, vec3 dir) {
    return exp(-fogOpticalDepthToSky(z0, dir));
}

// ---- water -------------------------------------------------------------------------------------------

float fresnelSchlick(float ndv) {
    float x = 1.0 - ndv;
    float x2 = x * x;
    return WATER_F0 + (1.0 - WATER_F0) * x2 * x2 * x; // (1 - ndv)^5 by multiplies
} // Schlick 1994

// Sunlight reaching altitude z through the fog.
vec3 sunLightAt(float z) {
    if (uSkyHoldsFog) // ClearSky::sunlight at the sea: through the air and the haze, the disc's share above
        return uSunColor * uSunIntensity; // the horizon included
    if (uPhysicalSky) // through the air (uSunColor, the horizon included) and the fog
        return uSunColor * uSunIntensity * skyTransmittance(z, uSunDir);
    return uSunColor * uSunIntensity * skyTransmittance(z, uSunDir) * step(0.0, uSunDir.z);
}

// Light scattered up out of the water body toward the eye (the "dull colour" of the "Complex Ocean Shader with Example" article, made view dependent):
// the view ray refracts into the water (Snell, n = WATER_IOR) and crosses the sunlit layer of depth D over
// D / cos(theta_t), gathering scatter (1 - e^(-sigma D / cos theta_t)). Scaled so that looking straight down
// gives uWaterColor (LightingDesc::waterColor, default DEEP_WATER_COLOR) under the default sky; oblique views see more (bluer) scattering. The light in the
// water follows the sky's irradiance and the sun's elevation.
// The luminance of the default sky's irradiance (skyIrradiance() of a default LightingDesc): the gradient's,
// or for the physical sky the default physical sky's (uWaterLightReference, computed once).
float waterLightReference() {
    vec3 reference = PI * mix(SKY_ZENITH, SKY_HORIZON, SKY_HORIZON_WEIGHT);
    return uPhysicalSky ? uWaterLightReference : dot(reference, vec3(0.2126, 0.7152, 0.0722));
}
// The water body under light of luminance `light` (relative to waterLightReference()) from elevation lightZ.
vec3 waterBodyLit(vec3 v, vec3 n, float light, float lightZ) {
    vec3 t = refract(-v, n, 1.0 / WATER_IOR);
    float cosT = max(abs(t.z), 0.1);
    vec3 sigma = vec3(WATER_EXT_R, WATER_EXT_G, WATER_EXT_B);
    vec3 nadir = 1.0 - exp(-sigma * WATER_SCATTER_DEPTH);
    vec3 along = 1.0 - exp(-sigma * (WATER_SCATTER_DEPTH / cosT));
    return uWaterColor * (along / nadir) * light *
           (0.6 + 0.4 * max(lightZ, 0.0)) * 4.0;
}
vec3 waterBody(vec3 v, vec3 n) {
    float light = dot(skyIrradiance(), vec3(0.2126, 0.7152, 0.0722)) / waterLightReference();
    return waterBodyLit(v, n, light, uSunDir.z);
}

// The sun's glitter: Cox & Munk's (1954) radiance of a sea whose facet slopes are Gaussian with mean-square
// slope m2 (the microfacet BRDF of Walter et al. 2007, eq. 20, with the Beckmann distribution, eq. 33):
//   L = E F(v.h) p(h) G1(v) / (4 cos(theta_v) cos^4(theta_h)),  p = e^(-tan^2(theta_h) / m2) / (pi m2),
// E the sunlight reaching the surface, theta_h the half vector's angle from the normal n (the slopes the
// model resolves tilt n; m2 holds the rest: Bruneton, Neyret & Holzschuch 2010, sec. 4) and G1 Smith's
// masking of the eye for Beckmann slopes by Walter et al.'s rational fit (eq. 27, a = cot(theta_v) / m),
// which keeps the glitter finite at grazing views. The mean radiance of a glitter pattern against this very
// formula is test_look_gl's SunGlitterFollowsCoxAndMunk.
uniform bool uGlitterBlinnPhong; // LightingDesc::Glitter::BlinnPhong: the lobe the glitter replaced (a knob)
// For light arriving from unit direction l (the sun: sunSpecular; a spot light: spot.glsl) with irradiance
// sunLight.
vec3 lightSpecular(vec3 n, vec3 v, vec3 l, float m2, vec3 sunLight) {
    vec3 h = normalize(l + v);
    if (uGlitterBlinnPhong) { // normalised Blinn-Phong, exponent 2 / m2 - 2 (Walter et al. 2007, eq. 30)
        float shininess = max(2.0 / m2 - 2.0, 1.0);
        float spec = pow(max(dot(n, h), 0.0), shininess) * (shininess + 8.0) / (8.0 * PI);
        return sunLight * (spec * fresnelSchlick(clamp(dot(n, v), 0.0, 1.0)));
    }
    float c = max(dot(n, h), 1e-3);
    float c2 = c * c;
    float e = (c2 - 1.0) / (c2 * m2); // -tan^2(theta_h) / m2
    if (e < -16.0)
        return vec3(0.0); // e^-16 = 1e-7 of the lobe's peak: most of the sea, which skips the rest
    float p = exp(e) / (PI * m2 * c2 * c2);
    float cv = max(dot(n, v), 1e-3);
    float a = cv * inversesqrt(m2 * max(1.0 - cv * cv, 1e-6));
    float g1 = a < 1.6 ? (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a) : 1.0;
    float fresnel = fresnelSchlick(clamp(dot(v, h), 0.0, 1.0));
    return sunLight * (fresnel * p * g1 / (4.0 * cv));
}
vec3 sunSpecular(vec3 n, vec3 v, float m2, vec3 sunLight) {
    return lightSpecular(n, v, uSunDir, m2, sunLight);
}

// The sky reflected at a surface point of altitude z: the sky over the reflection lobe, seen through the
// fog between the surface and the sky (so grazing reflections turn to the fog colour, like the horizon).
vec3 reflectedSky(vec3 r, float m2, float z) {
    float t = skyTransmittance(z, r);
    if (uSkyHoldsFog) // the map holds the haze above the camera: only the layer between is added
        t = min(t / max(skyTransmittance(max(uCameraHeight, z), r), 1e-6), 1.0);
    return mix(fogColor(r), skyRadianceLobe(r, m2), t);
}
