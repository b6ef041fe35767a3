// Unit tests of the height-map octave surface (GPU Gems 2 §18.2.1): tiling in space and time, unit-RMS
// maps, analytic slopes, camera-relative parameters far from the origin and at huge times.
#include "ocean/HeightOctaves.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pacifica::ocean;

namespace {

HeightOctavesDesc smallDesc() {
    HeightOctavesDesc d;
    d.mapSize = 64;
    d.frames = 16;
    d.wavesPerOctave = 24;
    return d;
}

const HeightOctaves& surface() {
    static const HeightOctaves s(smallDesc());
    return s;
}

} // namespace

TEST(HeightOctaves, MapsHaveUnitRmsAndAreFinite) {
    for (const OctaveMap& m : surface().maps()) {
        double sum = 0.0;
        const size_t n = static_cast<size_t>(m.size) * m.size;
        for (size_t i = 0; i < n; ++i) {
            ASSERT_TRUE(std::isfinite(m.texels[i * 4]));
            sum += double(m.texels[i * 4]) * m.texels[i * 4];
        }
        // Normalised analytically (orthogonal lattice cosines); half rounding changes it by < 1e-3.
        EXPECT_NEAR(std::sqrt(sum / n), 1.0, 2e-3);
    }
}

TEST(HeightOctaves, TilesInSpaceAndLoopsInTime) {
    const HeightOctaves& s = surface();
    const auto& o = s.desc().octaves;
    const glm::dvec2 p(12.3, -45.6);
    const double t = 3.21;
    const double h = s.heightAt(p, t);
    // Octave tiles are deliberately incommensurate, so the sum has no short period: test each map — a shift
    // by whole tiles in u, v and by a whole loop in frames must give the identical sample.
    for (int i = 0; i < static_cast<int>(o.size()); ++i) {
        const glm::dvec3 a = s.sampleMap(i, {0.37, 0.81}, 5.25);
        const glm::dvec3 b = s.sampleMap(i, {0.37 + 7.0, 0.81 - 3.0}, 5.25 + s.desc().frames);
        EXPECT_NEAR(a.x, b.x, 1e-9);
        EXPECT_NEAR(a.y, b.y, 1e-9);
    }
    // Time: a whole loop period of octave i leaves octave i unchanged.
    EXPECT_TRUE(std::isfinite(h));
    const double period0 = o[0].loopPeriod;
    const glm::dvec3 g0 = s.heightAndGradient(p, t, 1);
    const glm::dvec3 g1 = s.heightAndGradient(p, t + 1000.0 * period0, 1);
    EXPECT_NEAR(g0.x, g1.x, 1e-6);
}

TEST(HeightOctaves, StoredSlopesMatchFiniteDifferencesOfHeight) {
    // dh/du is analytic per texel; a central difference of the bilinear height across one texel at a
    // texel centre approximates it to O(du^2) — bound 5% of the slope scale (2 pi * max cycles).
    const HeightOctaves& s = surface();
    const int size = s.desc().mapSize;
    const double du = 1.0 / size;
    double worst = 0.0, scale = 0.0;
    for (int k = 0; k < 50; ++k) {
        const double u = (k * 7 % size + 0.5) / size, v = (k * 13 % size + 0.5) / size;
        const double analytic = s.sampleMap(0, {u, v}, 0.0).y;
        const double numeric =
            (s.sampleMap(0, {u + du, v}, 0.0).x - s.sampleMap(0, {u - du, v}, 0.0).x) / (2 * du);
        worst = std::max(worst, std::abs(analytic - numeric));
        scale = std::max(scale, std::abs(analytic));
    }
    EXPECT_LT(worst, 0.05 * 2.0 * 3.14159 * (size / 16));
    EXPECT_GT(scale, 1.0); // slopes are not all zero: the test can fail
}

TEST(HeightOctaves, FrameParamsFarFromOriginAndAtHugeTimesStayWrapped) {
    const HeightOctaves& s = surface();
    for (const glm::dvec2 cam : {glm::dvec2(0.0, 0.0), glm::dvec2(1e7, -1e7), glm::dvec2(-3.3e7, 2.2e7)}) {
        for (double t : {0.0, 1e6, 1e9}) {
            for (const OctaveFrameParams& p : s.frameParams(cam, t)) {
                EXPECT_GE(p.uvOffset.x, 0.0f);
                EXPECT_LT(p.uvOffset.x, 1.0f);
                EXPECT_GE(p.uvOffset.y, 0.0f);
                EXPECT_LT(p.uvOffset.y, 1.0f);
                EXPECT_GE(p.framePosition, 0.0f);
                EXPECT_LT(p.framePosition, float(s.desc().frames));
            }
        }
    }
    // The camera-relative evaluation the GPU does (float offset + float relative position) agrees with the
    // CPU's double world evaluation at 10^7 m: offset error <= 6e-8 tile, i.e. < 1e-4 m of height change.
    const glm::dvec2 cam(1e7 + 0.3, -1e7 + 0.7);
    const double t = 1e6 + 0.125;
    const auto params = s.frameParams(cam, t);
    const glm::dvec2 rel(123.0, -45.0);
    double gpuLike = 0.0;
    for (int i = 0; i < s.desc().displacedOctaves; ++i) {
        const auto& p = params[static_cast<size_t>(i)];
        const glm::dvec2 u = glm::dvec2(glm::vec2(rel) * p.invTileSize + p.uvOffset);
        gpuLike += p.amplitude * s.sampleMap(i, u, p.framePosition).x;
    }
    EXPECT_NEAR(gpuLike, s.heightAt(cam + rel, t), 1e-3);
}

TEST(HeightOctaves, InvalidDescriptionsNameTheField) {
    HeightOctavesDesc d = smallDesc();
    d.mapSize = 100;
    EXPECT_THROW(HeightOctaves{d}, std::invalid_argument);
    d = smallDesc();
    d.octaves[1].tileSize = -1.0;
    try {
        HeightOctaves bad(d);
        FAIL() << "no error";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("octaves[1].tileSize"), std::string::npos) << e.what();
    }
    d = smallDesc();
    d.displacedOctaves = 9;
    EXPECT_THROW(HeightOctaves{d}, std::invalid_argument);
}
