// Unit tests of the Gerstner-sum surface (GerstnerWaves, GPU Gems 1 ch.1 eq. 9): the closed form of one
// wave, the steepness limit (a request of 3 is clamped to exactly 1 and never folds), exact normals against
// finite differences, Eulerian heights, Hs, huge times and far positions, the distance fade, the default
// sea and the validation messages.
#include "engine/Log.h"
#include "ocean/GerstnerWaves.h"
#include "ocean/OceanConstants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <numbers>
#include <string>
#include <vector>

using namespace pacifica::ocean;

namespace {

constexpr double PI = std::numbers::pi;

GerstnerWave wave(double amplitude, double wavelength, double directionDeg, double steepness, double phase) {
    GerstnerWave w;
    w.amplitude = amplitude;
    w.wavelength = wavelength;
    w.directionDeg = directionDeg;
    w.steepness = steepness;
    w.phase = phase;
    return w;
}

/// Eight waves in eight directions with steepness q and equal wave slopes k A = sum / 8 (so that
/// sum_i Q_i k_i A_i = q * sum).
std::vector<GerstnerWave> crossedSea(double q, double slopeSum) {
    std::vector<GerstnerWave> waves;
    const double wavelengths[8] = {90.0, 71.0, 55.5, 43.0, 34.7, 27.1, 21.9, 17.3};
    for (int i = 0; i < 8; ++i) {
        const double L = wavelengths[i];
        waves.push_back(wave(slopeSum / 8.0 * L / (2.0 * PI), L, 12.0 + 47.0 * i, q, 0.7 * i));
    }
    return waves;
}

/// A small deterministic pseudo-random sequence in [0, 1) for sample points (a fixed LCG).
struct Lcg {
    uint64_t s = 12345;
    double next() {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(s >> 11) * 0x1.0p-53;
    }
};

/// min det J over an n x n grid covering [-half, half]^2 at each time.
double minJacobian(const GerstnerWaves& s, double half, int n, std::initializer_list<double> times) {
    double m = 1e300;
    for (double t : times)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const glm::dvec2 p(-half + 2.0 * half * i / (n - 1), -half + 2.0 * half * j / (n - 1));
                m = std::min(m, s.jacobianAt(p, t));
            }
    return m;
}

/// det J of the sum with the given steepnesses, computed here (to show what an unclamped request does).
double handJacobian(const std::vector<GerstnerWave>& waves, const glm::dvec2& p, double t) {
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (const GerstnerWave& w : waves) {
        const glm::dvec2 d = GerstnerWaves::direction(w);
        const double k = 2.0 * PI / w.wavelength;
        const double theta = k * glm::dot(d, p) - std::sqrt(GRAVITY * k) * t + w.phase;
        const double qaks = w.steepness * w.amplitude * k * std::sin(theta);
        sxx += qaks * d.x * d.x;
        sxy += qaks * d.x * d.y;
        syy += qaks * d.y * d.y;
    }
    return (1.0 - sxx) * (1.0 - syy) - sxy * sxy;
}

/// Collects warnings while alive.
struct LogCapture {
    std::vector<std::string> warnings;
    LogCapture() {
        pacifica::setLogSink([this](pacifica::LogLevel level, std::string_view m) {
            if (level == pacifica::LogLevel::Warning)
                warnings.emplace_back(m);
        });
    }
    ~LogCapture() { pacifica::setLogSink(nullptr); }
};

glm::dvec3 displacedPoint(const GerstnerWaves& s, const glm::dvec2& p, double t) {
    const glm::dvec3 d = s.displacementAt(p, t);
    return {p.x + d.x, p.y + d.y, d.z};
}

} // namespace

TEST(GerstnerWaves, SingleWaveMatchesClosedForm) {
    // East-going wave: D = (1, 0), k = 2 pi / 50, w = sqrt(g k).
    const GerstnerWaves s(GerstnerDesc{.waves = {wave(0.8, 50.0, 90.0, 0.6, 0.0)}});
    const double k = 2.0 * PI / 50.0, w = std::sqrt(GRAVITY * k);
    // theta = 0 at the origin: all horizontal, Q A forward.
    glm::dvec3 d = s.displacementAt({0.0, 0.0}, 0.0);
    EXPECT_NEAR(d.x, 0.48, 1e-12);
    EXPECT_NEAR(d.y, 0.0, 1e-12);
    EXPECT_NEAR(d.z, 0.0, 1e-12);
    // A quarter wavelength on: the crest, A up, no horizontal excursion.
    d = s.displacementAt({12.5, 3.0}, 0.0);
    EXPECT_NEAR(d.x, 0.0, 1e-12);
    EXPECT_NEAR(d.z, 0.8, 1e-12);
    // Half a period later at the origin: theta = -pi, Q A backward.
    d = s.displacementAt({0.0, 0.0}, PI / w);
    EXPECT_NEAR(d.x, -0.48, 1e-12);
    EXPECT_NEAR(d.z, 0.0, 1e-12);
    // The crest moves at the deep-water phase speed c = sqrt(g L / (2 pi)) = 8.8355 m/s.
    const double c = std::sqrt(GRAVITY * 50.0 / (2.0 * PI));
    EXPECT_NEAR(c, 8.8355, 1e-4);
    EXPECT_NEAR(s.displacementAt({12.5 + c * 7.0, 0.0}, 7.0).z, 0.8, 1e-12);

    // Compass 30 degrees (clockwise from north): D = (sin 30, cos 30), with a phase; general points.
    const GerstnerWaves s2(GerstnerDesc{.waves = {wave(0.35, 20.0, 30.0, 0.9, 0.4)}});
    const double k2 = 2.0 * PI / 20.0, w2 = std::sqrt(GRAVITY * k2);
    const glm::dvec2 dir(0.5, std::sqrt(3.0) / 2.0);
    for (const glm::dvec3 pt :
         {glm::dvec3(3.0, -7.0, 0.0), glm::dvec3(-120.5, 44.25, 13.7), glm::dvec3(1000.0, 1000.0, 99.9)}) {
        const double theta = k2 * (dir.x * pt.x + dir.y * pt.y) - w2 * pt.z + 0.4;
        const glm::dvec3 got = s2.displacementAt({pt.x, pt.y}, pt.z);
        EXPECT_NEAR(got.x, 0.9 * 0.35 * dir.x * std::cos(theta), 1e-12);
        EXPECT_NEAR(got.y, 0.9 * 0.35 * dir.y * std::cos(theta), 1e-12);
        EXPECT_NEAR(got.z, 0.35 * std::sin(theta), 1e-12);
        // One wave: J = 1 - Q k A sin(theta) exactly, and the normal is eq. 12's.
        EXPECT_NEAR(s2.jacobianAt({pt.x, pt.y}, pt.z), 1.0 - 0.9 * k2 * 0.35 * std::sin(theta), 1e-12);
        const glm::dvec3 n = s2.normalAt({pt.x, pt.y}, pt.z);
        const glm::dvec3 expected = glm::normalize(
            glm::dvec3(-dir * (k2 * 0.35 * std::cos(theta)), 1.0 - 0.9 * k2 * 0.35 * std::sin(theta)));
        EXPECT_NEAR(glm::length(n - expected), 0.0, 1e-12);
    }
    EXPECT_EQ(s2.kind(), SurfaceKind::Gerstner);
}

TEST(GerstnerWaves, SteepnessRequestOfThreeIsClampedToExactlyOne) {
    const std::vector<GerstnerWave> request = crossedSea(1.0, 3.0); // sum Q k A = 3
    LogCapture log;
    const GerstnerWaves s(GerstnerDesc{.waves = request});
    EXPECT_NEAR(s.requestedSteepnessSum(), 3.0, 1e-12);
    EXPECT_NEAR(s.clampedBy(), 1.0 / 3.0, 1e-15);
    double applied = 0.0;
    for (const GerstnerWave& w : s.waves()) {
        EXPECT_NEAR(w.steepness, 1.0 / 3.0, 1e-15);
        applied += w.steepness * (2.0 * PI / w.wavelength) * w.amplitude;
    }
    EXPECT_NEAR(applied, 1.0, 1e-12);
    ASSERT_EQ(log.warnings.size(), 1u);
    EXPECT_NE(log.warnings[0].find("= 3 > 1"), std::string::npos) << log.warnings[0];
    EXPECT_NE(log.warnings[0].find("applied sum = 1"), std::string::npos) << log.warnings[0];

    // Unclamped, this request folds (det J well below 0 somewhere)...
    double unclampedMin = 1e300;
    for (int j = 0; j < 61; ++j)
        for (int i = 0; i < 61; ++i)
            unclampedMin =
                std::min(unclampedMin, handJacobian(request, {-150.0 + 5.0 * i, -150.0 + 5.0 * j}, 3.0));
    EXPECT_LT(unclampedMin, -0.3);
    // ...clamped it never does (4 times, 201 x 201 points over 300 m).
    EXPECT_GT(minJacobian(s, 150.0, 201, {0.0, 3.0, 11.1, 1234.5}), -1e-9);

    // One wave with Q k A = 3 clamped to 1: J = 1 - sin(theta) touches 0 at the crest — the limit is the
    // limit, not a more conservative value.
    const GerstnerWaves one(GerstnerDesc{.waves = {wave(3.0 * 40.0 / (2.0 * PI), 40.0, 0.0, 1.0, 0.0)}});
    EXPECT_NEAR(one.clampedBy(), 1.0 / 3.0, 1e-15);
    double m = 1e300;
    for (int i = 0; i <= 40000; ++i)
        m = std::min(m, one.jacobianAt({0.0, i * 1e-3}, 0.0));
    EXPECT_GT(m, -1e-9);
    EXPECT_LT(m, 1e-6);
}

TEST(GerstnerWaves, JustBelowTheLimitIsNotClamped) {
    LogCapture log;
    // One wave with k A = 1 and Q = 0.99: min J = 1 - 0.99 = 0.01 at the crest.
    const GerstnerWaves one(GerstnerDesc{.waves = {wave(40.0 / (2.0 * PI), 40.0, 0.0, 0.99, 0.0)}});
    EXPECT_NEAR(one.requestedSteepnessSum(), 0.99, 1e-12);
    EXPECT_EQ(one.clampedBy(), 1.0);
    EXPECT_EQ(one.waves()[0].steepness, 0.99);
    double m = 1e300;
    for (int i = 0; i <= 40000; ++i)
        m = std::min(m, one.jacobianAt({0.0, i * 1e-3}, 0.0));
    EXPECT_NEAR(m, 0.01, 1e-6);
    // Eight crossed waves with the sum 0.99: min J > 0.
    const GerstnerWaves crossed(GerstnerDesc{.waves = crossedSea(0.99, 1.0)});
    EXPECT_NEAR(crossed.requestedSteepnessSum(), 0.99, 1e-12);
    EXPECT_EQ(crossed.clampedBy(), 1.0);
    EXPECT_GT(minJacobian(crossed, 150.0, 201, {0.0, 3.0, 11.1}), 0.0);
    EXPECT_TRUE(log.warnings.empty());
    // steepnessScale multiplies before the limit: 0.3 * 2 = 0.6 per wave, sum 0.6, not clamped.
    const GerstnerWaves scaled(GerstnerDesc{.waves = crossedSea(0.3, 1.0), .steepnessScale = 2.0});
    EXPECT_NEAR(scaled.requestedSteepnessSum(), 0.6, 1e-12);
    EXPECT_EQ(scaled.clampedBy(), 1.0);
    EXPECT_NEAR(scaled.waves()[3].steepness, 0.6, 1e-15);
}

TEST(GerstnerWaves, NormalMatchesFiniteDifferencesOfTheDisplacedSurface) {
    const GerstnerWaves defaultSea;
    const GerstnerWaves steep(GerstnerDesc{.waves = crossedSea(1.0, 0.9)});
    Lcg rng;
    const double h = 1e-3;
    double worstEq12 = 0.0;
    for (const GerstnerWaves* s : {&defaultSea, &steep}) {
        for (int sample = 0; sample < 200; ++sample) {
            const glm::dvec2 p(2000.0 * rng.next() - 1000.0, 2000.0 * rng.next() - 1000.0);
            const double t = 100.0 * rng.next();
            // Central differences on the Lagrangian grid: error ~h^2 k^3 A / 6 < 1e-8, rounding ~1e-10.
            const glm::dvec3 px = (displacedPoint(*s, p + glm::dvec2(h, 0.0), t) -
                                   displacedPoint(*s, p - glm::dvec2(h, 0.0), t)) /
                                  (2.0 * h);
            const glm::dvec3 py = (displacedPoint(*s, p + glm::dvec2(0.0, h), t) -
                                   displacedPoint(*s, p - glm::dvec2(0.0, h), t)) /
                                  (2.0 * h);
            const glm::dvec3 c = glm::cross(px, py);
            const glm::dvec3 n = s->normalAt(p, t);
            ASSERT_LT(glm::length(glm::normalize(c) - n), 1e-6) << "at " << p.x << ", " << p.y << ", t " << t;
            // N.z of the unnormalised cross product is the Jacobian of the horizontal map.
            ASSERT_NEAR(c.z, s->jacobianAt(p, t), 1e-6);
            if (s == &steep) { // Finch's eq. 12, which drops cross-wave products, for comparison
                glm::dvec3 e(0.0, 0.0, 1.0);
                for (const GerstnerWave& w : s->waves()) {
                    const glm::dvec2 d = GerstnerWaves::direction(w);
                    const double k = 2.0 * PI / w.wavelength;
                    const double theta = k * glm::dot(d, p) - std::sqrt(GRAVITY * k) * t + w.phase;
                    e -= glm::dvec3(d * (k * w.amplitude * std::cos(theta)),
                                    w.steepness * k * w.amplitude * std::sin(theta));
                }
                worstEq12 = std::max(worstEq12, glm::length(glm::normalize(e) - n));
            }
        }
    }
    // The test can tell the exact normal from eq. 12 on a steep sea (cross terms ~(Q k A)^2).
    EXPECT_GT(worstEq12, 1e-3);
}

TEST(GerstnerWaves, HeightAtInvertsTheHorizontalDisplacement) {
    const GerstnerWaves defaultSea;
    const GerstnerWaves moderate(GerstnerDesc{.waves = crossedSea(1.0, 0.3)});
    Lcg rng;
    for (const GerstnerWaves* s : {&defaultSea, &moderate}) {
        double worst = 0.0;
        for (int sample = 0; sample < 300; ++sample) {
            const glm::dvec2 x0(4000.0 * rng.next() - 2000.0, 4000.0 * rng.next() - 2000.0);
            const double t = 500.0 * rng.next();
            const glm::dvec3 d = s->displacementAt(x0, t);
            worst = std::max(worst, std::abs(s->heightAt(x0 + glm::dvec2(d.x, d.y), t) - d.z));
        }
        EXPECT_LT(worst, 1e-6);
    }
}

TEST(GerstnerWaves, SignificantWaveHeight) {
    EXPECT_NEAR(
        GerstnerWaves(GerstnerDesc{.waves = {wave(1.0, 30.0, 0.0, 0.5, 0.0)}}).significantWaveHeight(),
        4.0 / std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(GerstnerWaves(
                    GerstnerDesc{.waves = {wave(1.0, 30.0, 0.0, 0.5, 0.0), wave(2.0, 70.0, 45.0, 0.5, 1.0)}})
                    .significantWaveHeight(),
                4.0 * std::sqrt(2.5), 1e-12);
    // Hs = 4 sigma of the sampled heights of the default sea (incommensurate waves: the spatial average
    // over 4 km converges to within a few per cent).
    const GerstnerWaves s;
    double sum2 = 0.0;
    const int n = 300;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double z = s.displacementAt({-2000.0 + 13.37 * i, -2000.0 + 13.37 * j}, 0.0).z;
            sum2 += z * z;
        }
    EXPECT_NEAR(4.0 * std::sqrt(sum2 / (n * n)) / s.significantWaveHeight(), 1.0, 0.05);
}

TEST(GerstnerWaves, HugeTimesAndFarPositionsStayFiniteAndPrecise) {
    const GerstnerWaves s;
    const double twoPi = 2.0 * PI;
    for (const double t : {0.0, 1e6, 1e9 + 0.123}) {
        for (const glm::dvec2 camera :
             {glm::dvec2(0.0), glm::dvec2(1e7 + 0.37, -1e7 + 0.81), glm::dvec2(-1e7, 3e6)}) {
            const glm::dvec3 d = s.displacementAt(camera, t);
            const glm::dvec3 n = s.normalAt(camera, t);
            const double j = s.jacobianAt(camera, t);
            ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z));
            ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
            EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
            EXPECT_GT(j, 0.0);
            EXPECT_TRUE(std::isfinite(s.heightAt(camera, t)));

            const std::vector<float> theta0 = s.phaseOffsets(camera, t);
            ASSERT_EQ(theta0.size(), s.waves().size());
            for (size_t i = 0; i < theta0.size(); ++i) {
                const GerstnerWave& w = s.waves()[i];
                ASSERT_TRUE(std::isfinite(theta0[i]));
                EXPECT_GE(theta0[i], 0.0f);
                EXPECT_LT(static_cast<double>(theta0[i]), twoPi);
                // The same phase in 80-bit long double: wrapped in double, rounded to float, the offset is
                // within half a float ulp (2.4e-7) plus double rounding of w t (<= 2.5e-7 at 3e9 rad).
                using LD = long double;
                const LD twoPiL = 2.0L * std::numbers::pi_v<LD>;
                const LD kL = twoPiL / w.wavelength;
                const glm::dvec2 dir = GerstnerWaves::direction(w);
                const LD exact = kL * (LD(dir.x) * LD(camera.x) + LD(dir.y) * LD(camera.y)) -
                                 std::sqrt(LD(GRAVITY) * kL) * LD(t) + LD(w.phase);
                LD diff = std::fmod(LD(theta0[i]) - exact, twoPiL);
                if (diff > twoPiL / 2)
                    diff -= twoPiL;
                if (diff < -twoPiL / 2)
                    diff += twoPiL;
                EXPECT_LT(std::abs(static_cast<double>(diff)), 1e-6) << "wave " << i << " t " << t;
            }
            // The GPU's decomposition theta = k D . rel + theta0 (done here in double) reproduces the
            // reference within the float rounding of theta0 (2.4e-7 rad times sum A (1 + Q) ~ 1e-6 m).
            for (const glm::dvec2 rel :
                 {glm::dvec2(0.0), glm::dvec2(37.5, -12.25), glm::dvec2(-100.0, 220.0)}) {
                glm::dvec3 g(0.0);
                for (size_t i = 0; i < theta0.size(); ++i) {
                    const GerstnerWave& w = s.waves()[i];
                    const glm::dvec2 dir = GerstnerWaves::direction(w);
                    const double theta = GerstnerWaves::wavenumber(w) * glm::dot(dir, rel) + theta0[i];
                    g += glm::dvec3(dir * (w.steepness * w.amplitude * std::cos(theta)),
                                    w.amplitude * std::sin(theta));
                }
                EXPECT_LT(glm::length(g - s.displacementAt(camera + rel, t)), 2e-6);
            }
        }
    }
}

TEST(GerstnerWaves, PhaseOffsetThatWouldRoundUpToTwoPiIsZero) {
    // theta0 = nextafter(2 pi, 0) < 2 pi in double, but float(theta0) = 6.2831855 > 2 pi: the same phase as
    // 0.
    const double justBelow = std::nextafter(2.0 * PI, 0.0);
    ASSERT_GT(static_cast<double>(static_cast<float>(justBelow)), 2.0 * PI);
    const GerstnerWaves s(GerstnerDesc{.waves = {wave(0.5, 30.0, 0.0, 0.5, justBelow)}});
    EXPECT_EQ(s.phaseOffsets({0.0, 0.0}, 0.0)[0], 0.0f);
    EXPECT_NEAR(s.phaseOffsets({0.0, 7.5}, 0.0)[0], PI / 2.0, 1e-6); // a quarter wavelength north
}

TEST(GerstnerWaves, DistanceFade) {
    EXPECT_EQ(GerstnerWaves::fade(0.0, 100.0), 1.0);
    EXPECT_EQ(GerstnerWaves::fade(50.0, 100.0), 1.0);
    EXPECT_NEAR(GerstnerWaves::fade(75.0, 100.0), 0.5, 1e-15);
    EXPECT_NEAR(GerstnerWaves::fade(90.0, 100.0), 0.104, 1e-12); // s = 0.2: 0.04 * 2.6
    EXPECT_EQ(GerstnerWaves::fade(100.0, 100.0), 0.0);
    EXPECT_EQ(GerstnerWaves::fade(1e7, 100.0), 0.0);

    const GerstnerWaves s;
    double minL = 1e300, maxL = 0.0, allSlopes = 0.0;
    for (const GerstnerWave& w : s.waves()) {
        minL = std::min(minL, w.wavelength);
        maxL = std::max(maxL, w.wavelength);
        const double ka = GerstnerWaves::wavenumber(w) * w.amplitude;
        allSlopes += 0.5 * ka * ka;
    }
    const glm::dvec2 camera(1e7 + 0.37, -1e7 + 0.81);
    const double t = 1e6;
    // Within half the shortest wave's fade distance: the reference, bit for bit.
    const double nearR = 0.49 * GerstnerWaves::DISPLACEMENT_FADE_WAVELENGTHS * minL;
    for (int a = 0; a < 16; ++a) {
        const glm::dvec2 p = camera + nearR * glm::dvec2(std::cos(a * 0.4), std::sin(a * 0.4));
        const glm::dvec3 seen = s.displacementSeenFrom(p, t, camera);
        const glm::dvec3 ref = s.displacementAt(p, t);
        EXPECT_EQ(seen.x, ref.x);
        EXPECT_EQ(seen.y, ref.y);
        EXPECT_EQ(seen.z, ref.z);
        // The lighting near the camera: the slope of the exact normal, nothing unresolved.
        const glm::dvec3 l = s.lightingSeenFrom(p, t, camera);
        const glm::dvec3 n = s.normalAt(p, t);
        EXPECT_NEAR(l.x, -n.x / n.z, 1e-12);
        EXPECT_NEAR(l.y, -n.y / n.z, 1e-12);
        EXPECT_EQ(l.z, 0.0);
    }
    // Beyond the longest wave's displacement fade: flat; beyond its lighting fade: flat lighting, and all
    // the slope variance is reported as unresolved.
    const glm::dvec2 far =
        camera + glm::dvec2(GerstnerWaves::DISPLACEMENT_FADE_WAVELENGTHS * maxL + 1.0, 0.0);
    const glm::dvec3 flat = s.displacementSeenFrom(far, t, camera);
    EXPECT_EQ(flat, glm::dvec3(0.0));
    EXPECT_NE(s.displacementAt(far, t).z, 0.0);
    const glm::dvec2 farther =
        camera + glm::dvec2(0.0, GerstnerWaves::LIGHTING_FADE_WAVELENGTHS * maxL + 1.0);
    const glm::dvec3 l = s.lightingSeenFrom(farther, t, camera);
    EXPECT_EQ(l.x, 0.0);
    EXPECT_EQ(l.y, 0.0);
    EXPECT_NEAR(l.z, allSlopes, 1e-15);
    EXPECT_GT(l.z, 1e-3);
}

TEST(GerstnerWaves, DefaultSeaIsDeterministicAndPlausible) {
    const std::vector<GerstnerWave> a = GerstnerWaves::defaultWaves(8, 60.0, 7);
    const std::vector<GerstnerWave> b = GerstnerWaves::defaultWaves(8, 60.0, 7);
    const std::vector<GerstnerWave> c = GerstnerWaves::defaultWaves(8, 60.0, 8);
    ASSERT_EQ(a.size(), 8u);
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].wavelength, b[i].wavelength);
        EXPECT_EQ(a[i].amplitude, b[i].amplitude);
        EXPECT_EQ(a[i].directionDeg, b[i].directionDeg);
        EXPECT_EQ(a[i].steepness, b[i].steepness);
        EXPECT_EQ(a[i].phase, b[i].phase);
        EXPECT_NE(a[i].phase, c[i].phase);
        const double ka = 2.0 * PI / a[i].wavelength * a[i].amplitude;
        EXPECT_GE(a[i].wavelength, 120.0 * std::pow(8.0 / 120.0, i / 7.0) * 0.9);
        EXPECT_LT(a[i].wavelength, 120.0 * std::pow(8.0 / 120.0, i / 7.0) * 1.1);
        EXPECT_GE(ka, 0.015 - 1e-15);
        EXPECT_LT(ka, 0.025);
        const double fromWind = std::remainder(a[i].directionDeg - 60.0, 360.0);
        EXPECT_LE(std::abs(fromWind), 40.0);
        EXPECT_GE(a[i].steepness, 0.5);
        EXPECT_LE(a[i].steepness, 1.0);
        EXPECT_GE(a[i].phase, 0.0);
        EXPECT_LT(a[i].phase, 2.0 * PI);
    }
    // std::mt19937_64's sequence is fixed by the standard and the mapping to [0, 1) is ours, so these
    // values are the same with every standard library (golden values from the first run).
    EXPECT_NEAR(a[0].wavelength, 126.10524729966858, 1e-12);
    EXPECT_NEAR(a[7].directionDeg, 42.37453108596295, 1e-12);

    // An empty description is this sea (seed 7 by default); a plausible wind sea, far from the limit.
    const GerstnerWaves s;
    ASSERT_EQ(s.waves().size(), 8u);
    for (size_t i = 0; i < 8; ++i)
        EXPECT_EQ(s.waves()[i].wavelength, a[i].wavelength);
    EXPECT_GT(s.significantWaveHeight(), 1.0);
    EXPECT_LT(s.significantWaveHeight(), 2.0);
    EXPECT_EQ(s.clampedBy(), 1.0);
    EXPECT_LT(s.requestedSteepnessSum(), 0.25);
    EXPECT_EQ(GerstnerWaves::defaultWaves(1, 0.0, 1).size(), 1u);
    EXPECT_EQ(GerstnerWaves::defaultWaves(64, 0.0, 1).size(), 64u);
}

TEST(GerstnerWaves, InvalidDescriptionsNameTheField) {
    const auto expectMessage = [](const GerstnerDesc& d, const std::string& part) {
        try {
            GerstnerWaves s(d);
            ADD_FAILURE() << "no exception, expected one naming '" << part << "'";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    const auto with = [](int index, auto mutate) {
        GerstnerDesc d;
        d.waves = crossedSea(0.5, 0.5);
        mutate(d.waves[static_cast<size_t>(index)]);
        return d;
    };
    const double nan = std::nan(""), inf = INFINITY;
    expectMessage(with(2, [](GerstnerWave& w) { w.wavelength = 0.0; }),
                  "GerstnerDesc.waves[2].wavelength must be finite and > 0, got 0");
    expectMessage(with(2, [&](GerstnerWave& w) { w.wavelength = nan; }), "GerstnerDesc.waves[2].wavelength");
    expectMessage(with(5, [](GerstnerWave& w) { w.wavelength = -3.0; }), "GerstnerDesc.waves[5].wavelength");
    expectMessage(with(1, [](GerstnerWave& w) { w.amplitude = -0.1; }),
                  "GerstnerDesc.waves[1].amplitude must be finite and >= 0, got -0.1");
    expectMessage(with(1, [&](GerstnerWave& w) { w.amplitude = inf; }), "GerstnerDesc.waves[1].amplitude");
    expectMessage(with(0, [](GerstnerWave& w) { w.steepness = 1.5; }),
                  "GerstnerDesc.waves[0].steepness must be finite and in [0, 1], got 1.5");
    expectMessage(with(0, [](GerstnerWave& w) { w.steepness = -0.01; }), "GerstnerDesc.waves[0].steepness");
    expectMessage(with(7, [&](GerstnerWave& w) { w.steepness = nan; }), "GerstnerDesc.waves[7].steepness");
    expectMessage(with(3, [&](GerstnerWave& w) { w.directionDeg = inf; }),
                  "GerstnerDesc.waves[3].directionDeg must be finite");
    expectMessage(with(4, [&](GerstnerWave& w) { w.phase = nan; }),
                  "GerstnerDesc.waves[4].phase must be finite");
    GerstnerDesc scale;
    scale.steepnessScale = -1.0;
    expectMessage(scale, "GerstnerDesc.steepnessScale must be finite and >= 0, got -1");
    scale.steepnessScale = nan;
    expectMessage(scale, "GerstnerDesc.steepnessScale");
    GerstnerDesc many;
    many.waves.assign(65, wave(0.1, 30.0, 0.0, 0.5, 0.0));
    expectMessage(many, "GerstnerDesc.waves must hold at most 64 waves, got 65");
    EXPECT_THROW(GerstnerWaves::defaultWaves(0, 60.0, 1), std::invalid_argument);
    EXPECT_THROW(GerstnerWaves::defaultWaves(65, 60.0, 1), std::invalid_argument);
    EXPECT_THROW(GerstnerWaves::defaultWaves(8, nan, 1), std::invalid_argument);

    // The edges of the valid ranges are accepted: 64 waves, A = 0, Q = 0 and 1, scale 0.
    many.waves.resize(64);
    many.waves[0].amplitude = 0.0;
    many.waves[1].steepness = 0.0;
    many.waves[2].steepness = 1.0;
    many.steepnessScale = 0.0;
    EXPECT_NO_THROW(GerstnerWaves{many});
}

// Living whitecaps (GerstnerDesc::foamMemory): for one wave h = A sin(k D.x - w t + phi) the remembered
// crest at a point is, written out here independently of the class, max(h(t), e^(-(t - t_j)/tau)
// max_{k<30} e^(-k s/tau) max(h(t_j - k s), 0)) with t_j = floor(t / s) s, s = 0.2 s, tau = 4 s. Checked at
// points and times incl. 10^6 s, 10^7 m from the origin (within 1e-9 m), and against the behaviour it stands
// for: right after a crest passed (trough now) the memory holds ~e^(-age/tau) of the crest; with the memory
// off the foam height is the current height.
TEST(GerstnerWaves, FoamMemoryRemembersCrestsThatPassed) {
    GerstnerWave w;
    w.amplitude = 1.0;
    w.wavelength = 60.0;
    w.directionDeg = 90.0; // toward the east
    w.steepness = 0.5;
    w.phase = 0.3;
    GerstnerDesc d;
    d.waves = {w};
    const GerstnerWaves sea(d);
    const double k = 2.0 * std::numbers::pi / 60.0, omega = std::sqrt(GRAVITY * k);
    auto h = [&](double x, double t) { return std::sin(k * x - omega * t + 0.3); };
    auto expected = [&](double x, double t) {
        const double j = std::floor(t / FOAM_MEMORY_STEP);
        double m = 0.0;
        for (int i = 0; i < FOAM_MEMORY_WINDOW; ++i)
            m = std::max(m, std::exp(-i * FOAM_MEMORY_STEP / FOAM_DECAY_TIME) *
                                std::max(h(x, (j - i) * FOAM_MEMORY_STEP), 0.0));
        return std::max(h(x, t), std::exp(-(t - j * FOAM_MEMORY_STEP) / FOAM_DECAY_TIME) * m);
    };
    for (double x : {0.0, 17.3, 1.0e7 + 3.1})
        for (double t : {0.0, 12.34, 1.0e6 + 0.57}) {
            // At 10^6 s the phase w t ~ 1e6 rad carries ~1e-10 rad of double rounding in either form.
            EXPECT_NEAR(sea.foamHeightAt({x, 0.0}, t), expected(x, t), 1e-9) << "x " << x << " t " << t;
            EXPECT_GE(sea.foamHeightAt({x, 0.0}, t), sea.displacementAt({x, 0.0}, t).z - 1e-12);
        }
    // A trough now, the crest half a period (T/2 = pi / w ~ 3.1 s) ago: the memory holds most of the crest.
    const double tTrough = (0.3 + std::numbers::pi / 2.0 + 20.0 * std::numbers::pi) / omega; // h(0, t) = -1
    EXPECT_NEAR(sea.displacementAt({0.0, 0.0}, tTrough).z, -1.0, 1e-9);
    const double remembered = sea.foamHeightAt({0.0, 0.0}, tTrough);
    EXPECT_GT(remembered, std::exp(-(std::numbers::pi / omega) / FOAM_DECAY_TIME) * 0.95);
    EXPECT_LT(remembered, 1.0);
    GerstnerDesc off = d;
    off.foamMemory = false;
    EXPECT_EQ(GerstnerWaves(off).foamHeightAt({0.0, 0.0}, tTrough),
              sea.displacementAt({0.0, 0.0}, tTrough).z);
}
