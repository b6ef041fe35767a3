// SeaState: one knob -- the wind speed U10 (or a Beaufort number) -- that sets the sea consistently for all
// three surface models, from published fits to measurements:
//   - wave height: the fully developed significant wave height Hs = 0.21 U^2 / g (Pierson & Moskowitz 1964,
//     U at 19.5 m taken as U10 here); the FFT model gets U directly (its JONSWAP spectrum, FftOcean.h);
//   - whitecap coverage W = 3.84e-6 U^3.41 (Monahan & O'Muircheartaigh 1980, eq. 5): the foam thresholds are
//     set so the mean height-foam coverage over the model's own heights is W;
//   - total mean-square slope s^2 = 0.003 + 5.12e-3 U (Cox & Munk 1954, clean surface): the lighting's
//     microSlopeVariance is what the model's own slopes leave of it (at least MIN_MICRO_SLOPE_VARIANCE), so
//     the sun glitter's width follows the wind for every model.
//
// STEP BY STEP
//   OceanDesc d = applySeaState(oceanPreset(Quality::High), {.windSpeed = beaufortWindSpeed(6)});
//   d.model = SurfaceKind::Fft;   // any model: each reads its own part
//   registry.emplace<OceanComponent>(e, makeOcean(d));
#pragma once

#include "ocean/Ocean.h"

namespace pacifica::ocean {

struct SeaState {
    double windSpeed = 12.0;        ///< U10, m/s, in [MIN_WIND, MAX_WIND]
    double windDirectionDeg = 60.0; ///< compass direction the wind blows toward
};
inline constexpr double SEA_STATE_MIN_WIND = 1.0, SEA_STATE_MAX_WIND = 30.0;
/// The wind speed the default octave and Gerstner seas were shaped for (their Hs is scaled from here).
inline constexpr double SEA_STATE_REFERENCE_WIND = 12.0;
/// Floor of the sub-model slope variance (capillary roughness the models never hold).
inline constexpr double MIN_MICRO_SLOPE_VARIANCE = 0.0005;
/// The octave sea under a sea state: detail octaves are added (tile / SEA_STATE_DETAIL_RATIO each, down to
/// SEA_STATE_FINEST_TILE metres, SEA_STATE_OCTAVES in all) and its lighting-only octaves scaled so the model
/// resolves SEA_STATE_RESOLVED_SLOPES of Cox & Munk's slope variance (SeaState.cpp).
inline constexpr int SEA_STATE_OCTAVES = 7;
inline constexpr double SEA_STATE_DETAIL_RATIO = 4.37;
inline constexpr double SEA_STATE_FINEST_TILE = 0.15;
inline constexpr double SEA_STATE_RESOLVED_SLOPES = 0.8;

/// Pierson & Moskowitz (1964): fully developed Hs = 0.21 U^2 / g, metres.
double pmSignificantWaveHeight(double windSpeed);
/// Monahan & O'Muircheartaigh (1980): whitecap coverage fraction W = 3.84e-6 U^3.41 (0..1, capped at 1).
double monahanWhitecapCoverage(double windSpeed);
/// Cox & Munk (1954): total mean-square slope s^2 = 0.003 + 5.12e-3 U.
double coxMunkSlopeVariance(double windSpeed);
/// The middle of the WMO Beaufort force's wind range, m/s (force 0..12; std::invalid_argument otherwise).
double beaufortWindSpeed(int force);

/// Mean of the height-foam coverage clamp((h - h0) / (h1 - h0), 0, 1) (Lighting.h foamAlpha) over a
/// Gaussian sea of RMS height sigma: closed form from the normal pdf phi and cdf Phi (a quick estimate; a
/// sum of few waves has lighter tails, so applySeaState() samples the model instead).
double gaussianFoamCoverage(double sigma, double h0, double h1);

/// desc with the sea state applied: FFT wind speed and direction; octave and Gerstner heights scaled by
/// pmSignificantWaveHeight(U) / pmSignificantWaveHeight(SEA_STATE_REFERENCE_WIND) and their wind direction;
/// foam thresholds h0, h1 = h0 + Hs / 4 (the model's Hs) with h0 solved so the mean foamAlpha over the
/// model's heights (sampled on the CPU: builds the model once, ~0.1-0.5 s) equals monahanWhitecapCoverage(U).
/// lighting.microSlopeVariance = max(MIN_MICRO_SLOPE_VARIANCE, coxMunkSlopeVariance(U) - the model's
/// sampled slope variance). Throws std::invalid_argument naming the field for a bad SeaState.
OceanDesc applySeaState(OceanDesc desc, const SeaState& sea);

} // namespace pacifica::ocean
