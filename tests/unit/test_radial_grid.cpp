// Unit tests of the radial grid (GPU Gems 2 §18.2.3): end radii, monotonic rings, topology, validation.
#include "ocean/RadialGrid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

using pacifica::ocean::RadialGrid;
using pacifica::ocean::RadialGridDesc;

TEST(RadialGrid, EndRadiiMatchTheSeedWithin1e6Relative) {
    // The required bound: r_0 = 0.1 m and r_max = 40 km within 1e-6 relative, both as computed in double and
    // after storage as float (float has 24 bits: 6e-8 relative).
    const RadialGrid grid(RadialGridDesc{});
    EXPECT_NEAR(grid.radius(0), 0.1, 0.1 * 1e-6);
    EXPECT_NEAR(grid.radius(grid.desc().rings - 1), 40000.0, 40000.0 * 1e-6);
    const auto& v = grid.vertices();
    const size_t firstRing = grid.vertexIndex(0, 0), lastRing = grid.vertexIndex(grid.desc().rings - 1, 0);
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
    // centre + (rings + skirt rings) * (segments + 1) vertices are indexed; each ring is padded to the
    // stride 16 (= 16 mod 256, GridOrder.h), the padding repeating the ring's last vertex.
    EXPECT_EQ(grid.ringStride(), 16);
    EXPECT_EQ(grid.indexedVertexCount(), 1u + 13u * 9u);
    EXPECT_EQ(grid.vertexCount(), 1u + 13u * 16u);
    EXPECT_EQ(grid.vertexIndex(2, 3), 1u + 2u * 16u + 3u);
    // centre fan (8 tris) + 12 ring gaps (incl. skirt) * 8 segments * 2 tris
    EXPECT_EQ(grid.indices().size(), 3u * (8u + 12u * 8u * 2u));
    std::vector<int> uses(grid.vertexCount(), 0);
    for (uint32_t idx : grid.indices()) {
        ASSERT_LT(idx, grid.vertexCount());
        ++uses[idx];
    }
    for (int ring = 0; ring < 13; ++ring)
        for (int col = 0; col < 16; ++col) {
            const uint32_t i = grid.vertexIndex(ring, col);
            EXPECT_EQ(uses[i] > 0, col <= 8) << "ring " << ring << " column " << col; // padding: never drawn
            EXPECT_FLOAT_EQ(grid.vertices()[i * 2], std::min(col, 8) / 8.0f);
            EXPECT_FLOAT_EQ(grid.vertices()[i * 2 + 1], grid.vertices()[grid.vertexIndex(ring, 0) * 2 + 1]);
        }
    // Skirt rings are geometric from rMax to skirtRadius: 1e4, 1e5, 1e6.
    EXPECT_FLOAT_EQ(grid.vertices()[grid.vertexIndex(10, 0) * 2 + 1], 1e4f);
    EXPECT_FLOAT_EQ(grid.vertices()[grid.vertexIndex(11, 0) * 2 + 1], 1e5f);
    EXPECT_FLOAT_EQ(grid.vertices()[grid.vertexIndex(12, 4) * 2 + 1], 1e6f);
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
    // validate() says what the constructor says, without building the mesh.
    auto message = [](const RadialGridDesc& d) {
        std::string constructed = "no error", validated = "no error";
        try {
            RadialGrid g(d);
        } catch (const std::invalid_argument& e) {
            constructed = e.what();
        }
        try {
            RadialGrid::validate(d);
        } catch (const std::invalid_argument& e) {
            validated = e.what();
        }
        EXPECT_EQ(constructed, validated);
        return constructed;
    };
    EXPECT_EQ(message({}), "no error");
    // The largest grid (~134 M vertices) is valid, and validate() says so without allocating it.
    EXPECT_NO_THROW(RadialGrid::validate({.rings = 8192, .segments = 16384}));
    EXPECT_THROW(RadialGrid::validate({.rings = 8193}), std::invalid_argument);
    EXPECT_NE(message({.rings = 1}).find("RadialGridDesc.rings"), std::string::npos);
    EXPECT_NE(message({.segments = 2}).find("RadialGridDesc.segments"), std::string::npos);
    EXPECT_NE(message({.rMin = 0.0}).find("RadialGridDesc.rMin"), std::string::npos);
    EXPECT_NE(message({.rMin = NAN}).find("RadialGridDesc.rMin"), std::string::npos);
    EXPECT_NE(message({.rMax = 0.05}).find("RadialGridDesc.rMax"), std::string::npos);
    EXPECT_NE(message({.skirtRadius = 10.0}).find("RadialGridDesc.skirtRadius"), std::string::npos);
    EXPECT_NE(message({.skirtRings = 0}).find("RadialGridDesc.skirtRings"), std::string::npos);
    EXPECT_NE(message({.minRingPixels = -1.0}).find("RadialGridDesc.minRingPixels"), std::string::npos);
    EXPECT_NE(message({.minRingPixels = NAN}).find("RadialGridDesc.minRingPixels"), std::string::npos);
}

// Screen-space ring thinning (RadialGridDesc::minRingPixels, docs/PERFORMANCE.md).
TEST(RadialGridThinning, ZeroPixelsKeepsEveryRingAndTheSeedIndices) {
    const RadialGrid grid(RadialGridDesc{});
    const pacifica::ocean::RingView view{20.0, 311.8, 6371000.0};
    const std::vector<int> all = grid.ringsFor(view, 0.0);
    ASSERT_EQ(static_cast<int>(all.size()), grid.ringCount());
    EXPECT_EQ(grid.ringCount(), 256 + 16);
    EXPECT_EQ(grid.indicesFor(all), grid.indices());
}

TEST(RadialGridThinning, KeptRingsAreAtLeastMinPixelsApartAndEndsAreKept) {
    const RadialGrid grid(RadialGridDesc{});
    constexpr double R = 6371000.0;
    // 20 m + 2 Hs up, 360 px over a 60 degree fov: pixels per radian = 180 / tan(30 deg).
    const double ppr = 180.0 / std::tan(30.0 * PI / 180.0);
    const pacifica::ocean::RingView view{20.0, ppr, R};
    auto depression = [&](double r) { return std::atan2(20.0 + r * r / (2.0 * R), r); };
    for (double px : {0.5, 1.0, 2.0}) {
        const std::vector<int> kept = grid.ringsFor(view, px);
        ASSERT_GE(kept.size(), 3u);
        EXPECT_EQ(kept.front(), 0);
        // The last displaced ring and the whole skirt are always there.
        const int last = grid.desc().rings - 1;
        ASSERT_TRUE(std::find(kept.begin(), kept.end(), last) != kept.end());
        EXPECT_EQ(kept.back(), grid.ringCount() - 1);
        EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
        // Between ring 0 and the last displaced ring, a ring is kept when it is >= px from the last kept
        // ring on screen or the next ring lies beyond 1.1 times the last kept radius; a skipped ring is
        // neither.
        size_t k = 1;
        for (int i = 1; i < last; ++i) {
            const double prevRadius = grid.radius(kept[k - 1]);
            const double pixels = std::abs(depression(prevRadius) - depression(grid.radius(i))) * ppr;
            const bool chord = grid.radius(i + 1) > 1.1 * prevRadius;
            if (kept[k] == i) {
                EXPECT_TRUE(pixels >= px || chord) << "ring " << i;
                ++k;
            } else {
                EXPECT_TRUE(pixels < px && !chord) << "ring " << i << " was skipped";
            }
            // No two kept rings more than 1.1 x apart unless they are neighbours.
            if (k >= 2 && kept[k - 1] == i && kept[k - 2] != i - 1) {
                EXPECT_LE(grid.radius(i), 1.1 * grid.radius(kept[k - 2]) * (1.0 + 1e-12)) << "ring " << i;
            }
        }
        // From 20 m many rings are sub-pixel slivers: well under the 256 + 16 rings are drawn.
        EXPECT_LT(kept.size(), 200u) << px << " px";
        const std::vector<uint32_t> idx = grid.indicesFor(kept);
        EXPECT_EQ(idx.size(), 3u * 512u * (1u + 2u * (kept.size() - 1)));
        for (uint32_t i : idx)
            ASSERT_LT(i, grid.vertexCount());
    }
    // Higher up the rings spread over more pixels: more are kept; 1 px keeps fewer than 0.5 px.
    const pacifica::ocean::RingView high{5000.0, ppr, R};
    EXPECT_GT(grid.ringsFor(high, 1.0).size(), grid.ringsFor(view, 1.0).size());
    EXPECT_LT(grid.ringsFor(view, 1.0).size(), grid.ringsFor(view, 0.5).size());
    // A non-finite height keeps every ring (never a hole).
    EXPECT_EQ(static_cast<int>(grid.ringsFor({NAN, ppr, R}, 1.0).size()), grid.ringCount());
}

namespace {
// Vertex shadings per triangle of a triangle list under two post-transform reuse models (GridOrder.h):
// Mesa's draw module (segments of 1024 indices, each shading its distinct vertices once, found through a
// 256-entry table indexed by vertex index mod 256: gallium/auxiliary/draw/draw_pt_vsplit.c), and a FIFO
// cache of `fifo` vertices (hardware-like).
double mesaShadingsPerTriangle(const std::vector<uint32_t>& idx) {
    size_t shaded = 0;
    for (size_t s = 0; s < idx.size(); s += 1024) {
        std::vector<int64_t> table(256, -1);
        for (size_t k = s; k < std::min(idx.size(), s + 1024); ++k)
            if (table[idx[k] % 256] != int64_t(idx[k])) {
                table[idx[k] % 256] = idx[k];
                ++shaded;
            }
    }
    return double(shaded) / double(idx.size() / 3);
}
double fifoShadingsPerTriangle(const std::vector<uint32_t>& idx, size_t fifo) {
    std::vector<uint32_t> cache;
    size_t shaded = 0;
    for (uint32_t i : idx)
        if (std::find(cache.begin(), cache.end(), i) == cache.end()) {
            ++shaded;
            cache.push_back(i);
            if (cache.size() > fifo)
                cache.erase(cache.begin());
        }
    return double(shaded) / double(idx.size() / 3);
}
} // namespace

TEST(RadialGrid, TriangleOrderReusesShadedVertices) {
    // A triangle mesh has ~2 triangles per vertex, so 0.5 shadings per triangle is the floor. Row order (ring
    // after ring, 513 = 1 mod 256 vertices a ring) gave 1.0 in both models: every vertex shaded twice.
    for (const auto& [rings, segments] : {std::pair{256, 512}, {128, 256}, {64, 128}}) {
        const RadialGrid grid(RadialGridDesc{.rings = rings, .segments = segments});
        const double mesa = mesaShadingsPerTriangle(grid.indices());
        const double fifo = fifoShadingsPerTriangle(grid.indices(), 32);
        std::printf("grid %dx%d: %.3f shadings/triangle (Mesa draw), %.3f (FIFO 32)\n", rings, segments, mesa,
                    fifo);
        EXPECT_LT(mesa, 0.60) << rings << "x" << segments;
        EXPECT_LT(fifo, 0.56) << rings << "x" << segments;
        // Row order, modelled the same way, for the record: what the block order is measured against.
        std::vector<uint32_t> rowOrder;
        for (int i = 0; i + 1 < grid.ringCount(); ++i)
            for (int j = 0; j < segments; ++j) {
                const uint32_t a = grid.vertexIndex(i, j), b = grid.vertexIndex(i, j + 1);
                const uint32_t c = grid.vertexIndex(i + 1, j), d = grid.vertexIndex(i + 1, j + 1);
                rowOrder.insert(rowOrder.end(), {a, c, d, a, d, b});
            }
        EXPECT_GT(fifoShadingsPerTriangle(rowOrder, 32), 0.99);
    }
}

namespace {
// The quads between rings[k] and rings[k + 1] for k >= firstPair, as two triangles (a, c, d), (a, d, b) each.
void appendRowOrderQuads(std::vector<std::array<uint32_t, 3>>& out, const RadialGrid& grid,
                         const std::vector<int>& rings, size_t firstPair) {
    for (size_t k = firstPair; k + 1 < rings.size(); ++k)
        for (int j = 0; j < grid.desc().segments; ++j) {
            const uint32_t a = grid.vertexIndex(rings[k], j), b = grid.vertexIndex(rings[k], j + 1);
            const uint32_t c = grid.vertexIndex(rings[k + 1], j), d = grid.vertexIndex(rings[k + 1], j + 1);
            out.push_back({a, c, d});
            out.push_back({a, d, b});
        }
}
} // namespace

TEST(RadialGrid, BlockOrderDrawsEveryQuadOnce) {
    // The same triangles as row order (as sets), for the full grid and a thinned ring selection.
    const RadialGrid grid(RadialGridDesc{.rings = 20, .segments = 30, .rMax = 1000.0});
    for (const std::vector<int>& rings : {grid.ringsFor({}, 0.0), std::vector<int>{0, 3, 4, 9, 19, 20, 35}}) {
        const std::vector<uint32_t> idx = grid.indicesFor(rings);
        std::vector<std::array<uint32_t, 3>> got, want;
        for (size_t t = 0; t < idx.size(); t += 3)
            got.push_back({idx[t], idx[t + 1], idx[t + 2]});
        for (int j = 0; j < 30; ++j)
            want.push_back({0u, grid.vertexIndex(rings[0], j), grid.vertexIndex(rings[0], j + 1)});
        appendRowOrderQuads(want, grid, rings, 0);
        std::sort(got.begin(), got.end());
        std::sort(want.begin(), want.end());
        EXPECT_EQ(got, want);
    }
}

namespace {
pacifica::CameraFrame cameraAt(double height, double headingDeg, double pitchDeg, double rollDeg) {
    pacifica::Pose pose;
    pose.position = {-3.0e6, 5.0e6, height};
    pose.headingDeg = headingDeg;
    pose.pitchDeg = pitchDeg;
    pose.rollDeg = rollDeg;
    return pacifica::makeCameraFrame(pose, static_cast<float>(60.0 * PI / 180.0), 16.0f / 9.0f, 0.05f);
}
bool inFrustum(const pacifica::CameraFrame& cam, const glm::dvec3& rel) {
    const glm::dvec4 c = glm::dmat4(cam.viewProj) * glm::dvec4(rel, 1.0);
    return c.w > 0.0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w;
}
} // namespace

TEST(HiddenDisc, LevelCameraHidesTheSeaBelowItsBottomEdge) {
    // Pitched 3 deg down with a 60 deg vertical fov, the bottom edge looks 33 deg down: the sea's highest
    // points (a above mean sea level) are hidden out to (h - a) / tan(33 deg).
    for (double h : {20.0, 3000.0})
        for (double a : {0.0, 1.5}) {
            const double r = pacifica::ocean::hiddenDiscRadius(cameraAt(h, 70.0, -3.0, 0.0), a);
            EXPECT_NEAR(r, (h - a) / std::tan(33.0 * PI / 180.0), 1e-5 * r) << h << " m, reach " << a;
        }
    // Within the waves' reach nothing is hidden.
    EXPECT_EQ(pacifica::ocean::hiddenDiscRadius(cameraAt(1.0, 70.0, -3.0, 0.0), 1.5), 0.0);
    // Looking 40 deg up, the bottom plane rises 10 deg ahead and falls 10 deg behind the camera: one plane
    // alone hides the disc out to (h - a) / tan(10 deg) (the sea beyond, behind, is outside the others).
    const double up = pacifica::ocean::hiddenDiscRadius(cameraAt(20.0, 70.0, 40.0, 0.0), 1.5);
    EXPECT_NEAR(up, 18.5 / std::tan(10.0 * PI / 180.0), 1e-5 * up);
    // Looking straight down the nadir is in view.
    EXPECT_EQ(pacifica::ocean::hiddenDiscRadius(cameraAt(500.0, 0.0, -90.0, 0.0), 1.5), 0.0);
}

TEST(HiddenDisc, NoPointOfTheHiddenDiscIsInView) {
    // Points of the disc at any radius <= R, any azimuth and any height within the reach (and lowered by a
    // curvature drop) lie outside the frustum, over many attitudes; and the bound is tight for a level roll:
    // just beyond R straight ahead at the top of the reach the sea is in view.
    uint32_t state = 12345u;
    auto uniform = [&state]() {
        state = state * 1664525u + 1013904223u;
        return double(state >> 8) / double(1u << 24);
    };
    int hiddenViews = 0;
    for (double h : {0.8, 20.0, 500.0, 15000.0})
        for (double pitch : {-89.0, -60.0, -35.0, -10.0, -3.0, 0.0, 20.0})
            for (double roll : {0.0, 30.0, -75.0})
                for (double heading : {0.0, 133.0}) {
                    const pacifica::CameraFrame cam = cameraAt(h, heading, pitch, roll);
                    const double reach = 0.5;
                    const double r = pacifica::ocean::hiddenDiscRadius(cam, reach);
                    ASSERT_TRUE(std::isfinite(r) && r >= 0.0);
                    if (r == 0.0)
                        continue;
                    ++hiddenViews;
                    for (int k = 0; k < 2000; ++k) {
                        const double rho = r * std::sqrt(uniform()), az = 2.0 * PI * uniform();
                        const double z = -h + reach * (2.0 * uniform() - 1.0) - 0.1 * uniform();
                        const glm::dvec3 p(rho * std::cos(az), rho * std::sin(az), z);
                        ASSERT_FALSE(inFrustum(cam, p)) << h << " m pitch " << pitch << " roll " << roll;
                    }
                    if (roll == 0.0 && pitch > -60.0) {
                        const double az = (90.0 - heading) * PI / 180.0; // ahead
                        const glm::dvec3 p(1.001 * r * std::cos(az), 1.001 * r * std::sin(az), -h + reach);
                        EXPECT_TRUE(inFrustum(cam, p)) << h << " m pitch " << pitch;
                    }
                }
    EXPECT_GT(hiddenViews, 20);
}

TEST(RadialGrid, RangesFromLeaveOutTheFanAndTheInnerRingPairs) {
    const RadialGrid grid(RadialGridDesc{.rings = 20, .segments = 30, .rMax = 1000.0});
    const std::vector<int> rings{0, 3, 4, 9, 19, 20, 35};
    const std::vector<uint32_t> idx = grid.indicesFor(rings);
    const auto all = grid.rangesFrom(rings.size(), 0);
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(all[0].first, 0u);
    EXPECT_EQ(all[0].count, idx.size());
    for (size_t firstPair : {size_t(1), size_t(3), size_t(5)}) {
        std::vector<std::array<uint32_t, 3>> got, want;
        for (const auto& range : grid.rangesFrom(rings.size(), firstPair)) {
            ASSERT_EQ(range.count % 3, 0u);
            ASSERT_LE(range.first + range.count, idx.size());
            for (size_t t = range.first; t < range.first + range.count; t += 3)
                got.push_back({idx[t], idx[t + 1], idx[t + 2]});
        }
        appendRowOrderQuads(want, grid, rings, firstPair);
        std::sort(got.begin(), got.end());
        std::sort(want.begin(), want.end());
        EXPECT_EQ(got, want) << "first pair " << firstPair;
    }
    EXPECT_TRUE(grid.rangesFrom(rings.size(), rings.size() - 1).empty()); // every pair hidden
    // ringRadius() is the stored radius, skirt included.
    EXPECT_FLOAT_EQ(static_cast<float>(grid.ringRadius(19)), 1000.0f);
    EXPECT_FLOAT_EQ(static_cast<float>(grid.ringRadius(35)), 1e6f);
}
