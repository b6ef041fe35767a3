// GerstnerWaves: the Gerstner-sum surface in double precision — validation and the steepness limit, the
// default wind sea, displacement, exact normals and Jacobian, and the per-wave phase offsets and distance
// fade the GLSL twin (ocean/shaders/gerstner.glsl) uses. Formulas: Finch, GPU Gems 1 ch.1 eq. 9-12;
// Tessendorf 2001 §3.1 (Gerstner waves) and §4.4 (the Jacobian and folding).
#include "ocean/GerstnerWaves.h"

#include "engine/Log.h"
#include "engine/Time.h"
#include "ocean/OceanConstants.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace pacifica::ocean {
namespace {

constexpr double TWO_PI = 2.0 * std::numbers::pi;

/// "%.9g" (std::to_string prints 1e-9 as 0.000000).
std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

void require(bool ok, const std::string& message) {
    if (!ok)
        throw std::invalid_argument(message);
}

/// Uniform in [0, 1) from the top 53 bits of one mt19937_64 draw. std::mt19937_64's sequence is fixed by
/// the standard; std::uniform_real_distribution's mapping is not, so it is done here.
double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

} // namespace

glm::dvec2 GerstnerWaves::direction(const GerstnerWave& wave) {
    // Compass degrees (clockwise from north) in the ENU frame: 0 -> +y (north), 90 -> +x (east).
    const double rad = wave.directionDeg * (std::numbers::pi / 180.0);
    return {std::sin(rad), std::cos(rad)};
}

double GerstnerWaves::wavenumber(const GerstnerWave& wave) {
    return TWO_PI / wave.wavelength;
}

std::vector<GerstnerWave> GerstnerWaves::defaultWaves(int count, double windDirectionDeg, uint32_t seed) {
    require(count >= 1 && count <= MAX_WAVES, "GerstnerWaves::defaultWaves(): count must be in [1, " +
                                                  std::to_string(MAX_WAVES) + "], got " +
                                                  std::to_string(count));
    require(std::isfinite(windDirectionDeg),
            "GerstnerWaves::defaultWaves(): windDirectionDeg must be finite, got " + num(windDirectionDeg));
    std::mt19937_64 rng(seed);
    std::vector<GerstnerWave> waves(static_cast<size_t>(count));
    for (int i = 0; i < count; ++i) {
        GerstnerWave& w = waves[static_cast<size_t>(i)];
        // Wavelengths log-spaced from 120 m down to 8 m, each jittered by up to +-10%.
        const double u = count > 1 ? double(i) / double(count - 1) : 0.5;
        w.wavelength = 120.0 * std::pow(8.0 / 120.0, u) * (0.9 + 0.2 * uniform01(rng));
        // Equal wave slope k A per log-wavelength band (Phillips' saturation range): the short waves are as
        // steep as the long ones and much lower. k A in [0.015, 0.025] gives Hs 1.1-1.9 m for 8 waves.
        const double slope = 0.015 + 0.010 * uniform01(rng);
        w.amplitude = slope * w.wavelength / TWO_PI;
        w.directionDeg = wrapPhase(windDirectionDeg + 40.0 * (2.0 * uniform01(rng) - 1.0), 360.0);
        w.steepness = 0.5 + 0.5 * uniform01(rng);
        w.phase = TWO_PI * uniform01(rng);
    }
    return waves;
}

GerstnerWaves::GerstnerWaves(const GerstnerDesc& desc) {
    require(std::isfinite(desc.steepnessScale) && desc.steepnessScale >= 0.0,
            "GerstnerDesc.steepnessScale must be finite and >= 0, got " + num(desc.steepnessScale));
    require(desc.waves.size() <= static_cast<size_t>(MAX_WAVES),
            "GerstnerDesc.waves must hold at most " + std::to_string(MAX_WAVES) + " waves, got " +
                std::to_string(desc.waves.size()));
    mWaves = desc.waves.empty() ? defaultWaves(8, 60.0, desc.seed) : desc.waves;
    mFoamMemory = desc.foamMemory;
    for (size_t i = 0; i < mWaves.size(); ++i) {
        const GerstnerWave& w = mWaves[i];
        const std::string field = "GerstnerDesc.waves[" + std::to_string(i) + "].";
        require(std::isfinite(w.amplitude) && w.amplitude >= 0.0,
                field + "amplitude must be finite and >= 0, got " + num(w.amplitude));
        require(std::isfinite(w.wavelength) && w.wavelength > 0.0,
                field + "wavelength must be finite and > 0, got " + num(w.wavelength));
        require(std::isfinite(w.directionDeg),
                field + "directionDeg must be finite, got " + num(w.directionDeg));
        require(std::isfinite(w.steepness) && w.steepness >= 0.0 && w.steepness <= 1.0,
                field + "steepness must be finite and in [0, 1], got " + num(w.steepness));
        require(std::isfinite(w.phase), field + "phase must be finite, got " + num(w.phase));
    }

    // The steepness limit: with Q_i the scaled requests, the horizontal map's Jacobian is
    // I - sum_i Q_i k_i A_i sin(theta_i) D_i D_i^T, whose eigenvalues stay >= 1 - sum_i Q_i k_i A_i, so the
    // surface cannot fold while the sum is <= 1 (Tessendorf 2001 §4.4; the per-wave form Q_i <= 1/(k_i A_i)
    // is GPU Gems 1 ch.1 §1.2.4). Above it, every Q_i is scaled by the same factor 1/S.
    mTerms.resize(mWaves.size());
    double sum = 0.0;
    for (size_t i = 0; i < mWaves.size(); ++i) {
        GerstnerWave& w = mWaves[i];
        Terms& t = mTerms[i];
        t.dir = direction(w);
        t.k = wavenumber(w);
        t.omega = std::sqrt(GRAVITY * t.k); // deep water, w^2 = g k
        t.amplitude = w.amplitude;
        t.wavelength = w.wavelength;
        t.phase = w.phase;
        w.steepness *= desc.steepnessScale;
        sum += w.steepness * t.k * w.amplitude;
    }
    mRequestedSum = sum;
    mClampFactor = sum > 1.0 ? 1.0 / sum : 1.0;
    double applied = 0.0;
    for (size_t i = 0; i < mWaves.size(); ++i) {
        mWaves[i].steepness *= mClampFactor;
        mTerms[i].q = mWaves[i].steepness;
        applied += mTerms[i].q * mTerms[i].k * mTerms[i].amplitude;
    }
    if (mClampFactor != 1.0)
        logWarning("GerstnerWaves: requested steepness sum sum_i Q_i k_i A_i = " + num(sum) +
                   " > 1 would fold the surface; every Q_i scaled by " + num(mClampFactor) +
                   ", applied sum = " + num(applied));
}

double GerstnerWaves::fade(double distance, double fadeEnd) {
    const double s = std::clamp((fadeEnd - distance) / (0.5 * fadeEnd), 0.0, 1.0);
    return s * s * (3.0 - 2.0 * s);
}

namespace {

/// Calls f(wave, A_i (faded), theta_i) for every wave with a non-zero amplitude at grid point xy, time t:
/// theta_i = k_i D_i . xy - w_i t + phi_i (GPU Gems 1 ch.1 eq. 9's phase).
template <class Terms, class F>
void forEachWave(const Terms& terms, const glm::dvec2& xy, double t, const double* fades, F&& f) {
    for (size_t i = 0; i < terms.size(); ++i) {
        const auto& w = terms[i];
        const double a = fades ? w.amplitude * fades[i] : w.amplitude;
        if (a != 0.0)
            f(w, a, w.k * glm::dot(w.dir, xy) - w.omega * t + w.phase);
    }
}

/// Wave w's term of eq. 9 (amplitude a, cos and sin of its phase) added to d.
template <class Wave>
void addDisplacement(const Wave& w, double a, double c, double sn, glm::dvec3& d) {
    d.x += w.q * a * c * w.dir.x;
    d.y += w.q * a * c * w.dir.y;
    d.z += a * sn;
}

/// Wave w's term of -grad (dx, dy) = sum Q A k sin theta D D^T added to s = (sxx, sxy, syy).
template <class Wave>
void addHorizontalJacobian(const Wave& w, double a, double sn, glm::dvec3& s) {
    const double qaks = w.q * a * w.k * sn;
    s.x += qaks * w.dir.x * w.dir.x;
    s.y += qaks * w.dir.x * w.dir.y;
    s.z += qaks * w.dir.y * w.dir.y;
}

} // namespace

glm::dvec3 GerstnerWaves::displacement(const glm::dvec2& xy, double t, const double* fades) const {
    // GPU Gems 1 ch.1 eq. 9: (sum Q_i A_i D_i cos theta_i, sum A_i sin theta_i).
    glm::dvec3 d(0.0);
    forEachWave(mTerms, xy, t, fades, [&](const Terms& w, double a, double theta) {
        addDisplacement(w, a, std::cos(theta), std::sin(theta), d);
    });
    return d;
}

void GerstnerWaves::jacobianTerms(const glm::dvec2& xy, double t, const double* fades, glm::dvec3& s,
                                  glm::dvec2& gradZ) const {
    // Derivatives of eq. 9 with respect to the grid point x: d/dx [Q A D cos theta] = -Q A k sin theta D D^T
    // and d/dx [A sin theta] = A k cos theta D (GPU Gems 1 ch.1 eq. 10-11 are the columns of this).
    s = glm::dvec3(0.0);
    gradZ = glm::dvec2(0.0);
    forEachWave(mTerms, xy, t, fades, [&](const Terms& w, double a, double theta) {
        addHorizontalJacobian(w, a, std::sin(theta), s);
        gradZ += (a * w.k * std::cos(theta)) * w.dir;
    });
}

bool GerstnerWaves::displacementAndGradient(const glm::dvec2& xy, double t, glm::dvec3& d,
                                            glm::dmat2& grad) const {
    // displacement(xy, t, nullptr) (the same sums in the same order, so the same bits) and the horizontal
    // block of jacobianTerms(): d/dx [Q A D cos theta] = -Q A k sin theta D D^T.
    d = glm::dvec3(0.0);
    glm::dvec3 s(0.0);
    forEachWave(mTerms, xy, t, nullptr, [&](const Terms& w, double a, double theta) {
        const double sn = std::sin(theta);
        addDisplacement(w, a, std::cos(theta), sn, d);
        addHorizontalJacobian(w, a, sn, s);
    });
    grad = glm::dmat2(-s.x, -s.y, -s.y, -s.z); // columns d/dx, d/dy of (dx, dy)
    return true;
}

glm::dvec3 GerstnerWaves::displacementAt(const glm::dvec2& xy, double t) const {
    return displacement(xy, t, nullptr);
}

glm::dvec3 GerstnerWaves::normalAt(const glm::dvec2& xy, double t) const {
    // The tangents of the displaced surface along the grid axes are the binormal B (eq. 10) and tangent T
    // (eq. 11) of GPU Gems 1 ch.1; the normal is B x T. Finch's eq. 12 expands that cross product but drops
    // the products of terms of different waves (an O((Q k A)^2) error, ~1e-2 for steep seas, and evaluates
    // at the displaced point); here the cross product is taken exactly, so N.z is the Jacobian.
    glm::dvec3 s;
    glm::dvec2 g;
    jacobianTerms(xy, t, nullptr, s, g);
    const glm::dvec3 b(1.0 - s.x, -s.y, g.x);
    const glm::dvec3 tg(-s.y, 1.0 - s.z, g.y);
    return glm::normalize(glm::cross(b, tg));
}

double GerstnerWaves::jacobianAt(const glm::dvec2& xy, double t) const {
    // det(I - sum_i Q_i A_i k_i sin(theta_i) D_i D_i^T) (Tessendorf 2001 §4.4).
    glm::dvec3 s;
    glm::dvec2 g;
    jacobianTerms(xy, t, nullptr, s, g);
    return (1.0 - s.x) * (1.0 - s.z) - s.y * s.y;
}

double GerstnerWaves::significantWaveHeight() const {
    // Hs = 4 sigma_h; a sinusoid of amplitude A has variance A^2 / 2, independent waves add.
    double var = 0.0;
    for (const Terms& w : mTerms)
        var += 0.5 * w.amplitude * w.amplitude;
    return 4.0 * std::sqrt(var);
}

std::vector<float> GerstnerWaves::phaseOffsets(const glm::dvec2& cameraXY, double t) const {
    std::vector<float> out(mTerms.size());
    for (size_t i = 0; i < mTerms.size(); ++i) {
        const Terms& w = mTerms[i];
        const double theta0 = wrapPhase(w.k * glm::dot(w.dir, cameraXY) - w.omega * t + w.phase, TWO_PI);
        const float f = static_cast<float>(theta0);
        // float(theta0) may round up to float(2 pi) > 2 pi; 0 is the same phase (within half a float ulp).
        out[i] = static_cast<double>(f) < TWO_PI ? f : 0.0f;
    }
    return out;
}

glm::dvec3 GerstnerWaves::displacementSeenFrom(const glm::dvec2& xy, double t,
                                               const glm::dvec2& cameraXY) const {
    const double r = glm::length(xy - cameraXY);
    double fades[MAX_WAVES];
    for (size_t i = 0; i < mTerms.size(); ++i)
        fades[i] = fade(r, DISPLACEMENT_FADE_WAVELENGTHS * mTerms[i].wavelength);
    return displacement(xy, t, fades);
}

glm::dvec3 GerstnerWaves::lightingSeenFrom(const glm::dvec2& xy, double t, const glm::dvec2& cameraXY) const {
    const double r = glm::length(xy - cameraXY);
    double fades[MAX_WAVES];
    double variance = 0.0;
    for (size_t i = 0; i < mTerms.size(); ++i) {
        const Terms& w = mTerms[i];
        fades[i] = fade(r, LIGHTING_FADE_WAVELENGTHS * w.wavelength);
        const double lostSlope = (1.0 - fades[i]) * w.k * w.amplitude;
        variance += 0.5 * lostSlope * lostSlope;
    }
    glm::dvec3 s;
    glm::dvec2 g;
    jacobianTerms(xy, t, fades, s, g);
    // Eulerian slope at the image of xy: grad_x H = J^-T grad_x0 z, J^-1 = adj(J) / det J (J symmetric).
    const double det = std::max((1.0 - s.x) * (1.0 - s.z) - s.y * s.y, MIN_LIGHTING_JACOBIAN);
    return {((1.0 - s.z) * g.x + s.y * g.y) / det, (s.y * g.x + (1.0 - s.x) * g.y) / det, variance};
}

glm::dvec2 GerstnerWaves::foamInputsSeenFrom(const glm::dvec2& xy, double t,
                                             const glm::dvec2& cameraXY) const {
    const double r = glm::length(xy - cameraXY);
    double fades[MAX_WAVES];
    for (size_t i = 0; i < mTerms.size(); ++i)
        fades[i] = fade(r, DISPLACEMENT_FADE_WAVELENGTHS * mTerms[i].wavelength);
    glm::dvec3 s;
    glm::dvec2 g;
    jacobianTerms(xy, t, fades, s, g);
    const double h = mFoamMemory ? rememberedHeight(xy, t, fades) : displacement(xy, t, fades).z;
    return {h, (1.0 - s.x) * (1.0 - s.z) - s.y * s.y};
}

double GerstnerWaves::foamHeightAt(const glm::dvec2& xy, double t) const {
    return mFoamMemory ? rememberedHeight(xy, t, nullptr) : displacement(xy, t, nullptr).z;
}

double GerstnerWaves::rememberedHeight(const glm::dvec2& xy, double t, const double* fades) const {
    const int64_t j = foamStepIndex(t);
    double memory = 0.0;
    for (int k = 0; k < FOAM_MEMORY_WINDOW; ++k)
        memory = std::max(memory, std::exp(-k * FOAM_MEMORY_STEP / FOAM_DECAY_TIME) *
                                      std::max(displacement(xy, foamStepTime(j - k), fades).z, 0.0));
    const double decay = std::exp(-(t - foamStepTime(j)) / FOAM_DECAY_TIME);
    return std::max(displacement(xy, t, fades).z, decay * memory);
}

} // namespace pacifica::ocean
