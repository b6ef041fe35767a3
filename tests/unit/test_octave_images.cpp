// Unit tests of caller-supplied ("painted") octave height maps (HeightOctavesDesc.images, makeOctaveMap):
// a synthetic single cosine gives the analytic height at texel centres (up to the half rounding every map
// gets) and within the bilinear interpolation bound between them, the analytic slope through the spectral
// derivative channels, frames in the right order and linear in time, the right significant wave height;
// replacing one octave leaves the generated ones bit-identical; bad images throw naming the field.
#include "ocean/HeightOctaves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace pacifica::ocean;

namespace {

constexpr double TWO_PI = 2.0 * std::numbers::pi;
constexpr int SIZE = 64;
constexpr int N = 3, M = 2;    // cycles per tile along u and v
constexpr double PHASE = 0.4;  // radians
constexpr double TILE = 100.0; // metres
constexpr double AMPLITUDE = 1.5;
constexpr double LOOP = 10.0; // seconds
constexpr int FRAMES = 8;

/// cos(2 pi (N u + M v) + PHASE - 2 pi cyclesPerLoop f / FRAMES) at texel centres u = (x + 0.5) / SIZE.
OctaveImage cosineImage(int frames, double cyclesPerLoop) {
    OctaveImage img{SIZE, frames, {}};
    for (int f = 0; f < frames; ++f)
        for (int y = 0; y < SIZE; ++y)
            for (int x = 0; x < SIZE; ++x) {
                const double u = (x + 0.5) / SIZE, v = (y + 0.5) / SIZE;
                img.heights.push_back(static_cast<float>(
                    std::cos(TWO_PI * (N * u + M * v) + PHASE - TWO_PI * cyclesPerLoop * f / FRAMES)));
            }
    return img;
}

HeightOctavesDesc oneOctave(OctaveImage image) {
    HeightOctavesDesc d;
    d.octaves = {{TILE, AMPLITUDE, LOOP}};
    d.displacedOctaves = 1;
    d.mapSize = SIZE;
    d.frames = FRAMES;
    d.images = {std::move(image)};
    return d;
}

double analytic(const glm::dvec2& world) {
    return AMPLITUDE * std::cos(TWO_PI * (N * world.x + M * world.y) / TILE + PHASE);
}

std::string messageOf(const HeightOctavesDesc& d) {
    try {
        HeightOctaves s(d);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "(no exception)";
}

} // namespace

TEST(OctaveImages, CosineHeightsEqualTheAnalyticValue) {
    const HeightOctaves s(oneOctave(cosineImage(1, 0.0)));
    // Texel centres: the stored texel itself, rounded to half: |h| <= 1 has half spacing <= 2^-11, so the
    // rounding error is <= 2^-12, times the amplitude.
    const double halfBound = AMPLITUDE * std::ldexp(1.0, -12);
    double worstCentre = 0.0;
    for (int y = 0; y < SIZE; y += 3)
        for (int x = 0; x < SIZE; x += 5) {
            // World point of texel (x, y)'s centre, 7 tiles away from the origin (tiling).
            const glm::dvec2 w =
                (glm::dvec2(x, y) + 0.5) / double(SIZE) * TILE + glm::dvec2(7.0, -3.0) * TILE;
            worstCentre = std::max(worstCentre, std::abs(s.heightAt(w, 1.234) - analytic(w)));
        }
    EXPECT_LE(worstCentre, halfBound);
    // Between centres the map is bilinear: the interpolation error of f is <= (1/8)(max|f_xx| + max|f_yy|)
    // texel^2 (tensor-product linear interpolation bound), here A (2 pi / SIZE)^2 (N^2 + M^2) / 8 = 0.0235 m.
    const double interpBound = AMPLITUDE * std::pow(TWO_PI / SIZE, 2) * (N * N + M * M) / 8.0;
    double worst = 0.0;
    for (int i = 0; i < 500; ++i) {
        const glm::dvec2 w(-1234.5 + i * 0.731, 987.6 + i * 0.377);
        worst = std::max(worst, std::abs(s.heightAt(w, 5.0) - analytic(w)));
    }
    EXPECT_LE(worst, interpBound + halfBound);
    EXPECT_GT(worst, 10.0 * halfBound); // the points are between centres: the test sees interpolation
    std::printf("cosine map: max |CPU - analytic| %.3g m at texel centres, %.3g m between (bound %.3g m)\n",
                worstCentre, worst, interpBound + halfBound);
}

TEST(OctaveImages, SpectralSlopesGiveTheAnalyticNormal) {
    const HeightOctaves s(oneOctave(cosineImage(1, 0.0)));
    const OctaveMap& m = s.maps()[0];
    // Stored channels at texel centres: dh/du = -2 pi N sin(theta), dh/dv = -2 pi M sin(theta), exact for a
    // whole-cycle cosine (spectral derivative), then rounded to half: |slope| <= 2 pi N < 32, spacing 2^-6.
    double worst = 0.0;
    for (int y = 0; y < SIZE; ++y)
        for (int x = 0; x < SIZE; ++x) {
            const double theta = TWO_PI * (N * (x + 0.5) + M * (y + 0.5)) / SIZE + PHASE;
            const float* t = m.texel(0, x, y);
            worst = std::max({worst, std::abs(t[1] + TWO_PI * N * std::sin(theta)),
                              std::abs(t[2] + TWO_PI * M * std::sin(theta))});
            const double sq = std::pow(TWO_PI * std::sin(theta), 2) * (N * N + M * M);
            EXPECT_NEAR(t[3], sq, std::ldexp(1.0, -3) + 1e-3 * sq)
                << x << "," << y; // |.|^2 < 512: spacing <= 2^-2
        }
    EXPECT_LE(worst, std::ldexp(1.0, -7));
    // normalAt at a texel centre: -(dH/dx, dH/dy) = -A B (dh/du, dh/dv).
    const glm::dvec2 w = (glm::dvec2(10, 20) + 0.5) / double(SIZE) * TILE;
    const double theta = TWO_PI * (N * w.x + M * w.y) / TILE + PHASE;
    const glm::dvec3 want = glm::normalize(glm::dvec3(AMPLITUDE / TILE * TWO_PI * N * std::sin(theta),
                                                      AMPLITUDE / TILE * TWO_PI * M * std::sin(theta), 1.0));
    const double angle = std::acos(std::min(1.0, glm::dot(s.normalAt(w, 0.0), want)));
    EXPECT_LT(angle, 1e-4); // half rounding of the slope (2^-7) times A B = 1.2e-4 per component, ~1e-4 rad
}

TEST(OctaveImages, FramesAreOrderedAndLinearInTime) {
    // One wave cycle per loop: slice f is the cosine shifted by 2 pi f / FRAMES.
    const HeightOctaves s(oneOctave(cosineImage(FRAMES, 1.0)));
    const glm::dvec2 w = (glm::dvec2(17, 41) + 0.5) / double(SIZE) * TILE;
    const double theta = TWO_PI * (N * w.x + M * w.y) / TILE + PHASE;
    const double tol = AMPLITUDE * std::ldexp(1.0, -12);
    for (int f = 0; f < FRAMES; ++f) {
        const double t = 3.0 * LOOP + f * LOOP / FRAMES; // whole loops later: the same
        EXPECT_NEAR(s.heightAt(w, t), AMPLITUDE * std::cos(theta - TWO_PI * f / FRAMES), tol)
            << "frame " << f;
        // Half-way to the next slice: the mean of the two (time is linear between slices).
        const double mid =
            0.5 * (std::cos(theta - TWO_PI * f / FRAMES) + std::cos(theta - TWO_PI * (f + 1) / FRAMES));
        EXPECT_NEAR(s.heightAt(w, t + 0.5 * LOOP / FRAMES), AMPLITUDE * mid, tol) << "frame " << f << ".5";
    }
}

TEST(OctaveImages, SignificantWaveHeightUsesTheMapsRms) {
    // A whole-cycle cosine has RMS 1/sqrt(2) over the tile: Hs = 4 A / sqrt(2).
    const HeightOctaves s(oneOctave(cosineImage(1, 0.0)));
    EXPECT_NEAR(s.significantWaveHeight(), 4.0 * AMPLITUDE / std::sqrt(2.0), 1e-5);
}

TEST(OctaveImages, ReplacingOneOctaveLeavesTheGeneratedOnesUnchanged) {
    HeightOctavesDesc d;
    d.mapSize = SIZE;
    d.frames = FRAMES;
    d.wavesPerOctave = 16;
    const HeightOctaves generated(d);
    d.images.resize(d.octaves.size());
    d.images[2] = cosineImage(1, 0.0);
    const HeightOctaves painted(d);
    ASSERT_EQ(painted.maps().size(), generated.maps().size());
    for (size_t i = 0; i < d.octaves.size(); ++i) {
        if (i == 2)
            EXPECT_NE(painted.maps()[i].texels, generated.maps()[i].texels);
        else
            EXPECT_EQ(painted.maps()[i].texels, generated.maps()[i].texels) << "octave " << i;
    }
    // The still image fills every slice.
    const OctaveMap& m = painted.maps()[2];
    EXPECT_EQ(m.frames, FRAMES);
    for (int f = 1; f < FRAMES; ++f)
        EXPECT_EQ(m.texel(f, 5, 9)[0], m.texel(0, 5, 9)[0]);
}

TEST(OctaveImages, BadImagesNameTheField) {
    HeightOctavesDesc d = oneOctave(cosineImage(1, 0.0));
    d.images.push_back({});
    EXPECT_NE(
        messageOf(d).find("HeightOctavesDesc.images must be empty or hold one entry per octave (1), got 2"),
        std::string::npos)
        << messageOf(d);

    d = oneOctave(cosineImage(1, 0.0));
    d.mapSize = 128;
    EXPECT_NE(messageOf(d).find(
                  "HeightOctavesDesc.images[0].size must equal HeightOctavesDesc.mapSize (128), got 64"),
              std::string::npos)
        << messageOf(d);

    d = oneOctave(cosineImage(1, 0.0));
    d.images[0].heights[SIZE + 5] = std::nanf("");
    EXPECT_NE(
        messageOf(d).find("HeightOctavesDesc.images[0].heights[69] is not finite (frame 0, texel (5, 1))"),
        std::string::npos)
        << messageOf(d);

    d = oneOctave(cosineImage(1, 0.0));
    d.images[0].frames = 3;
    EXPECT_NE(messageOf(d).find("HeightOctavesDesc.images[0].frames must be 1 or 8"), std::string::npos)
        << messageOf(d);

    d = oneOctave(cosineImage(1, 0.0));
    d.images[0].heights.pop_back();
    EXPECT_NE(messageOf(d).find("HeightOctavesDesc.images[0].heights must hold frames * size * size = 4096"),
              std::string::npos)
        << messageOf(d);

    d = oneOctave(cosineImage(1, 0.0));
    d.images[0].heights[7] = 1.0e5f; // beyond half's 65504
    EXPECT_NE(messageOf(d).find("exceeds half-float range"), std::string::npos) << messageOf(d);
    EXPECT_NE(messageOf(d).find("HeightOctavesDesc.images[0]"), std::string::npos) << messageOf(d);

    // makeOctaveMap directly: a size that is not a power of two.
    try {
        (void)makeOctaveMap({48, 1, std::vector<float>(48 * 48, 0.0f)}, 8, "painted");
        ADD_FAILURE() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "painted.size must be a power of two in [16, 1024], got 48");
    }
}
