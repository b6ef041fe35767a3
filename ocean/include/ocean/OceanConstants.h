// OceanConstants: physical and shading constants shared by the CPU maths and the GLSL shaders.
// The shaders receive them as #defines generated from these values (OceanShaders.cpp), so there is
// exactly one source of truth.
#pragma once

#include "engine/Space.h"

#include <string>

namespace pacifica::ocean {

inline constexpr double GRAVITY = 9.81;  ///< m/s^2, deep-water dispersion w^2 = g k
inline constexpr double WATER_F0 = 0.02; ///< Schlick reflectance at normal incidence, n = 1.33
inline constexpr float DEEP_WATER_COLOR[3] = {0.0045f, 0.019f, 0.032f}; ///< scene-linear upwelling radiance
inline constexpr float FOG_DENSITY = 1.0f / 60000.0f; ///< 1/m, exponential distance fog (overridable)
inline constexpr int MAX_OCTAVES = 8;
/// The FFT sea's cascades (FftDesc::cascades): at most this many tiles, and a wave goes to the coarsest
/// tile whose grid spacing is at most 1/FFT_CASCADE_BAND_TEXELS of its wavelength (6: bilinear interpolation
/// of the displacement keeps such a wave within 4 % of its amplitude; the finer tile takes the rest).
inline constexpr int FFT_MAX_CASCADES = 4;
inline constexpr double FFT_CASCADE_BAND_TEXELS = 6.0;
/// The FFT cascades' aperiodic mix (FftDesc::aperiodic): cascade c is cos(theta) A + sin(theta) B of two
/// independent draws A, B, with theta(x) = FFT_MIX_AMPLITUDE * sum_j sin(k_j . x + phi_j), |k_j| = 2 pi /
/// (FFT_MIX_WAVELENGTHS[j] L_c) toward compass FFT_MIX_DIRECTIONS_DEG[j]. A lattice shift s of the tile
/// leaves A and B alone, so the field's correlation at s is E[cos(theta(x + s) - theta(x))] = prod_j J0(2 a
/// sin(k_j . s / 2)) (J0 the Bessel function): for the tile's shifts (L, 0), (0, L), (L, +-L), (2L, 0), ...
/// it is below 0.03 with these values; theta changes by ~6 radians over a tile (RMS gradient 6.4 / L).
inline constexpr int FFT_MIX_TERMS = 4;
inline constexpr double FFT_MIX_AMPLITUDE = 1.5;
inline constexpr double FFT_MIX_WAVELENGTHS[FFT_MIX_TERMS] = {1.37, 2.11, 2.97, 4.43};
inline constexpr double FFT_MIX_DIRECTIONS_DEG[FFT_MIX_TERMS] = {17.0, 79.0, 133.0, 211.0};
/// The octave sea's lighting-only octaves take the same mix (HeightOctavesDesc::aperiodic) with B = the
/// octave's own map shifted by (OCTAVE_MIX_SHIFT_U, OCTAVE_MIX_SHIFT_V) tiles (the golden ratio's parts: no
/// lattice vector, and far beyond the maps' correlation length) and phase set OCTAVE_MIX_SET + octave.
inline constexpr double OCTAVE_MIX_SHIFT_U = 0.381966011250105;
inline constexpr double OCTAVE_MIX_SHIFT_V = 0.618033988749895;
inline constexpr int OCTAVE_MIX_SET = 16;
/// The foam layers' mixes (ocean.frag foamMixWeights) take phase sets FOAM_MIX_SET (fine) and + 1 (coarse),
/// their shifted copies the octaves' shift.
inline constexpr int FOAM_MIX_SET = OCTAVE_MIX_SET + MAX_OCTAVES;
inline constexpr double EARTH_RADIUS = ::pacifica::EARTH_RADIUS; ///< m (engine/Space.h): the curvature drop

// Shading (ocean.frag, sky.glsl; docs/ARCHITECTURE.md "Shading").
inline constexpr double WATER_IOR = 1.33; ///< refractive index of sea water (Snell's law for the view ray)
/// Extinction of clear ocean water along the refracted view ray, 1/m (R, G, B): pure-water absorption
/// (Pope & Fry 1997: ~0.3 at 600 nm, 0.06 at 550 nm, 0.01 at 450 nm) plus particle scattering.
inline constexpr float WATER_EXTINCTION[3] = {0.35f, 0.075f, 0.045f};
/// Depth of the sunlit layer whose in-scattering the eye sees, metres: a view ray refracted to angle
/// theta_t crosses it over WATER_SCATTER_DEPTH / cos(theta_t) (the "dull colour" of the "Complex Ocean Shader
/// with Example" article, made view dependent).
inline constexpr float WATER_SCATTER_DEPTH = 8.0f;
/// Irradiance of the sun on diffuse surfaces (foam) per unit of LightingDesc::sunIntensity, which is
/// calibrated for the specular glitter: 0.2 puts the default sun at ~6x the procedural sky's irradiance, the
/// clear-day ratio of direct to diffuse light, so sunlit foam is bright without losing its texture.
inline constexpr float SUN_DIFFUSE_SCALE = 0.2f;
inline constexpr float FOAM_ALBEDO = 0.8f; ///< diffuse reflectance of whitecap foam
/// Light scattered out of thin lit crests (ocean.frag crestScatter): the scattering coefficient b of clear
/// ocean water, 1/m (Mobley 1994, "Light and Water", ch. 3: b ~ 0.03 m^-1 for case-1 water, mostly forward
/// scattering by particles), the Henyey-Greenstein asymmetry g of that scattering (a soft forward lobe;
/// Petzold's ocean phase function is more peaked, g ~ 0.9, but the crest's surfaces spread it), and the
/// length of the sunlit path through a crest standing one crest height (Hs / 2) above mean sea level, m.
inline constexpr float WATER_SCATTERING = 0.03f;
inline constexpr float CREST_SCATTER_G = 0.6f;
inline constexpr float CREST_SCATTER_PATH = 3.0f;
inline constexpr int FOAM_PATTERN_SIZE = 256;   ///< texels per side of the foam texture (mipmapped)
inline constexpr double FOAM_TILE_NEAR = 7.3;   ///< metres per repeat of the fine foam layer
inline constexpr double FOAM_TILE_FAR = 37.9;   ///< metres per repeat of the coarse layer (incommensurate)
inline constexpr double FOAM_DRIFT_SPEED = 0.4; ///< m/s the two foam layers drift apart, along the wind
/// The foam pattern's cells are this many times shorter across the wind than along it: streaks.
inline constexpr int FOAM_STREAK_ASPECT = 4;
/// Weights of the fine and coarse foam layers in the threshold field n = wn a + wf b (a, b standard normal
/// and independent, wn^2 + wf^2 = 1 so n is standard normal too; ocean.frag, Lighting.h foamCover).
inline constexpr double FOAM_NEAR_WEIGHT = 0.6;
inline constexpr double FOAM_FAR_WEIGHT = 0.8;
/// The unresolved variance of the threshold field never falls below this (a texel's own edge, antialiased).
inline constexpr double FOAM_MIN_VARIANCE = 1e-4;
/// Effects' foam (crowns, slicks, wake strips: churned water) thresholds the pattern with this softness
/// (Lighting.h foamCover): soft clouds of the share's mean, not the whitecaps' crisp lace.
inline constexpr double FOAM_EFFECT_SOFTNESS = 1.5;
/// Shares closer than this to 0 or 1 are clamped before the normal quantile (float precision in GLSL).
inline constexpr double FOAM_SHARE_MIN = 1e-5;
/// Spot lights a frame lights the sea with (OceanScene::spots); more are left out and counted
/// (OceanStats::spotsDropped).
inline constexpr int MAX_SPOT_LIGHTS = 8;
/// Spot lights' nearest distance in the inverse square law, metres: a surface point at the lamp itself gets a
/// finite irradiance (Lighting.h spotIrradiance).
inline constexpr double SPOT_MIN_DISTANCE = 0.1;
/// Henyey-Greenstein asymmetry g of the fog's scattering of the spots' light (their beams: spot.glsl
/// spotScatter, Lighting.h spotInScatter). Fog and haze droplets, a few micrometres across, scatter forward:
/// Mie theory gives g ~ 0.7-0.85 for them in visible light (Petty, "A First Course in Atmospheric Radiation",
/// 2nd ed., sec. 12.2); 0.7 keeps a beam seen from the side visible as it is at night.
inline constexpr double SPOT_FOG_PHASE_G = 0.7;
/// Width of the foam's soft edge in coverage (Lighting.h meanFoamOpacity: the share of the sea a coverage c
/// puts under foam).
inline constexpr double FOAM_EDGE = 0.3;
/// Abramowitz & Stegun, "Handbook of Mathematical Functions", 7.1.26 (erf, |error| <= 1.5e-7): p, a1..a5.
inline constexpr double ERF_AS_P = 0.3275911;
inline constexpr double ERF_AS_A[5] = {0.254829592, -0.284496736, 1.421413741, -1.453152027, 1.061405429};
/// M. Giles, "Approximating the erfinv function" (GPU Computing Gems, 2011), single precision: Horner
/// coefficients (highest power first) of the central branch (w = -ln(1 - x^2) < 5, in w - 2.5) and the tail
/// (in sqrt(w) - 3).
inline constexpr double ERFINV_CENTRAL[9] = {2.81022636e-08,  3.43273939e-07, -3.5233877e-06,
                                             -4.39150654e-06, 0.00021858087,  -0.00125372503,
                                             -0.00417768164,  0.246640727,    1.50140941};
inline constexpr double ERFINV_TAIL[9] = {-0.000200214257, 0.000100950558, 0.00134934322,
                                          -0.00367342844,  0.00573950773,  -0.0076224613,
                                          0.00943887047,   1.00167406,     2.83297682};
inline constexpr int FOG_NOISE_SIZE = 32;                 ///< texels per side of the 3D fog noise (mipmapped)
inline constexpr double FOG_NOISE_TILE = 12000.0;         ///< metres per horizontal repeat of the fog noise
inline constexpr double FOG_NOISE_TILE_VERTICAL = 1500.0; ///< metres per vertical repeat of the fog noise
/// The fog noise's domain is warped by a second read of the same texture at these tiles (the first ones over
/// the golden ratio, incommensurate), FOG_NOISE_WARP tiles per unit of that read (sky.glsl fogNoiseFactor),
/// so the noise repeats at no distance a view spans. One tile alone showed from 10-15 km as a 12 km
/// repetition of the fogged sea once the physical sky made the fog brighter than the sea beneath.
inline constexpr double FOG_NOISE_TILE_2 = 7416.4;
inline constexpr double FOG_NOISE_TILE_VERTICAL_2 = 927.05;
inline constexpr double FOG_NOISE_WARP = 2.0;
/// Height foam fades out between these distances (metres): beyond them the radial grid's vertices are too
/// far apart to resolve wave crests, so a single high vertex would paint a triangle-sized white patch.
inline constexpr float FOAM_FADE_START = 1500.0f;
inline constexpr float FOAM_FADE_END = 5000.0f;
/// Living whitecaps (HeightOctaves foam memory, foamMemory()): a breaking crest's foam stays where the crest
/// was, decays with an e-folding time of FOAM_DECAY_TIME seconds (whitecap foam area decays over a few
/// seconds: Callaghan, Deane & Stokes 2012, "Two regimes of laboratory whitecap foam decay", JGR 117, decay
/// times 1-5 s; Monahan's "stage B" residual foam lasts longest) and spreads as a diffusion of coefficient
/// FOAM_SPREAD_DIFFUSIVITY m^2/s (a patch grows by sqrt(2 D t) ~ 1.8 m over 8 s).
inline constexpr double FOAM_DECAY_TIME = 4.0;
inline constexpr double FOAM_SPREAD_DIFFUSIVITY = 0.2;
/// Living whitecaps of the FFT and Gerstner seas (FftDesc/GerstnerDesc::foamMemory): the crest heights
/// h+ = max(h, 0) at a grid point are
/// sampled every FOAM_MEMORY_STEP seconds of simulation time (on the fixed lattice t_j = j *
/// FOAM_MEMORY_STEP, so the memory does not depend on the frame rate), and the memory is the largest of the
/// last FOAM_MEMORY_WINDOW samples, each decayed by e^(-age / FOAM_DECAY_TIME). 0.2 s: a 20 m wave's crest
/// (5.6 m/s) moves ~1 m between samples, about half the 500 m / 256 tile's texel, so its trail has no gaps.
/// 30 samples = 6 s: an older crest is decayed below e^(-1.5) = 0.22 of its height, so it would still show
/// foam only if it stood 4.5 times the foam threshold high (a threshold is ~1.5-2.5 sigma, crests < 4 sigma).
/// A fixed window, not a running recursion, makes the memory a function of the time alone: a seek, a pause
/// or a different frame rate give the same foam (FftGpu recomputes the samples it lacks; gerstner.glsl
/// evaluates the window's heights per pixel by rotating each wave's phase).
inline constexpr double FOAM_MEMORY_STEP = 0.2;
inline constexpr int FOAM_MEMORY_WINDOW = 30;
/// The colour of the sunlight above the haze for the gradient sky and environment maps (the physical sky
/// reddens it through the air instead: ClearSky::sunlight); the shaders' uSunColor.
inline constexpr float SUN_COLOR[3] = {1.0f, 0.92f, 0.80f};
/// The physical sky is computed for the camera's altitude rounded to the level k nearest to
/// log(1 + h / H0) / log(1 + step): altitudes H0 ((1 + step)^k - 1) = 0, 25, 50.6, 76.9 m, ..., so a
/// camera below ~12 m sees the sea-level sky, levels are 2.5 % of (h + 1 km) apart, and 0-15 km holds 112
/// levels. Levels, not the last altitude drawn, so a frame's sky does not depend on the frames before it
/// (sharded replay, seeking). The error this costs is in docs/LOOK.md ("The clear sky").
inline constexpr double SKY_ALTITUDE_H0 = 1000.0;
inline constexpr double SKY_ALTITUDE_STEP = 0.025;
/// The luminance of the irradiance of a horizontal surface at the sea from the default physical sky (a
/// default LightingDesc: its sun direction and haze), per unit solar irradiance: the sky under which
/// LightingDesc::waterColor is the upwelling radiance straight down (sky.glsl waterBody). test_atmosphere
/// recomputes it from ClearSky.
inline constexpr float PHYSICAL_SKY_WATER_REFERENCE = 0.05622f;
inline constexpr int ENVIRONMENT_HORIZON_BINS = 64; ///< azimuth bins of environmentHorizonBand() (Lighting.h)

/// How far the sea surface at horizontal distance d from the camera lies below the camera's tangent plane
/// on a spherical Earth: d^2 / (2 R) (the small-angle sagitta; error < 1e-4 relative up to 100 km). The
/// vertex shader applies the same drop, so from 15 km the horizon sits 3.9 degrees below eye level.
inline double curvatureDrop(double d) {
    return d * d / (2.0 * EARTH_RADIUS);
}

/// GLSL `#define` lines for the constants above (plus MAX_OCTAVES), prepended to every ocean shader.
std::string shaderConstantDefines();
/// GLSL `#define` lines for the effects' constants (Effects.h), prepended to the programs with effects.
std::string effectConstantDefines();

} // namespace pacifica::ocean
