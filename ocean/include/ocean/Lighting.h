// Lighting: how the sea and the sky are lit, fogged and foamed (scene-linear HDR). The shading itself lives
// in ocean/shaders/sky.glsl (sky, environment map, fog, water body: shared by the sky and sea programs) and
// ocean/shaders/ocean.frag (the sea); ocean/src/gpu/LightingGpu.cpp sets these values as uniforms and owns
// the lighting textures. The formulas that decide how much fog and foam there is are defined here once in
// C++ (fogOpticalDepth, foamAlpha) and repeated expression for expression in GLSL, so the CPU tests check the
// shader's maths (docs/ARCHITECTURE.md, "Shading").
//
// STEP BY STEP (lighting an ocean)
//   1. OceanDesc desc; desc.lighting.sunDirection = {...};           // everything has working defaults
//   2. Optional HDR sky: load a lat-long image yourself (the ocean library reads no image files), then
//        desc.lighting.environment = std::make_shared<const EnvironmentMap>(
//            makeEnvironmentMap(width, height, std::move(rgb)));     // throws EnvironmentMapError on NaN/Inf
//      and, for a matching sun, desc.lighting.sunDirection = environmentBrightestDirection(*map).
//   3. Fog: fogDensity (1/m at sea level) thinning with altitude over fogHeightFalloff metres; foam:
//      foamHeightStart/foamHeightFull (GPU Gems 2 §18.3) and foamJacobianThreshold (folding waves).
//   4. validateLighting(desc.lighting) names a bad field; the renderer uploads each texture once.
#pragma once

#include "ocean/OceanConstants.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pacifica::ocean {

/// A scene-linear HDR environment in the latitude-longitude (equirectangular) layout, used for the sky
/// behind the sea and for its reflections.
///
/// Layout and orientation (world ENU: x east, y north, z up):
///   - `rgb` holds width * height * 3 floats, rows top-down, pixels left to right.
///   - v (row) is elevation: the top edge is +90 degrees (zenith), the middle row the horizon, the bottom
///     edge -90 degrees: elevation = pi * (0.5 - v) with v = (row + 0.5) / height.
///   - u (column) is heading, clockwise from north seen from above, like Pose::headingDeg:
///     heading = 2 pi * (u - 0.5) with u = (column + 0.5) / width. So the CENTRE column looks north (+y),
///     u = 0.75 looks east (+x), and u = 0 (the left edge, the wrap-around seam) looks south (-y).
///   This is OpenEXR's lat-long convention (ImfEnvmap.h) with its +z axis (the image centre) turned to
///   north: reading a panorama from left to right turns the viewer to the right.
struct EnvironmentMap {
    int width = 0;
    int height = 0;
    std::vector<float> rgb; ///< scene-linear Rec.709, finite and >= 0 (makeEnvironmentMap checks)
    float intensity = 1.0f; ///< scale applied to every pixel when rendering
};

/// makeEnvironmentMap() rejected the data. what() is "makeEnvironmentMap(): pixel (x,y) is NaN" (or
/// "... is infinite", "... is negative (-0.5)", or a size mismatch); problem() is the part after "(): ",
/// so a tool can print "FILE: pixel (x,y) is NaN". x, y are the column and row (top row 0), or -1.
class EnvironmentMapError : public std::invalid_argument {
public:
    EnvironmentMapError(const std::string& problem, int x = -1, int y = -1)
        : std::invalid_argument("makeEnvironmentMap(): " + problem), mProblem(problem), mX(x), mY(y) {}
    const std::string& problem() const { return mProblem; }
    int x() const { return mX; }
    int y() const { return mY; }

private:
    std::string mProblem;
    int mX, mY;
};

/// Validates and wraps lat-long RGB data (see EnvironmentMap for the layout). Throws EnvironmentMapError
/// naming the first bad pixel in row-major order (NaN, infinite or negative: data is rejected, never
/// silently clamped, so a broken file is noticed), or a size that does not match width * height * 3, or
/// width/height outside [1, 16384].
EnvironmentMap makeEnvironmentMap(int width, int height, std::vector<float> rgb);

/// World direction (unit, ENU) of the lat-long coordinate (u, v) in [0,1]^2 (EnvironmentMap convention).
glm::dvec3 environmentDirection(double u, double v);
/// Inverse of environmentDirection(): (u, v) of a world direction (u in [0,1), v in [0,1]).
glm::dvec2 environmentUv(const glm::dvec3& direction);
/// Direction of the brightest region of the map: the luminance- and solid-angle-weighted mean direction of
/// the pixels at least half as bright as the brightest one, for pointing LightingDesc::sunDirection at the
/// sun the map shows. (0, 0, 1) for an all-black map.
glm::dvec3 environmentBrightestDirection(const EnvironmentMap& map);

/// Cosine-weighted irradiance of a horizontal surface from the map's upper hemisphere (before
/// EnvironmentMap::intensity), with the sun taken out: every pixel's luminance is capped at 16x the
/// median luminance of the upper hemisphere, so a photographed sun (the Kerner map's reaches 1678) does
/// not count twice — the renderer adds the sun itself (LightingDesc::sunDirection/sunIntensity).
glm::vec3 environmentIrradiance(const EnvironmentMap& map);
/// The fog colour of an environment-lit scene per azimuth: ENVIRONMENT_HORIZON_BINS bins of heading (bin i
/// centred on u = (i + 0.5) / bins), each the mean of the band 0..20 degrees above the horizon, with the
/// same sun cap as environmentIrradiance() and a circular (1,4,6,4,1)/16 smoothing across bins. The fogged
/// sea and sky then meet the horizon in the map's own haze colour without the sun flaring the fog.
std::vector<glm::vec3> environmentHorizonBand(const EnvironmentMap& map);

struct LightingDesc {
    glm::dvec3 sunDirection{0.35, -0.55, 0.30}; ///< towards the sun, world ENU (normalised on use)
    float sunIntensity = 20.0f; ///< scene-linear radiance scale of the sun's specular highlight
    float skyIntensity = 1.0f;  ///< scale of the procedural sky radiance
    /// Fog extinction at sea level, 1/m (GPU Gems 2 ch. 18's fog: f = e^(-rho d n)). 3e-5 ~ 130 km
    /// meteorological visibility (Koschmieder: V = 3.912 / rho) at sea level: a very clear day. With a
    /// height falloff it is also the physical sky's haze layer (Atmosphere.h), so sky and sea hold one haze;
    /// the gradient sky is the sky above it; a photographed sky already holds some haze, to which this adds.
    float fogDensity = 3.0e-5f;
    float normalTilt = 0.15f; ///< §18.2.6: tilt of the lighting normal toward the viewer
    /// Beckmann mean-square slope of the waves no surface model resolves (short gravity and capillary
    /// waves), added to the model's unresolved slope variance for the sun's lobe and the sky's blur
    /// (ocean.frag). applySeaState() sets it so the total is Cox & Munk's (SeaState.h).
    float microSlopeVariance = 0.0012f;

    /// The sky when there is no `environment`: the physically based clear sky (Atmosphere.h: precomputed
    /// scattering by air and haze over a spherical Earth, seen from the camera's altitude, with the sunlight
    /// reddened through it; the default), or the zenith-to-horizon gradient it replaced (cheaper: no table
    /// to compute or upload; a knob of `pacifica bench accuracy`).
    enum class Sky { Physical, Gradient };
    Sky sky = Sky::Physical;

    /// HDR lat-long sky for the background and the sea's reflections; null = the procedural sky. Shared
    /// and immutable: the renderer uploads each map once (mipmapped) and keeps it while it is in use.
    std::shared_ptr<const EnvironmentMap> environment;
    /// false: the map lights the sea (reflections, foam) but the sky pass still draws the procedural sky.
    bool environmentBackground = true;

    /// Scale height H of the fog, metres: rho(z) = fogDensity * e^(-z / H), so the vertical optical depth
    /// of the whole layer is fogDensity * H (0.06 here: from 15 km the sea shows through 94 % of it
    /// straight down). 0 = the old uniform distance fog applied to the sea only (the sky stays clear).
    float fogHeightFalloff = 600.0f;
    /// Amplitude of the 3D noise modulating the density (0 = smooth fog, 1 = density varies 0..2x).
    float fogNoise = 0.2f;
    /// Horizontal wind carrying the fog noise, m/s (east, north).
    glm::dvec2 fogWind{3.0, 4.0};
    /// Colour the fog scatters (scene-linear). Empty: the sky's own radiance at the horizon in the view's
    /// azimuth (procedural or environment), so the fogged horizon meets the sky without a seam. A host that
    /// draws its own sky (OceanDesc::drawSky = false) sets it to match that sky's horizon.
    std::optional<glm::vec3> fogColor;

    /// GPU Gems 2 §18.3 foam: alpha = (H - H0) / (Hmax - H0), clamped to [0, 1], H the displaced height
    /// above mean sea level, metres.
    float foamHeightStart = 1.6f; ///< H0
    float foamHeightFull = 3.2f;  ///< Hmax (> H0)
    /// Foam where the horizontal displacement folds the surface: alpha = (J0 - J) / J0 for Jacobian J < J0
    /// (Tessendorf 2001 §4.4); only models that provide modelFoamInputs() report J (others: J = 1).
    float foamJacobianThreshold = 0.3f;
    float foamIntensity = 1.0f; ///< scales the foam coverage; 0 disables foam
    /// Compass direction the wind blows toward, degrees (as SeaState::windDirectionDeg): the foam's streaks
    /// lie along it and its pattern drifts with it. applySeaState() sets it with the sea's wind.
    double windDirectionDeg = 60.0;
    /// Upwelling radiance of the water body seen straight down under the default sky (the "Complex Ocean
    /// Shader with Example" article's "dull colour"; oblique views and other skies scale it, sky.glsl
    /// waterBody), scene-linear, each >= 0.
    glm::vec3 waterColor{DEEP_WATER_COLOR[0], DEEP_WATER_COLOR[1], DEEP_WATER_COLOR[2]};
    /// Scale of the sunlight scattered out of thin lit crests toward the eye (ocean.frag crestScatter:
    /// single scattering over the crest's sunlit path, Henyey-Greenstein forward lobe), in [0, 10]; 0 = off.
    float subsurface = 1.0f;
    /// The sun's glitter: Cox & Munk's radiance (Beckmann microfacets with Smith masking, sky.glsl
    /// sunSpecular; the default) or the normalised Blinn-Phong lobe it replaced (exponent 2 / m2 - 2, Walter
    /// et al. 2007 eq. 30, Fresnel at n.v, no masking) -- a knob of `pacifica bench accuracy`.
    enum class Glitter { CoxMunk, BlinnPhong };
    Glitter glitter = Glitter::CoxMunk;
    /// Spot lights' beams in the fog (spotInScatter): quadrature points per beam and pixel, in [0, 64]; 0 =
    /// no beams (the lamps still light the sea). The error of each count is a row of `pacifica bench
    /// accuracy`; 8 keeps a beam seen from the side within a few per cent of the exact integral.
    int spotScatterSamples = 8;
};

/// Throws std::invalid_argument naming the first bad field ("OceanDesc.lighting.fogDensity must be ...").
void validateLighting(const LightingDesc& lighting);

/// The Sun's illuminance outside the atmosphere, lux: the luminous solar constant (Darula, Kittler & Gueymard
/// 2005, "Reference luminous solar constant and solar luminance for illuminance calculations", Solar Energy
/// 79: 133.8 klx). LightingDesc::sunIntensity is this light's scale; the Moon's is a fraction of it.
inline constexpr double SUN_ILLUMINANCE_LUX = 133800.0;
/// The Moon's illuminance outside the atmosphere at phase angle `phaseDeg` (0 = full, 180 = new), lux:
/// Krisciunas & Schaefer 1991, "A model of the brightness of moonlight" (PASP 103): the Moon's apparent
/// magnitude m = -12.73 + 0.026 |a| + 4e-9 a^4 (a in degrees; Allen's law, the opposition surge included) and
/// I = 10^(-0.4 (m + 16.57)) foot-candles (10.764 lx each). Full: 0.313 lx, 2.3e-6 of the Sun's.
/// Throws std::invalid_argument outside [0, 180].
double moonIlluminanceLux(double phaseDeg);
/// A moonlit night: the Moon, not the Sun (below the horizon), is the light. The Moon is a sunlit grey disc
/// of nearly the Sun's apparent size (0.52 degrees against 0.53), so it is the Sun's light in its direction
/// scaled by moonIlluminanceLux(phaseDeg) / SUN_ILLUMINANCE_LUX: its glitter (the same Cox & Munk lobe), its
/// disc, its reddening through the air and the physical sky it lights (the same scattering, as dim), the
/// gradient sky, an environment map (copied) and a fixed fog colour scaled alike. Starlight and airglow
/// (~1/10 of a full Moon's sky) are not modelled. `moonDirection` toward the Moon, world ENU. Throws
/// std::invalid_argument for a zero or non-finite direction or a phase outside [0, 180].
LightingDesc moonlit(LightingDesc lighting, const glm::dvec3& moonDirection, double phaseDeg);
/// Pre-exposure (Lagarde & de Rousiers 2014, "Moving Frostbite to Physically Based Rendering", sec. 5.1):
/// every light scaled by 2^ev -- the sun (and the physical sky, which follows it), the gradient sky, an
/// environment map (copied with its intensity scaled), a fixed fog colour -- so the frame holds radiance x
/// 2^ev. A moonlit sea (~2e-6 of daylight) would otherwise lie in half float's subnormals (below 6.1e-5),
/// whose coarse steps band the sky once a view transform brightens it. The host scales its own lights
/// (spots, objects) alike. Throws std::invalid_argument for a non-finite ev or |ev| > 40.
LightingDesc exposed(LightingDesc lighting, double ev);

/// A spot light over the sea (a lighthouse, a ship's searchlight, a deck light), supplied by the host per
/// frame (OceanScene::spots). It lights the sea's glitter (the sun's Cox & Munk lobe with the spot as its
/// source), the water body and the foam. As in the Intel projected-grid ocean's lighthouse ("Light
/// Implementation"), a point lies in the light when the angle theta between the spot's axis and the ray from
/// the spot to the point is within the frustum's half-angle theta_f, and the light falls off as
/// saturate(|theta_f / theta| - 1): full within theta_f / 2, none from theta_f on (spotFalloff).
struct SpotLight {
    glm::dvec3 position{0.0};             ///< world ENU, metres
    glm::dvec3 direction{0.0, 0.0, -1.0}; ///< the cone's axis, world ENU (normalised on use; not zero)
    double frustumDeg = 15.0;             ///< theta_f, the cone's half-angle, degrees in (0, 90]
    glm::vec3 color{1.0f};                ///< scene-linear, each >= 0
    /// Radiant intensity on the axis, in the sun's units: the irradiance at distance d is intensity / d^2
    /// (the sun's is LightingDesc::sunIntensity, 20 by default, for ~1e5 lux; so 2e4 is ~1e8 cd, a large
    /// naval searchlight). >= 0.
    float intensity = 2.0e4f;
    /// Metres: the light fades smoothly to 0 here, (1 - (d / range)^4)^2 on the inverse square (Karis,
    /// "Real Shading in Unreal Engine 4", SIGGRAPH 2013, eq. 9), so a spot costs nothing beyond it. > 0.
    double range = 5000.0;
};

/// The largest colour x intensity per channel a spot may have: a large naval searchlight is ~2e4, and 1e12
/// keeps the shader's products (over SPOT_MIN_DISTANCE^2, times the glitter's peak) far inside a float.
inline constexpr double MAX_SPOT_INTENSITY = 1e12;

/// Throws std::invalid_argument naming the spot and field ("spots[2].frustumDeg must be in (0, 90], got
/// 120"; colour x intensity above MAX_SPOT_INTENSITY).
void validateSpotLight(const SpotLight& spot, size_t index);
/// The seed's falloff saturate(|theta_f / theta| - 1), as saturate(theta_f / max(theta, theta_f / 2) - 1):
/// the same value at every theta > 0, and its limit 1 on the axis, where the seed's is undefined.
double spotFalloff(double theta, double frustum);
/// The irradiance the spot delivers at world point p on a surface facing it (times n.l for a surface of
/// normal n), scene-linear: color intensity spotFalloff(theta, theta_f) window(d / range) / max(d,
/// SPOT_MIN_DISTANCE)^2. spot.glsl's spotIrradiance is the same expression.
glm::dvec3 spotIrradiance(const SpotLight& spot, const glm::dvec3& p);

/// The part [t0, t1] of the ray origin + t dir (dir unit, t in the given [t0, t1]) inside the spot's cone and
/// range; false when none is. The cone (half-angle <= 90 degrees) is convex, so the part is one interval: its
/// ends are among the ray's crossings of the cone's quadric and of the plane through the apex across the
/// axis, and one point between consecutive crossings decides each piece. spot.glsl's spotConeInterval.
bool spotConeInterval(const SpotLight& spot, const glm::dvec3& origin, const glm::dvec3& dir, double& t0,
                      double& t1);
/// The spot's light scattered once toward the eye by the fog along the ray eye + t dir, t in [0, tMax]
/// (world ENU, dir unit), scene-linear radiance:
///   SUN_DIFFUSE_SCALE color intensity int sigma(z) p(l . -dir) falloff window T_eye T_lamp / max(d, d_min)^2
///   dt
/// over the ray's part in the cone, sigma(z) = fogDensity e^(-z/H) (the noise factor taken as 1), p the
/// Henyey-Greenstein phase function with g = SPOT_FOG_PHASE_G, T the fog's transmittance (fogOpticalDepth)
/// from the point to the eye and from the lamp to the point. `samples` quadrature points, equiangular about
/// the lamp (Kulla & Fajardo 2012, "Importance Sampling Techniques for Path Tracing in Participating Media",
/// sec. 4.1), which integrates the 1/d^2 peak exactly; spot.glsl's spotScatter is the same quadrature.
glm::dvec3 spotInScatter(const SpotLight& spot, const LightingDesc& lighting, const glm::dvec3& eye,
                         const glm::dvec3& dir, double tMax, int samples);

/// Optical depth of the fog along a straight segment of length `distance` (metres) from altitude z0 to z1
/// (metres above mean sea level), for rho(z) = rho0 e^(-z/H) (rho0 = fogDensity, H = fogHeightFalloff):
///
///   tau = integral_0^d rho0 e^(-z(s)/H) ds = rho0 H (e^(-z0/H) - e^(-z1/H)) / ((z1 - z0) / d)
///
/// (z linear in s), and the horizontal limit z1 -> z0 is rho0 e^(-z0/H) d. Evaluated in the equivalent
/// form rho0 d e^(-min(z0,z1)/H) (1 - e^(-delta)) / delta, delta = |z1 - z0| / H, whose factors all lie in
/// [0, 1], so it neither overflows nor cancels (15 km above a 10 m scale height included). H = 0 gives the
/// uniform rho0 d. The noise factor n of De Sylva's fog multiplies this in the shader. ocean.frag/sky.glsl
/// use the same expression (fogOpticalDepth in sky.glsl).
double fogOpticalDepth(double z0, double z1, double distance, const LightingDesc& lighting);

/// GPU Gems 2 §18.3: clamp((height - H0) / (Hmax - H0), 0, 1); a step at H0 when Hmax <= H0. The shader's
/// foamAlpha() in ocean.frag is the same expression.
double foamAlpha(double height, const LightingDesc& lighting);
/// Folding foam: clamp((J0 - J) / J0, 0, 1) (0 when J0 <= 0).
double foamAlphaJacobian(double jacobian, const LightingDesc& lighting);

/// The share of the sea that foam covers where the foam coverage (foamAlpha, times foamIntensity) is c: a
/// threshold ramp of soft edge e = FOAM_EDGE over a uniform rank, clamp((r - 1 + c (1 + e)) / e, 0, 1),
/// averaged over r: 0 at c = 0, 1 at c = 1, increasing. ocean.frag thresholds the foam pattern so that
/// each pixel's expected opacity is this share (foamCover), at every distance. What applySeaState() matches
/// to Monahan's whitecap coverage.
double meanFoamOpacity(double coverage);

/// The tileable fog density noise: size^3 values in [0, 1] (x fastest), mean ~0.5, a sum of 3 octaves of
/// periodic gradient (Perlin) noise blurred once with the binomial (1,2,1) kernel, wrapping at the edges
/// (De Sylva's fog: noise octaves + Gaussian blur, "a mod operator to wrap the sampling space").
std::vector<float> makeFogNoise(int size, uint32_t seed = 7);
/// The tileable foam patterns, size^2 values each (x fastest), wrapping at the edges. Each is a standard
/// normal sample (its texels' ranks through normalQuantile) whose shapes are foam's, x laid along the wind:
/// makeFoamPattern, the fine layer: the lace of cell walls between bubbles at two scales, holes, and fine
/// streaks; makeFoamStreaks, the coarse layer: streaks and windrows, fBm FOAM_STREAK_ASPECT times longer
/// along x than across, with no cells (whose regular spacing showed from a distance). LightingGpu uploads
/// both with their squares (the moments ocean.frag's foamCover filters).
std::vector<float> makeFoamPattern(int size, uint32_t seed = 11);
std::vector<float> makeFoamStreaks(int size, uint32_t seed = 12);

/// The standard normal CDF Phi(x) (Abramowitz & Stegun 7.1.26: |error| <= 1.5e-7); ocean.frag's normalCdf is
/// the same expression.
double normalCdf(double x);
/// The standard normal quantile Phi^-1(p) (M. Giles' single-precision erfinv), p clamped to [FOAM_SHARE_MIN,
/// 1 - FOAM_SHARE_MIN]; ocean.frag's normalQuantile is the same expression.
double normalQuantile(double p);
/// The foam opacity of a pixel whose footprint holds the pattern's threshold field with this mean and
/// variance, where a share `share` of the sea is to be foam: Phi((mean - Phi^-1(1 - share) sqrt(1 + s)) /
/// sqrt(variance + s)) (the denominator's variance at least FOAM_MIN_VARIANCE), 0 at share <= 0 and 1 at
/// share >= 1. The softness s >= 0 adds an unseen normal of variance s to the field: 0 for the whitecaps'
/// crisp edges, FOAM_EFFECT_SOFTNESS for effects' churned water. Over a standard normal field its mean is
/// `share` for every softness, however the field is split between resolved mean and unresolved variance.
/// ocean.frag's foamCover is the same expression.
double foamCover(double mean, double variance, double share, double softness = 0.0);

} // namespace pacifica::ocean
