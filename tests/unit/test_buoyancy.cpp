// Unit tests of Buoyancy (ocean/Buoyancy.h): a hull's 3 x 3 points lie where its heading, length and beam put
// them; on a tilted plane of water the fit returns that plane's heave, pitch and roll exactly; a hull much
// longer than the waves hardly pitches on them; non-finite heights give non-finite poses (the caller's query
// reports them).
#include "ocean/Buoyancy.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

using namespace pacifica::ocean;

namespace {
constexpr double DEG = std::numbers::pi / 180.0;
}

TEST(Buoyancy, HullPointsFollowHeadingLengthAndBeam) {
    std::array<glm::dvec2, HULL_POINTS> p;
    hullPoints({1e7, -2e6}, 90.0, 100.0, 10.0, p); // heading east: ahead = +x, right = -y
    EXPECT_NEAR(p[4].x, 1e7, 1e-9);                // the centre
    EXPECT_NEAR(p[4].y, -2e6, 1e-9);
    EXPECT_NEAR(p[7].x - p[4].x, 40.0, 1e-9); // bow row, centre: 0.4 L ahead
    EXPECT_NEAR(p[1].x - p[4].x, -40.0, 1e-9);
    EXPECT_NEAR(p[5].y - p[4].y, -8.0, 1e-9); // starboard: 0.8 of the half beam to the right
    EXPECT_NEAR(p[3].y - p[4].y, 8.0, 1e-9);
}

TEST(Buoyancy, ATiltedPlaneOfWaterIsFoundExactly) {
    // h = 1.5 + 0.02 along - 0.05 across (across = to starboard): bow up atan(0.02), starboard lower: roll
    // right side down atan(0.05).
    const glm::dvec2 centre(300.0, -20.0);
    const double heading = 37.0, length = 130.0, halfBeam = 9.1;
    std::array<glm::dvec2, HULL_POINTS> p;
    hullPoints(centre, heading, length, halfBeam, p);
    const glm::dvec2 ahead(std::sin(heading * DEG), std::cos(heading * DEG)), right(ahead.y, -ahead.x);
    std::array<double, HULL_POINTS> h;
    for (int i = 0; i < HULL_POINTS; ++i)
        h[i] = 1.5 + 0.02 * glm::dot(p[i] - centre, ahead) - 0.05 * glm::dot(p[i] - centre, right);
    const HullPose pose = floatHull(h, length, halfBeam);
    EXPECT_NEAR(pose.heave, 1.5, 1e-12);
    EXPECT_NEAR(pose.pitchDeg, std::atan(0.02) / DEG, 1e-10);
    EXPECT_NEAR(pose.rollDeg, std::atan(0.05) / DEG, 1e-10);
}

TEST(Buoyancy, AHullLongerThanTheWavesHardlyPitches) {
    // A 1 m swell 20 m long: the pitch of the fitted plane is at most atan(A / (0.4 L)) -- 0.43 degrees for
    // a 330 m carrier -- while a 20 m boat on the same swell tilts by its slope (3 degrees here).
    auto swell = [](const glm::dvec2& x) { return 1.0 * std::sin(2.0 * std::numbers::pi * x.y / 20.0); };
    for (const auto& [length, bound] : {std::pair{330.0, 0.44}, std::pair{20.0, 90.0}}) {
        std::array<glm::dvec2, HULL_POINTS> p;
        hullPoints({0.0, 2.5}, 0.0, length, 0.07 * length, p);
        std::array<double, HULL_POINTS> h;
        for (int i = 0; i < HULL_POINTS; ++i)
            h[i] = swell(p[i]);
        const HullPose pose = floatHull(h, length, 0.07 * length);
        EXPECT_LT(std::abs(pose.pitchDeg), bound) << length;
        if (length < 100.0) {
            EXPECT_GT(std::abs(pose.pitchDeg), 2.0);
        }
        EXPECT_NEAR(pose.rollDeg, 0.0, 1e-9); // the swell runs along the hull
    }
}

TEST(Buoyancy, NonFiniteHeightsGiveANonFinitePose) {
    std::array<double, HULL_POINTS> h{};
    h[3] = NAN;
    const HullPose pose = floatHull(h, 100.0, 7.0);
    EXPECT_TRUE(std::isnan(pose.heave));
    EXPECT_TRUE(std::isnan(pose.rollDeg));
}
