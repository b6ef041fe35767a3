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
    const size_t firstRing = 1,
                 lastRing = 1 + static_cast<size_t>(grid.desc().rings - 1) * grid.desc().segments;
    EXPECT_NEAR(v[firstRing * 3 + 2], 0.1, 0.1 * 1e-6);
    EXPECT_NEAR(v[lastRing * 3 + 2], 40000.0, 40000.0 * 1e-6);
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
    // centre + (rings + skirt rings) * segments vertices
    EXPECT_EQ(grid.vertexCount(), 1u + 13u * 8u);
    // centre fan (8 tris) + 12 ring gaps (incl. skirt) * 8 segments * 2 tris
    EXPECT_EQ(grid.indices().size(), 3u * (8u + 12u * 8u * 2u));
    for (uint32_t idx : grid.indices())
        EXPECT_LT(idx, grid.vertexCount());
    // Skirt rings are geometric from rMax to skirtRadius: 1e4, 1e5, 1e6.
    EXPECT_FLOAT_EQ(grid.vertices()[(1 + 10 * 8) * 3 + 2], 1e4f);
    EXPECT_FLOAT_EQ(grid.vertices()[(1 + 11 * 8) * 3 + 2], 1e5f);
    EXPECT_FLOAT_EQ(grid.vertices()[(1 + 12 * 8) * 3 + 2], 1e6f);
    // Every triangle winds counter-clockwise seen from above (+z).
    const auto& v = grid.vertices();
    for (size_t t = 0; t < grid.indices().size(); t += 3) {
        auto p = [&](size_t k) {
            const uint32_t i = grid.indices()[t + k];
            return std::pair<double, double>(v[i * 3] * v[i * 3 + 2], v[i * 3 + 1] * v[i * 3 + 2]);
        };
        const auto [ax, ay] = p(0);
        const auto [bx, by] = p(1);
        const auto [cx, cy] = p(2);
        EXPECT_GT((bx - ax) * (cy - ay) - (by - ay) * (cx - ax), 0.0) << "triangle " << t / 3;
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
