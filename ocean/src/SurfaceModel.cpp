// SurfaceModel: the shared Eulerian height query (inverse of the horizontal displacement).
#include "ocean/SurfaceModel.h"

#include "ocean/OceanConstants.h"

#include "Eulerian.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pacifica::ocean {

const char* toString(SurfaceKind kind) {
    switch (kind) {
    case SurfaceKind::Octaves:
        return "octaves";
    case SurfaceKind::Gerstner:
        return "gerstner";
    case SurfaceKind::Fft:
        return "fft";
    }
    return "?";
}

int64_t foamStepIndex(double t) {
    if (!std::isfinite(t))
        throw std::invalid_argument("foamStepIndex(): time must be finite");
    return static_cast<int64_t>(std::floor(t / FOAM_MEMORY_STEP));
}

double foamStepTime(int64_t j) {
    return static_cast<double>(j) * FOAM_MEMORY_STEP;
}

glm::dvec3 aperiodicMixTerm(double tile, int set, int j) {
    const double twoPi = 2.0 * std::numbers::pi;
    const double k = twoPi / (FFT_MIX_WAVELENGTHS[j] * tile);
    const double a = FFT_MIX_DIRECTIONS_DEG[j] * std::numbers::pi / 180.0;
    // Phases from the golden ratio's fractional parts, a different set per tiled field.
    const double phase = twoPi * std::fmod(0.5 + 0.6180339887498949 * (j + FFT_MIX_TERMS * set), 1.0);
    return {k * std::sin(a), k * std::cos(a), phase};
}

glm::dvec2 aperiodicMixWeights(double tile, int set, const glm::dvec2& xy) {
    double theta = 0.0;
    for (int j = 0; j < FFT_MIX_TERMS; ++j) {
        const glm::dvec3 m = aperiodicMixTerm(tile, set, j);
        theta += std::sin(m.x * xy.x + m.y * xy.y + m.z); // the argument's rounding: ~1e-16 of it
    }
    theta *= FFT_MIX_AMPLITUDE;
    return {std::cos(theta), std::sin(theta)};
}

double SurfaceModel::heightAt(const glm::dvec2& xy, double t) const {
    return eulerianHeight([&](const glm::dvec2& p) { return displacementAt(p, t); }, xy);
}

void SurfaceModel::heightsAt(const std::vector<glm::dvec2>& points, double t,
                             std::vector<double>& out) const {
    out.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i)
        out[i] = heightAt(points[i], t);
}

} // namespace pacifica::ocean
