// Unit tests of the radial grid (GPU Gems 2 §18.2.3): end radii, monotonic rings, topology, validation.
#include "ocean/RadialGrid.h"

#include <gtest/gtest.h>

#include <cmath>

using pacifica::ocean::RadialGrid;
using pacifica::ocean::RadialGridDesc;

TEST(RadialGrid, EndRadiiMatchTheSeedWithin1e6Relative) {
    // The bound: r_0 = 0.1 m and r_max = 40 km within 1e-6 relative, both as computed in double and
    // after storage as float (float has 24 bits: 6e-8 relative).
    const RadialGrid grid(RadialGridDesc{});
    EXPECT_NEAR(grid.radius(0), 0.1, 0.1 * 1e-6);
    EXPECT_NEAR(grid.radius(grid.desc().rings - 1), 40000.0, 40000.0 * 1e-6);
    const auto& v = grid.vertices();
    const size_t cols = static_cast<size_t>(grid.desc().segments) + 1;
    const size_t firstRing = 1, lastRing = 1 + static_cast<size_t>(grid.desc().rings - 1) * cols;
    EXPECT_NEAR(v[firstRing * 2 + 1], 0.1, 0.1 * 1e-6);
    EXPECT_NEAR(v[lastRing * 2 + 1], 40000.0, 40000.0 * 1e-6);
}

TEST(RadialGrid, RadiiFollowA0PlusA1ITo4) {
    const RadialGrid grid(RadialGridDesc{.rings = 64, .segments = 16, .rMin = 0.1, .rMax = 40000.0});
    EXPECT_DOUBLE_EQ(grid.a0(), 0.1);
    EXPECT_DOUBLE_EQ(grid.a1(), (40000.0 - 0.1) / std::pow(63.0, 4));
    for (int i = 1; i < 64; ++i) {
        EXPECT_GT(grid.radius(i), grid.radius(i - 1));
        EXPECT_NEAR(grid.radius(i), 0.1 + grid.a1() * std::pow(i, 4), 1e-9 * grid.radius(i));
    }
}

TEST(RadialGrid, TopologyHasCentreFanRingsAndSkirt) {
    const RadialGridDesc d{
        .rings = 10, .segments = 8, .rMin = 0.1, .rMax = 1000.0, .skirtRadius = 1e6, .skirtRings = 3};
    const RadialGrid grid(d);
    // centre + (rings + skirt rings) * (segments + 1) vertices
    EXPECT_EQ(grid.vertexCount(), 1u + 13u * 9u);
    // centre fan (8 tris) + 12 ring gaps (incl. skirt) * 8 segments * 2 tris
    EXPECT_EQ(grid.indices().size(), 3u * (8u + 12u * 8u * 2u));
    for (uint32_t idx : grid.indices())
        EXPECT_LT(idx, grid.vertexCount());
    // Skirt rings are geometric from rMax to skirtRadius: 1e4, 1e5, 1e6.
    EXPECT_FLOAT_EQ(grid.vertices()[(1 + 10 * 9) * 2 + 1], 1e4f);
    EXPECT_FLOAT_EQ(grid.vertices()[(1 + 11 * 9) * 2 + 1], 1e5f);
    EXPECT_FLOAT_EQ(grid.vertices()[(1 + 12 * 9) * 2 + 1], 1e6f);
    // Every triangle winds counter-clockwise seen from above (+z), for a full circle and for a sector.
    for (const pacifica::ocean::ViewSector sector :
         {pacifica::ocean::ViewSector{}, pacifica::ocean::ViewSector{1.0, 0.8}}) {
        const auto& v = grid.vertices();
        for (size_t t = 0; t < grid.indices().size(); t += 3) {
            auto p = [&](size_t k) {
                const uint32_t i = grid.indices()[t + k];
                return pacifica::ocean::sectorPosition(v[i * 2], v[i * 2 + 1], sector, 0.0);
            };
            const glm::dvec2 a = p(0), b = p(1), c = p(2);
            const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
            EXPECT_GT(area, 0.0) << "triangle " << t / 3;
        }
    }
}

namespace {
constexpr double PI = 3.14159265358979323846;
pacifica::CameraFrame camera(double headingDeg, double pitchDeg, double rollDeg) {
    pacifica::Pose pose;
    pose.position = {1e7, -1e7, 100.0};
    pose.headingDeg = headingDeg;
    pose.pitchDeg = pitchDeg;
    pose.rollDeg = rollDeg;
    return pacifica::makeCameraFrame(pose, static_cast<float>(60.0 * PI / 180.0), 16.0f / 9.0f, 0.05f);
}
double azimuthOfHeading(double headingDeg) {
    return (90.0 - headingDeg) * PI / 180.0;
}
} // namespace

TEST(ViewSector, LevelCameraSeesItsHorizontalFieldOfView) {
    // 60 deg vertical fov at 16:9: horizontal fov = 2 atan(tan(30 deg) 16/9) = 91.49 deg; looking level, the
    // top corners project to the same azimuths as the bottom ones.
    const auto s = pacifica::ocean::computeViewSector(camera(0.0, 0.0, 0.0), 0.0);
    EXPECT_NEAR(s.halfWidth, 2.0 * std::atan(std::tan(PI / 6.0) * 16.0 / 9.0) / 2.0, 1e-5);
    EXPECT_NEAR(s.center, azimuthOfHeading(0.0), 1e-6); // north = +y = azimuth pi/2
    const auto e = pacifica::ocean::computeViewSector(camera(90.0, -10.0, 0.0), 0.05);
    EXPECT_NEAR(std::remainder(e.center - azimuthOfHeading(90.0), 2 * PI), 0.0, 1e-6);
    EXPECT_GT(e.halfWidth, s.halfWidth + 0.05); // pitched down: the bottom corners spread wider
    EXPECT_LT(e.halfWidth, PI / 2.0);
}

TEST(ViewSector, LookingDownAtTheNadirNeedsTheWholeCircle) {
    EXPECT_DOUBLE_EQ(pacifica::ocean::computeViewSector(camera(30.0, -90.0, 0.0), 0.0).halfWidth, PI);
    EXPECT_DOUBLE_EQ(pacifica::ocean::computeViewSector(camera(30.0, -75.0, 0.0), 0.0).halfWidth, PI);
    EXPECT_LT(pacifica::ocean::computeViewSector(camera(30.0, -45.0, 0.0), 0.0).halfWidth, PI * 0.75);
}

TEST(ViewSector, EveryVisibleSeaPointLiesInsideTheSector) {
    // Rays through a grid of screen points, for many attitudes: where a ray hits the sea plane, its azimuth
    // from the camera must lie within the sector (no gap at the screen edges or the horizon).
    for (double heading : {0.0, 77.0, 200.0, 333.0})
        for (double pitch : {-89.0, -60.0, -30.0, -5.0, 0.0, 10.0})
            for (double roll : {0.0, 45.0, -80.0}) {
                const pacifica::CameraFrame cam = camera(heading, pitch, roll);
                const auto s = pacifica::ocean::computeViewSector(cam, 0.0);
                const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.viewProj));
                for (int iy = 0; iy <= 20; ++iy)
                    for (int ix = 0; ix <= 20; ++ix) {
                        const glm::dvec4 p = inv * glm::dvec4(-1.0 + ix * 0.1, -1.0 + iy * 0.1, 0.5, 1.0);
                        const glm::dvec3 d = glm::dvec3(p) / p.w;
                        if (d.z >= 0.0 || std::hypot(d.x, d.y) < 1e-9)
                            continue; // misses the sea, or straight down (the sector is then the whole
                                      // circle)
                        const double az = std::atan2(d.y, d.x);
                        EXPECT_LE(std::abs(std::remainder(az - s.center, 2 * PI)), s.halfWidth + 1e-9)
                            << "heading " << heading << " pitch " << pitch << " roll " << roll;
                    }
            }
}

TEST(RadialGrid, InvalidDescriptionsNameTheField) {
    auto message = [](const RadialGridDesc& d) {
        try {
            RadialGrid g(d);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({.rings = 1}).find("RadialGridDesc.rings"), std::string::npos);
    EXPECT_NE(message({.segments = 2}).find("RadialGridDesc.segments"), std::string::npos);
    EXPECT_NE(message({.rMin = 0.0}).find("RadialGridDesc.rMin"), std::string::npos);
    EXPECT_NE(message({.rMin = NAN}).find("RadialGridDesc.rMin"), std::string::npos);
    EXPECT_NE(message({.rMax = 0.05}).find("RadialGridDesc.rMax"), std::string::npos);
    EXPECT_NE(message({.skirtRadius = 10.0}).find("RadialGridDesc.skirtRadius"), std::string::npos);
    EXPECT_NE(message({.skirtRings = 0}).find("RadialGridDesc.skirtRings"), std::string::npos);
}
