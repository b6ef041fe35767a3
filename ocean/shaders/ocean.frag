// ocean.frag: per-pixel sea lighting in scene-linear HDR — normals from the surface model's modelLighting()
// (for octaves: all maps light, the leading ones displace, §18.2.1), the normal tilt toward the viewer
// (§18.2.6), Schlick's Fresnel (Schlick 1994), reflection of the sky or environment map over the LEAN
// roughness lobe, the sun glitter of Cox & Munk (Beckmann microfacets, Smith masking), the view-dependent
// water body colour (Snell), foam (§18.3 height threshold, Jacobian folding) and Perlin fog with height
// falloff (the Intel projected-grid ocean's fog, C. De Sylva). The shared
// pieces (sky, fog, water body, highlight) are in sky.glsl, included before this file.
//
// Foam inputs — the optional third function of the surface-model contract (ocean/src/gpu/SurfaceGpu.h):
// a model that knows its height and horizontal-displacement Jacobian per fragment adds
//     #define MODEL_HAS_FOAM_INPUTS
//     vec2 modelFoamInputs(vec2 rel); // (H: height above mean sea level, metres; J: Jacobian determinant)
// to its GLSL file (rel = the camera-relative undisplaced grid point, as for modelLighting; it is called
// after modelLighting at the same point). Without it the height is the interpolated displaced vertex height
// and J = 1 (no folding foam). A model whose H remembers crests (the octaves' living whitecaps) also defines
// MODEL_FOAM_REMEMBERS, and the crests' glow takes the displaced height instead.

// Compute shading (OceanDesc::computeShading, ocean_shade.comp): the same lighting runs per pixel of a
// compute pass from a G-buffer (ocean_gbuffer.frag); it sets these inputs, and the screen derivatives the
// fragment stage takes with dFdx/dFdy (gGridDx.., shade_compute.glsl), itself.
#ifdef SHADE_COMPUTE
vec3 vRel = vec3(0.0);
vec2 vGrid = vec2(0.0);
#else
in vec3 vRel;  // camera-relative displaced position (ocean.vert)
in vec2 vGrid; // camera-relative undisplaced grid point
out vec4 fragColor;
#endif

// Effects (Effects.h): with effects present (EFFECT_FIELD) every pixel adds the effects field's slope and
// foam at its surface point (effects_sample.glsl, included before this file); the base grid's variant leaves
// out the discs the secondary grids cover (EFFECT_HOLES). Neither is compiled into a scene without effects.

uniform float uNormalTilt;
uniform float uMicroSlopeVariance; // LightingDesc::microSlopeVariance
uniform float uDisplaceRadius; // ocean.vert's: beyond it the grid is the undisplaced skirt

uniform sampler2D uFoamMap;   // the foam patterns and their squares (fine RG, coarse BA), mipmapped
uniform vec2 uFoamWind;       // unit vector the wind blows toward (east, north): the pattern's x axis
uniform vec2 uFoamOffsetNear; // fract((camera + drift t) / FOAM_TILE_NEAR) in the wind's frame, in double
uniform vec2 uFoamOffsetFar;
uniform vec3 uFoamMix[2 * FFT_MIX_TERMS]; // (k_x, k_y, psi) per layer (fine, coarse) and term
uniform float uFoamHeightStart; // H0
uniform float uFoamHeightFull;  // Hmax
uniform float uFoamJacobianThreshold;
uniform float uFoamIntensity;
uniform float uSubsurface;  // LightingDesc::subsurface
uniform float uCrestHeight; // Hs / 2 of the surface model, metres

// Sunlight scattered out of thin lit crests toward the eye: light scattered under the surface brightens thin
// lit crests. Sunlight entering a wave's sunward face crosses the crest, width
// w = CREST_SCATTER_PATH, losing e^(-sigma w) (the red most: the glow is blue-green), and is scattered on in
// the lit water under the eye's side over a length l = w c (c = z / crest height, clamped: the higher and
// thinner the crest, the more of it the light reaches; none at or below mean sea level, where the water
// body's own term holds): single scattering b l in the thin-path limit of (b / sigma)(1 - e^(-sigma l))
// (within 11% in green at c = 1; red, the channel it overstates, is mostly gone by then), per unit solid
// angle by Schlick's approximation of the Henyey-Greenstein phase function, p = (1 - k^2) / (4 pi
// (1 - k cos theta)^2), k = 1.55 g - 0.55 g^3 (Blasi, Le Saec & Schlick 1993), of the angle between the
// light's travel (-sun) and the eye. The light enters through the crest's side: scaled by the sun's
// horizontal share, and by the diffuse sun irradiance (SUN_DIFFUSE_SCALE) as foam is. The caller weights it
// by (1 - Fresnel). It fades out with distance as foam does (nearFade, FOAM_FADE_START..END): farther, the
// grid's sparse vertices alias the crest heights, and beyond the displaced radius the skirt has none -- faded,
// there is no seam at either. Per pixel it is a few multiplies and one division (the exponentials are
// constants): the GPU's graphics pipe has few SMs here, so exp() per channel per pixel showed in the frame.
vec3 crestScatter(vec3 v, float z, vec3 sunLight, float nearFade) {
    float c = uCrestHeight > 0.0 ? clamp(z / uCrestHeight, 0.0, 1.0) : 0.0;
    float weight = uSubsurface * c * nearFade;
    const vec3 sigma = vec3(WATER_EXT_R, WATER_EXT_G, WATER_EXT_B);
    const vec3 perCrest = WATER_SCATTERING * CREST_SCATTER_PATH * exp(-sigma * CREST_SCATTER_PATH);
    const float g = CREST_SCATTER_G;
    const float k = 1.55 * g - 0.55 * g * g * g;
    float d = 1.0 - k * dot(-uSunDir, v);
    float phase = (1.0 - k * k) / (4.0 * PI * d * d);
    return (weight * SUN_DIFFUSE_SCALE * phase * length(uSunDir.xy)) * sunLight * perCrest;
}


// GPU Gems 2 §18.3: alpha = (H - H0) / (Hmax - H0), clamped (the C++ twin: foamAlpha in Lighting.h).
float foamAlpha(float h) {
    if (uFoamHeightFull <= uFoamHeightStart)
        return h >= uFoamHeightStart ? 1.0 : 0.0;
    return clamp((h - uFoamHeightStart) / (uFoamHeightFull - uFoamHeightStart), 0.0, 1.0);
}

// Folding: alpha = (J0 - J) / J0, clamped (foamAlphaJacobian in Lighting.h).
float foamAlphaJacobian(float j) {
    if (uFoamJacobianThreshold <= 0.0)
        return 0.0;
    return clamp((uFoamJacobianThreshold - j) / uFoamJacobianThreshold, 0.0, 1.0);
}

// Height above the curved mean sea level of this fragment: the vertex stage subtracted the camera height and
// the curvature drop |rel|^2 / (2 R), so both are added back. The skirt beyond uDisplaceRadius is flat sea
// by definition (0): its triangles are chords kilometres long, whose midpoints stand up to metres above
// the sphere, which a fog of a few metres' scale height would show as rings.
float surfaceHeight() {
    if (dot(vGrid, vGrid) > uDisplaceRadius * uDisplaceRadius)
        return 0.0;
    return vRel.z + uCameraHeight + dot(vGrid, vGrid) * uCurvature;
}

vec2 foamInputs() {
#ifdef MODEL_HAS_FOAM_INPUTS
    return modelFoamInputs(vGrid);
#else
    return vec2(surfaceHeight(), 1.0);
#endif
}

// The share of the sea under foam where the coverage is c (the C++ twin: meanFoamOpacity in Lighting.h).
float foamOpacity(float c) {
    float t0 = 1.0 - c * (1.0 + FOAM_EDGE);
    float lo = clamp(t0, 0.0, 1.0);
    float hi = clamp(t0 + FOAM_EDGE, 0.0, 1.0);
    return (1.0 - hi) + ((hi - t0) * (hi - t0) - (lo - t0) * (lo - t0)) / (2.0 * FOAM_EDGE);
}

// The standard normal CDF and quantile (C++ twins normalCdf, normalQuantile in Lighting.h, same constants):
// Abramowitz & Stegun 7.1.26 for erf, M. Giles' "Approximating the erfinv function" for its inverse.
float normalCdf(float x) {
    float z = abs(x) * 0.70710678;
    float t = 1.0 / (1.0 + ERF_AS_P * z);
    const float a[5] = ERF_AS_A;
    float poly = t * (a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * a[4]))));
    float e = 1.0 - poly * exp(-z * z);
    return 0.5 * (1.0 + (x < 0.0 ? -e : e));
}
float normalQuantile(float p) {
    float x = 2.0 * clamp(p, FOAM_SHARE_MIN, 1.0 - FOAM_SHARE_MIN) - 1.0;
    float w = -log((1.0 - x) * (1.0 + x));
    float q;
    if (w < 5.0) {
        const float c[9] = ERFINV_CENTRAL;
        w -= 2.5;
        q = c[0];
        for (int i = 1; i < 9; ++i)
            q = c[i] + q * w;
    } else {
        const float c[9] = ERFINV_TAIL;
        w = sqrt(w) - 3.0;
        q = c[0];
        for (int i = 1; i < 9; ++i)
            q = c[i] + q * w;
    }
    return 1.41421356 * q * x;
}
// A foam layer's mix weights (cos theta, sin theta), theta = FFT_MIX_AMPLITUDE sum_j sin(psi_j + k_j . rel)
// (aperiodicMixWeights in SurfaceModel.h, phase set FOAM_MIX_SET + layer).
vec2 foamMixWeights(int layer, vec2 rel) {
    float theta = APERIODIC_MIX_THETA(uFoamMix, layer * FFT_MIX_TERMS, rel);
    return vec2(cos(theta), sin(theta));
}
// The mean and variance of a layer's field cos theta A + sin theta B over a footprint, from the two reads'
// moments (m, m^2 filtered); A and B (the pattern and its copy shifted by OCTAVE_MIX_SHIFT tiles) are
// independent, so the field stays standard normal and the variances add.
vec2 foamLayerMoments(vec2 a, vec2 b, vec2 w) {
    return vec2(w.x * a.x + w.y * b.x, w.x * w.x * (a.y - a.x * a.x) + w.y * w.y * (b.y - b.x * b.x));
}

// The foam opacity of a pixel (the C++ twin: foamCover in Lighting.h). The texture holds two standard normal
// fields and their squares (makeFoamPattern, makeFoamStreaks) and n mixes them, so their filtered reads give
// the mean and the variance of n over the pixel's footprint; foam is where n exceeds the threshold
// Phi^-1(1 - share), and the pixel shows the probability of that under a normal of those moments. Where the
// pattern is resolved this is its sharp edge, where it is not the edge softens exactly as much as the pixel
// averages it, and at every distance the mean over the sea is the share itself. `softness` s adds an
// unseen normal of variance s to n (the threshold scaled by sqrt(1 + s) to keep the share): 0 gives the
// whitecaps' crisp lace, more gives churned water's soft clouds.
float foamCover(float mean, float variance, float share, float softness) {
    if (share <= 0.0)
        return 0.0;
    if (share >= 1.0)
        return 1.0;
    float threshold = normalQuantile(1.0 - share) * sqrt(1.0 + softness);
    return normalCdf((mean - threshold) * inversesqrt(max(variance + softness, FOAM_MIN_VARIANCE)));
}

// The lit, fogged sea at this pixel (scene-linear).
vec3 shadeSea() {
    float dist = length(vRel);
    vec3 v = -vRel / max(dist, 1e-6); // towards the eye
    vec3 g = modelLighting(vGrid);
#ifdef EFFECT_FIELD
    vec4 effect = effectFieldAt(vRel.xy); // (E, dE/dx, dE/dy, foam)
    g.xy += effect.yz;
#endif
    vec3 n = normalize(vec3(-g.xy, 1.0));
    // §18.2.6: the surface is lit as if flat under the displacement; tilt toward the viewer so back faces
    // of waves seen at grazing angles do not flash.
    n = normalize(n + v * uNormalTilt * (1.0 - abs(v.z)));
    if (dot(n, v) < 0.0) // viewer below the tangent plane (grazing): reflect about the view-facing normal
        n = normalize(n - (dot(n, v) - 0.01) * v);
    float ndv = clamp(dot(n, v), 0.0, 1.0);
    float fresnel = fresnelSchlick(ndv);
    float z = surfaceHeight();
    // Beckmann mean-square slope m^2 = the slopes no model resolves (microSlopeVariance; with a sea state,
    // Cox & Munk's total minus the model's) + the model's slopes filtered away here (LEAN): it sets both
    // the sun's lobe and the blur of the reflected sky.
    float m2 = uMicroSlopeVariance + g.z;
    vec3 r = reflect(-v, n);
    r.z = abs(r.z); // rays reflected into the sea would hit another wave: use the sky above instead
    vec3 sunLight = sunLightAt(max(z, 0.0));
    vec2 fi = foamInputs(); // (height at this fragment, Jacobian)
    // Crest heights are resolved only near the eye: foam and the crests' glow fade out between these.
    float nearFade = 1.0 - smoothstep(FOAM_FADE_START, FOAM_FADE_END, dist);
#ifdef MODEL_FOAM_REMEMBERS
    float crest = z; // the foam input remembers crests that have passed: the glow needs the crest that stands
#else
    float crest = fi.x;
#endif
    vec3 water = fresnel * reflectedSky(r, m2, max(z, 0.0)) +
                 (1.0 - fresnel) * (waterBody(v, n) + crestScatter(v, crest, sunLight, nearFade)) +
                 sunSpecular(n, v, m2, sunLight);
#ifdef SPOT_LIGHTS
    // The spots' glitter and the light they put into the water body (spot.glsl).
    vec3 spotSpecular, spotLight;
    spotLighting(vRel, n, v, m2, spotSpecular, spotLight);
    water += (1.0 - fresnel) * spotWaterBody(v, n, spotLight) + spotSpecular;
#endif

    // Foam (§18.3): coverage from height and folding, textured by the pattern; a diffuse white (albedo
    // FOAM_ALBEDO) lit by the sun (SUN_DIFFUSE_SCALE) and the sky, covering the water's reflection and
    // highlight.
    float coverage = max(foamAlpha(fi.x), foamAlphaJacobian(fi.y)) * uFoamIntensity * nearFade;
    // The coverage thresholds the pattern (the §18.3 "foam texture", its alpha the coverage): a little
    // coverage shows only the pattern's densest streaks and lace, full coverage is solid foam (foamCover).
    // Two layers at incommensurate scales, laid along the wind (uFoamWind), drift apart, so the lace changes
    // over time; each is mixed with a shifted copy of itself (foamMixWeights), so neither tile repeats.
    // Most of the sea has no foam: its fetches and shading are skipped there, the derivatives taken first
    // (in uniform control flow) and the layers read with them.
    mat2 toWind = transpose(mat2(uFoamWind, vec2(-uFoamWind.y, uFoamWind.x))); // (along, across) the wind
    vec2 windGrid = toWind * vGrid;
    vec2 nearUv = windGrid / FOAM_TILE_NEAR + uFoamOffsetNear;
#ifdef SHADE_COMPUTE
    vec2 dnx = toWind * gGridDx / FOAM_TILE_NEAR, dny = toWind * gGridDy / FOAM_TILE_NEAR;
#else
    vec2 dnx = dFdx(nearUv), dny = dFdy(nearUv);
#endif
    vec3 color = water;
#ifdef EFFECT_FIELD
    float effectFoam = effect.w * uFoamIntensity;
    if (coverage > 0.0 || effectFoam > 0.0) {
#else
    if (coverage > 0.0) {
#endif
        const float farScale = FOAM_TILE_NEAR / FOAM_TILE_FAR;
        const vec2 shift = vec2(OCTAVE_MIX_SHIFT_U, OCTAVE_MIX_SHIFT_V);
        vec2 farUv = windGrid / FOAM_TILE_FAR + uFoamOffsetFar;
        vec2 fdx = dnx * farScale, fdy = dny * farScale;
        vec2 a = foamLayerMoments(textureGrad(uFoamMap, nearUv, dnx, dny).rg,
                                  textureGrad(uFoamMap, nearUv + shift, dnx, dny).rg, foamMixWeights(0, vGrid));
        vec2 b = foamLayerMoments(textureGrad(uFoamMap, farUv, fdx, fdy).ba,
                                  textureGrad(uFoamMap, farUv + shift, fdx, fdy).ba, foamMixWeights(1, vGrid));
        float mean = FOAM_NEAR_WEIGHT * a.x + FOAM_FAR_WEIGHT * b.x;
        float variance = FOAM_NEAR_WEIGHT * FOAM_NEAR_WEIGHT * a.y + FOAM_FAR_WEIGHT * FOAM_FAR_WEIGHT * b.y;
        float foam = foamCover(mean, variance, foamOpacity(coverage), 0.0);
#ifdef EFFECT_FIELD
        // Effect foam (crown, crests, wake strip) is churned white water: its coverage is the share itself,
        // thresholded softly in the same pattern (clouds, not lace), and not faded with distance (the field resolves it wherever it
        // is, and a wake must stay visible from 10 km).
        foam = max(foam, foamCover(mean, variance, min(effectFoam, 1.0), FOAM_EFFECT_SOFTNESS));
#endif
        vec3 foamColor =
            FOAM_ALBEDO / PI * (sunLight * (SUN_DIFFUSE_SCALE * max(dot(n, uSunDir), 0.0)) + skyIrradiance());
#ifdef SPOT_LIGHTS
        foamColor += FOAM_ALBEDO / PI * spotLight;
#endif
        color = mix(water, foamColor, foam);
    }

    // Fog between the eye and the surface (De Sylva's fog: f = e^(-tau n)), tau integrated over the height falloff
    // and the noise over the path (fogNoiseAlongPath).
    float tau = fogOpticalDepth(uCameraHeight, z, dist) * fogNoiseAlongPath(vRel, uCameraHeight, z);
    vec3 fogged = mix(fogColor(-v), color, exp(-tau));
#ifdef SPOT_LIGHTS
    fogged += spotScatter(-v, dist); // the beams in the fog before the sea
    fogged = min(fogged, vec3(SPOT_RADIANCE_MAX)); // a lamp's glare stays finite in a half-float target
#endif
    return fogged;
}

#ifndef SHADE_COMPUTE
void main() {
#if defined(EFFECT_HOLES) && !defined(EFFECT_HOLES_CLIPPED) // else cut by the clipper
    if (insideEffectGrid(vGrid))
        discard;
#endif
    fragColor = vec4(shadeSea(), 1.0);
}
#endif
