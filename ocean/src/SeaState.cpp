// SeaState: the wind speed -> wave height, whitecaps and slopes (SeaState.h).
#include "ocean/SeaState.h"
#include "ocean/OceanHost.h"

#include "ocean/GerstnerWaves.h"
#include "ocean/HeightOctaves.h"
#include "ocean/Lighting.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pacifica::ocean {

namespace {
constexpr double G = 9.81;
double phi(double x) {
    return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi);
}
double Phi(double x) {
    return 0.5 * std::erfc(-x / std::sqrt(2.0));
}
} // namespace

double pmSignificantWaveHeight(double u) {
    return 0.21 * u * u / G;
}

double monahanWhitecapCoverage(double u) {
    return std::min(1.0, 3.84e-6 * std::pow(u, 3.41));
}

double coxMunkSlopeVariance(double u) {
    return 0.003 + 5.12e-3 * u;
}

double beaufortWindSpeed(int force) {
    // WMO Beaufort scale, m/s at 10 m: lower bounds of forces 0..12 (and 32.7 as force 12's upper end).
    static constexpr double LOWER[] = {0.0,  0.5,  1.6,  3.4,  5.5,  8.0, 10.8,
                                       13.9, 17.2, 20.8, 24.5, 28.5, 32.7};
    if (force < 0 || force > 12)
        throw std::invalid_argument("beaufortWindSpeed(): force must be in [0, 12], got " +
                                    std::to_string(force));
    if (force == 12)
        return 32.7;
    return 0.5 * (LOWER[force] + LOWER[force + 1]);
}

double gaussianFoamCoverage(double sigma, double h0, double h1) {
    if (sigma <= 0.0)
        return h0 <= 0.0 ? 1.0 : 0.0;
    const double a = h0 / sigma, b = h1 / sigma;
    if (h1 <= h0)
        return 1.0 - Phi(a);
    // E[clamp((h - h0) / (h1 - h0))] = (sigma (phi(a) - phi(b)) - h0 (Phi(b) - Phi(a))) / (h1 - h0) + 1 -
    // Phi(b)
    return (sigma * (phi(a) - phi(b)) - h0 * (Phi(b) - Phi(a))) / (h1 - h0) + 1.0 - Phi(b);
}

namespace {

constexpr double PHI3 = 1.22074408460575947536;

/// Point n of the R3 low-discrepancy sequence over 5 km x 5 km (Roberts 2018: fractional parts of n / phi3^k,
/// phi3 = 1.2207.., k = 1..3): a lattice would alias with the octaves' tile periods.
glm::dvec2 r3Point(int n) {
    return {5000.0 * std::fmod(0.5 + n / PHI3, 1.0), 5000.0 * std::fmod(0.5 + n / (PHI3 * PHI3), 1.0)};
}

/// The octave sea's short waves: detail octaves continue the tile ratio down to ~16 cm (amplitude in
/// proportion to the tile, the saturation range's equal slope per octave: Phillips 1958), so that near the
/// camera the sun meets resolved facets (glints) and only far away the BRDF (resolveOctaveSlopes).
void addDetailOctaves(HeightOctavesDesc& d) {
    auto& oct = d.octaves;
    while (!oct.empty() && static_cast<int>(oct.size()) < SEA_STATE_OCTAVES &&
           oct.back().tileSize / SEA_STATE_DETAIL_RATIO >= SEA_STATE_FINEST_TILE) {
        OctaveDesc o = oct.back();
        o.tileSize /= SEA_STATE_DETAIL_RATIO;
        o.amplitude /= SEA_STATE_DETAIL_RATIO;
        o.loopPeriod = std::max(1.0, o.loopPeriod / 2.0);
        oct.push_back(o);
    }
}

/// Foam thresholds (h0, h1): h1 = h0 + sigma (the model's RMS height), h0 by bisection so the share of the
/// sea the rendered foam covers, over the model's own foam heights (foamHeightAt: the octaves' remembered
/// crests), equals Monahan's W at wind u. Fewer points for the FFT, whose CPU evaluation sums every mode.
/// (The heights are not Gaussian: a sum of few waves has lighter tails, which decide the coverage of a
/// light sea.)
std::pair<double, double> foamThresholds(const SurfaceModel& surface, bool fft, double u) {
    const double sigma = surface.significantWaveHeight() / 4.0;
    // Points and times of the R3 sequence over 5 km x 5 km x 100 s (a few fixed times would alias with
    // the octaves' loops; a light sea's foam is rare crests, so both matter). The FFT shares its costly
    // per-point sum over 16 times a point (FftOcean::foamHeightsAt), spread over the 100 s by the point's
    // R3 time plus k/16 of it: a light sea's whitecaps are rare, and 768 single samples left the coverage
    // at 8 m/s 1.75x Monahan's (about 3 samples above the threshold).
    const int count = fft ? 768 : 24000, timesPerPoint = fft ? 16 : 1;
    std::vector<double> heights;
    for (int n = 0; n < count; ++n) {
        std::vector<double> times;
        for (int k = 0; k < timesPerPoint; ++k)
            times.push_back(100.0 *
                            std::fmod(0.5 + n / (PHI3 * PHI3 * PHI3) + double(k) / timesPerPoint, 1.0));
        for (double h : surface.foamHeightsAt(r3Point(n), times))
            heights.push_back(h);
    }
    // The share of the sea the rendered foam covers: the pattern thresholded by the coverage.
    auto coverage = [&](double h0) {
        double sum = 0.0;
        for (double h : heights)
            sum += meanFoamOpacity(std::clamp((h - h0) / sigma, 0.0, 1.0));
        return sum / static_cast<double>(heights.size());
    };
    const double target = monahanWhitecapCoverage(u);
    double lo = -4.0 * sigma, hi = 8.0 * sigma;
    for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (lo + hi);
        (coverage(mid) > target ? lo : hi) = mid;
    }
    return {0.5 * (lo + hi), 0.5 * (lo + hi) + sigma};
}

/// The model's slope variance from its normals at `count` R3 points and three times.
double sampledSlopeVariance(const SurfaceModel& surface, int count) {
    double sx = 0.0, sy = 0.0, sxx = 0.0;
    for (int n = 0; n < count; ++n) {
        const glm::dvec3 nrm = surface.normalAt(r3Point(n), 7.9 * (n % 3));
        const double gx = -nrm.x / nrm.z, gy = -nrm.y / nrm.z;
        sx += gx;
        sy += gy;
        sxx += gx * gx + gy * gy;
    }
    return sxx / count - (sx * sx + sy * sy) / (double(count) * count);
}

/// The octave sea: its lighting-only octaves carry SEA_STATE_RESOLVED_SLOPES of Cox & Munk's total at wind u
/// (the geometry-to-BRDF split of Bruneton, Neyret & Holzschuch 2010, sec. 4: what a pixel resolves is
/// facets, the rest its BRDF, here through the octaves' LEAN moments). Each octave's slope variance is taken
/// as the GPU lights it (HeightOctaves::octaveSlopeVariance: over its texels); octaves are uncorrelated, so
/// the model's variance is the displaced octaves' D plus the lighting octaves' L, and L scales with the
/// square of a common amplitude factor c: D + c^2 L = the resolved share of the total. Scales `d`'s
/// lighting octaves and returns the model's slope variance.
double resolveOctaveSlopes(HeightOctavesDesc& d, const HeightOctaves& octaves, double u) {
    const int octaveCount = static_cast<int>(d.octaves.size());
    double displaced = 0.0, lighting = 0.0;
    for (int i = 0; i < octaveCount; ++i)
        (i < d.displacedOctaves ? displaced : lighting) += octaves.octaveSlopeVariance(i);
    if (lighting <= 0.0)
        return displaced;
    const double resolved = SEA_STATE_RESOLVED_SLOPES * coxMunkSlopeVariance(u);
    const double c = std::sqrt(std::max(resolved - displaced, 0.0) / lighting);
    for (int i = d.displacedOctaves; i < octaveCount; ++i)
        d.octaves[static_cast<size_t>(i)].amplitude *= c;
    return displaced + c * c * lighting;
}

} // namespace

OceanDesc applySeaState(OceanDesc d, const SeaState& sea) {
    if (!(std::isfinite(sea.windSpeed) && sea.windSpeed >= SEA_STATE_MIN_WIND &&
          sea.windSpeed <= SEA_STATE_MAX_WIND))
        throw std::invalid_argument("SeaState.windSpeed must be in [1, 30] m/s, got " +
                                    std::to_string(sea.windSpeed));
    if (!std::isfinite(sea.windDirectionDeg))
        throw std::invalid_argument("SeaState.windDirectionDeg must be finite");
    const double u = sea.windSpeed;
    const double scale = pmSignificantWaveHeight(u) / pmSignificantWaveHeight(SEA_STATE_REFERENCE_WIND);
    if (d.model == SurfaceKind::Octaves)
        addDetailOctaves(d.octaves);
    d.fft.windSpeed = u;
    d.fft.windDirectionDeg = sea.windDirectionDeg;
    d.octaves.windDirectionDeg = sea.windDirectionDeg;
    d.lighting.windDirectionDeg = sea.windDirectionDeg;
    for (OctaveDesc& o : d.octaves.octaves)
        o.amplitude *= scale;
    if (d.gerstner.waves.empty())
        d.gerstner.waves = GerstnerWaves::defaultWaves(8, sea.windDirectionDeg, d.gerstner.seed);
    for (GerstnerWave& w : d.gerstner.waves)
        w.amplitude *= scale;
    const OceanComponent built = makeOcean(d);
    const auto [h0, h1] = foamThresholds(*built.surface, d.model == SurfaceKind::Fft, u);
    // Slopes: Cox & Munk's total minus the model's own, at least a floor for the capillaries no model holds.
    const auto* octaves = dynamic_cast<const HeightOctaves*>(built.surface.get());
    const double modelSlopes =
        d.model == SurfaceKind::Octaves && octaves
            ? resolveOctaveSlopes(d.octaves, *octaves, u)
            : sampledSlopeVariance(*built.surface, d.model == SurfaceKind::Fft ? 256 : 2000);
    d.lighting.microSlopeVariance =
        static_cast<float>(std::max(MIN_MICRO_SLOPE_VARIANCE, coxMunkSlopeVariance(u) - modelSlopes));
    d.lighting.foamHeightStart = static_cast<float>(h0);
    d.lighting.foamHeightFull = static_cast<float>(h1);
    return d;
}

} // namespace pacifica::ocean
