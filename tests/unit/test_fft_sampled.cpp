// Unit tests of FftSampledSea (ocean/FftSampled.h): the FFT sea's tiles inverse-transformed on the CPU and
// interpolated, against the direct sum over every spectral component (FftCascades):
// - at a tile's lattice points the transform equals the direct sum (both interpolations), which pins the
//   lattice's sign, shift and scale conventions;
// - between them the error is bounded per interpolation (stated below, with the measured values), bicubic
//   under bilinear; the Eulerian height likewise;
// - far from the origin (10^7 m) and late (t = 10^6 s) the error is the same (both wrap in double);
// - the thread count that samples the tiles changes no bit;
// - a NaN time and mismatched spans are refused.
#include "ocean/FftSampled.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

using namespace pacifica::ocean;

namespace {

/// RMS and max of |sampled - direct| of the displacement's three components over random points.
struct Error {
    double rms = 0.0, max = 0.0;
};

Error displacementError(const FftCascades& sea, const FftSampledSea& sampled, const glm::dvec2& origin,
                        int count) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-3000.0, 3000.0);
    double sum = 0.0, worst = 0.0;
    for (int i = 0; i < count; ++i) {
        const glm::dvec2 p = origin + glm::dvec2(u(rng), u(rng));
        const glm::dvec3 e = sampled.displacementAt(p) - sea.displacementAt(p, sampled.time());
        const double m = std::max({std::abs(e.x), std::abs(e.y), std::abs(e.z)});
        sum += glm::dot(e, e) / 3.0;
        worst = std::max(worst, m);
    }
    return {std::sqrt(sum / count), worst};
}

} // namespace

TEST(FftSampled, LatticePointsEqualTheDirectSum) {
    FftDesc d;
    d.cascades = 1;
    d.aperiodic = false;
    d.size = 64;
    d.tileSize = 400.0;
    const FftCascades sea(d);
    for (auto interpolation :
         {FftSampledSea::Interpolation::Bilinear, FftSampledSea::Interpolation::Bicubic}) {
        const FftSampledSea sampled(sea, 37.25, interpolation);
        double worst = 0.0;
        for (int b = 0; b < 64; b += 7)
            for (int a = 0; a < 64; a += 5) {
                const glm::dvec2 p(a * 400.0 / 64, b * 400.0 / 64);
                worst =
                    std::max(worst, glm::length(sampled.displacementAt(p) - sea.displacementAt(p, 37.25)));
            }
        // Single-precision transform of ~4000 components of a sea with Hs ~ 1 m: ~1e-6 m.
        EXPECT_LT(worst, 1e-4) << "interpolation " << static_cast<int>(interpolation);
    }
}

TEST(FftSampled, BetweenLatticePointsTheErrorIsBoundedBicubicBelowBilinear) {
    const FftCascades sea{FftDesc{}}; // the default sea: 4 cascades, mixed draws
    const double hs = sea.significantWaveHeight();
    const FftSampledSea cubic(sea, 12.5, FftSampledSea::Interpolation::Bicubic);
    const FftSampledSea linear(sea, 12.5, FftSampledSea::Interpolation::Bilinear);
    const Error c = displacementError(sea, cubic, {0.0, 0.0}, 150);
    const Error l = displacementError(sea, linear, {0.0, 0.0}, 150);
    std::printf("[fft sampled] Hs %.3f m: bicubic RMS %.4g max %.4g m, bilinear RMS %.4g max %.4g m\n", hs,
                c.rms, c.max, l.rms, l.max);
    // Measured (Hs 3.64 m): bicubic RMS 2.8 mm, max 10.6 mm; bilinear RMS 23.9 mm, max 103 mm.
    EXPECT_LT(c.rms, 0.002 * hs);
    EXPECT_LT(c.max, 0.01 * hs);
    EXPECT_LT(l.rms, 0.015 * hs);
    EXPECT_LT(c.rms, 0.25 * l.rms);
}

TEST(FftSampled, EulerianHeightFollowsTheDirectSum) {
    const FftCascades sea{FftDesc{}};
    const FftSampledSea sampled(sea, 12.5);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-2000.0, 2000.0);
    std::vector<glm::dvec2> points;
    for (int i = 0; i < 40; ++i)
        points.emplace_back(u(rng), u(rng));
    std::vector<double> heights(points.size());
    sampled.heightsAt(points, heights);
    double worst = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
        ASSERT_TRUE(std::isfinite(heights[i]));
        EXPECT_DOUBLE_EQ(heights[i], sampled.heightAt(points[i]));
        worst = std::max(worst, std::abs(heights[i] - sea.heightAt(points[i], 12.5)));
    }
    std::printf("[fft sampled] Eulerian height: worst |sampled - direct| %.4g m\n", worst);
    EXPECT_LT(worst, 0.01 * sea.significantWaveHeight());
}

TEST(FftSampled, FarFromTheOriginAndLateTheErrorIsTheSame) {
    const FftCascades sea{FftDesc{}};
    const double hs = sea.significantWaveHeight();
    const FftSampledSea late(sea, 1e6 + 12.5);
    const Error far = displacementError(sea, late, {1e7, -1e7}, 100);
    std::printf("[fft sampled] at 1e7 m, t = 1e6 s: bicubic RMS %.4g max %.4g m\n", far.rms, far.max);
    EXPECT_LT(far.rms, 0.002 * hs);
    EXPECT_LT(far.max, 0.01 * hs);
}

TEST(FftSampled, TheThreadCountChangesNoBit) {
    const FftCascades sea{FftDesc{}};
    const FftSampledSea one(sea, 7.0, FftSampledSea::Interpolation::Bicubic, 1);
    const FftSampledSea three(sea, 7.0, FftSampledSea::Interpolation::Bicubic, 3);
    for (const glm::dvec2 p :
         {glm::dvec2(0.0, 0.0), glm::dvec2(123.4, -987.6), glm::dvec2(-4000.5, 2500.25)}) {
        const glm::dvec3 a = one.displacementAt(p), b = three.displacementAt(p);
        EXPECT_EQ(a.x, b.x);
        EXPECT_EQ(a.y, b.y);
        EXPECT_EQ(a.z, b.z);
        EXPECT_EQ(one.heightAt(p), three.heightAt(p));
    }
}

TEST(FftSampled, BadInputIsRefused) {
    FftDesc d;
    d.cascades = 1;
    d.size = 16;
    const FftCascades sea(d);
    EXPECT_THROW(FftSampledSea(sea, std::nan("")), std::invalid_argument);
    const FftSampledSea sampled(sea, 1.0);
    const std::vector<glm::dvec2> points(3);
    std::vector<double> heights(2);
    EXPECT_THROW(sampled.heightsAt(points, heights), std::invalid_argument);
}
