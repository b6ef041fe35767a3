// Unit tests of the projected grid (ocean/ProjectedGrid.h, Johanson 2004 §2.3-2.4): the mesh, validation,
// and above all coverage without gaps. For a sweep of camera poses (altitudes 0.5 m to 15 km, pitches from
// straight down to 45 degrees up, several headings and rolls up to +-60 degrees, at the origin and 10^7 m
// from it, flat and curved sea, with and without the wave bound), every screen sample whose ray hits the
// sea - an independent ray/drop-surface intersection in double - must map back into the grid's (u, v)
// square, including a dense row just below the horizon; `visible` is false exactly when no sample meets the
// displaceable volume; and no point of the grid lies behind the camera.
#include "engine/Space.h"
#include "ocean/OceanConstants.h"
#include "ocean/ProjectedGrid.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

using pacifica::CameraFrame;
using pacifica::Pose;
using pacifica::ocean::ProjectedGrid;
using pacifica::ocean::ProjectedGridDesc;

namespace {

constexpr double PI = 3.14159265358979323846;
constexpr double DEG = PI / 180.0;

CameraFrame makeCamera(glm::dvec2 xy, double altitude, double heading, double pitch, double roll,
                       double fovYDeg = 60.0, double aspect = 16.0 / 9.0) {
    Pose pose;
    pose.position = glm::dvec3(xy, altitude);
    pose.headingDeg = heading;
    pose.pitchDeg = pitch;
    pose.rollDeg = roll;
    return pacifica::makeCameraFrame(pose, static_cast<float>(fovYDeg * DEG), static_cast<float>(aspect),
                                     0.1f);
}

/// Where the ray from the camera along `dir` first meets the sea z = -h - d^2 / 2R (d: horizontal distance;
/// flat when R = 0), as the hit's camera-relative (x, y); nothing if it misses. Solves
/// (rho^2 / 2R) t^2 + dir.z t + h = 0 for the smaller positive root, written without cancellation.
std::optional<glm::dvec2> seaHit(const glm::dvec3& dir, double h, double R) {
    const double a = R > 0.0 ? (dir.x * dir.x + dir.y * dir.y) / (2.0 * R) : 0.0;
    if (dir.z >= 0.0)
        return std::nullopt;
    const double disc = dir.z * dir.z - 4.0 * a * h;
    if (disc < 0.0)
        return std::nullopt;
    const double t = 2.0 * h / (-dir.z + std::sqrt(disc));
    return glm::dvec2(dir) * t;
}

/// Whether the ray meets the displaceable volume: reaches the upper bound surface z = -h + D - d^2 / 2R
/// (at once when the camera is inside), no farther than `cap` horizontally.
bool volumeHit(const glm::dvec3& dir, double h, double D, double R, double cap) {
    if (h <= D)
        return true;
    const std::optional<glm::dvec2> hit = seaHit(dir, h - D, R);
    return hit && glm::length(*hit) <= cap;
}

/// (u, v) of a camera-relative base-plane point under the frame's homography, from its corners alone:
/// the blend c0 + u (c1 - c0) + v (c2 - c0) (exact bilinear because c3 = c1 + c2 - c0, checked separately)
/// is homogeneous (x, y, w) = w (x/w, y/w, 1), so M^-1 (x, y, 1) = (u, v, 1) / w with w > 0.
std::optional<glm::dvec2> uvOf(const ProjectedGrid::Frame& f, glm::dvec2 p) {
    auto xyw = [](const glm::dvec4& c) { return glm::dvec3(c.x, c.y, c.w); };
    const glm::dmat3 m(xyw(f.corners[1]) - xyw(f.corners[0]), xyw(f.corners[2]) - xyw(f.corners[0]),
                       xyw(f.corners[0]));
    const glm::dvec3 s = glm::inverse(m) * glm::dvec3(p, 1.0);
    if (!(s.z > 0.0))
        return std::nullopt;
    return glm::dvec2(s.x, s.y) / s.z;
}

/// Direction (camera-relative world) of the ray through NDC (x, y), from the inverse of the GPU's matrix.
glm::dvec3 rayThroughNdc(const glm::dmat4& invViewProj, double x, double y) {
    const glm::dvec4 p = invViewProj * glm::dvec4(x, y, 1.0, 1.0); // a point on the near plane
    return glm::dvec3(p) / p.w;
}

bool onScreen(const glm::dmat4& viewProj, const glm::dvec3& dir) {
    const glm::dvec4 c = viewProj * glm::dvec4(dir, 1.0);
    return c.w > 0.0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w;
}

struct SweepStats {
    int frames = 0, visibleFrames = 0;
    long long seaSamples = 0, horizonSamples = 0, uncovered = 0, behind = 0, visibleMismatch = 0;
    double minMargin = 1e9; ///< smallest distance of a covered sea sample to the edge of the (u, v) square
    std::string minMarginAt;
};

/// All poses of the sweep for one grid description and curvature radius; EXPECTs on every failure (the
/// first few reported in full) and returns counts.
SweepStats sweep(const ProjectedGridDesc& desc, double R, double tolerance = 0.0) {
    const ProjectedGrid grid(desc);
    SweepStats st;
    int reported = 0;
    auto report = [&](const std::string& what) {
        if (++reported <= 12)
            ADD_FAILURE() << what;
        else if (reported == 13)
            ADD_FAILURE() << "(further failures not listed)";
    };
    const double altitudes[] = {0.5, 2.0, 10.0, 100.0, 1000.0, 5000.0, 15000.0};
    const double pitches[] = {-90.0, -60.0, -30.0, -10.0, -3.0, 0.0, 3.0, 10.0, 45.0};
    const double headingRolls[][2] = {{0.0, 0.0},    {0.0, 60.0},    {0.0, -60.0},  {137.5, 0.0},
                                      {137.5, 25.0}, {290.0, -45.0}, {290.0, 60.0}, {45.0, -30.0}};
    const glm::dvec2 positions[] = {{0.0, 0.0}, {1e7, -1e7}};
    // Rays that reach the flat sea less than FLAT_HORIZON_GAP below eye level are the documented cut.
    for (const glm::dvec2& xy : positions)
        for (double h : altitudes)
            for (double pitch : pitches)
                for (const auto& hr : headingRolls) {
                    const CameraFrame cam = makeCamera(xy, h, hr[0], pitch, hr[1]);
                    const ProjectedGrid::Frame f = grid.frame(cam, R);
                    ++st.frames;
                    const std::string pose = "h=" + std::to_string(h) + " pitch=" + std::to_string(pitch) +
                                             " heading=" + std::to_string(hr[0]) +
                                             " roll=" + std::to_string(hr[1]) + " R=" + std::to_string(R) +
                                             " maxD=" + std::to_string(desc.maxDisplacement);
                    const glm::dmat4 vp(cam.viewProj);
                    const glm::dmat4 inv = glm::inverse(vp);
                    const double flatCap = std::max(h, 1.0) / std::tan(ProjectedGrid::FLAT_HORIZON_GAP);
                    const double cap = R > 0.0 ? 1e300 : flatCap;

                    std::vector<glm::dvec3> samples;
                    for (int j = 0; j < 36; ++j) // 64 x 36, the outermost on the screen's edges
                        for (int i = 0; i < 64; ++i)
                            samples.push_back(
                                rayThroughNdc(inv, -1.0 + 2.0 * i / 63.0, -1.0 + 2.0 * j / 35.0));
                    const size_t gridSamples = samples.size();
                    // The dense row(s): every 1/20 degree of azimuth, 1e-3, 1e-4 and 2e-5 rad below the
                    // horizon of the (curved) sea, wherever that lies on the screen.
                    const double dip = R > 0.0 ? std::atan(std::sqrt(2.0 * h / R)) : 0.0;
                    for (double below : {1e-3, 1e-4, 2e-5})
                        for (int k = 0; k < 7200; ++k) {
                            const double az = k * 2.0 * PI / 7200.0, e = -dip - below;
                            const glm::dvec3 d(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az),
                                               std::sin(e));
                            if (onScreen(vp, d))
                                samples.push_back(d);
                        }

                    bool anyVolume = false;
                    for (size_t s = 0; s < samples.size(); ++s) {
                        const glm::dvec3& d = samples[s];
                        anyVolume = anyVolume || volumeHit(d, h, desc.maxDisplacement, R, cap);
                        const std::optional<glm::dvec2> hit = seaHit(d, h, R);
                        if (!hit || glm::length(*hit) > cap)
                            continue;
                        ++(s < gridSamples ? st.seaSamples : st.horizonSamples);
                        const std::optional<glm::dvec2> uv = f.visible ? uvOf(f, *hit) : std::nullopt;
                        const glm::dvec2 at = uv.value_or(glm::dvec2(-1.0));
                        const double margin = std::min({at.x, 1.0 - at.x, at.y, 1.0 - at.y});
                        if (margin < st.minMargin) {
                            st.minMargin = margin;
                            st.minMarginAt = pose + " sample " + std::to_string(s) +
                                             " (grid samples: " + std::to_string(gridSamples) + ")";
                        }
                        if (margin < -tolerance) {
                            ++st.uncovered;
                            report("sea sample not covered: " + pose + " dir=(" + std::to_string(d.x) + ", " +
                                   std::to_string(d.y) + ", " + std::to_string(d.z) + ") hit at " +
                                   std::to_string(glm::length(*hit)) + " m, visible=" +
                                   std::to_string(f.visible) + " uv=(" + std::to_string(at.x) + ", " +
                                   std::to_string(at.y) + ")" + (uv ? "" : " (behind the homography)"));
                        }
                    }
                    if (f.visible != anyVolume) {
                        ++st.visibleMismatch;
                        report("visible=" + std::to_string(f.visible) + " but a sample meets the volume: " +
                               std::to_string(anyVolume) + " at " + pose);
                    }
                    if (!f.visible)
                        continue;
                    ++st.visibleFrames;

                    // The homography: affine blend (c3 = c1 + c2 - c0), w > 0 at the corners.
                    const glm::dvec4 affine = f.corners[1] + f.corners[2] - f.corners[0] - f.corners[3];
                    double scale = 0.0;
                    for (const glm::dvec4& c : f.corners)
                        scale = std::max(scale, glm::length(c));
                    EXPECT_LT(glm::length(affine), 1e-12 * scale) << pose;
                    for (const glm::dvec4& c : f.corners)
                        EXPECT_GT(c.w, 0.0) << pose;

                    // No grid point behind the camera: clip w > 0 for the dropped (undisplaced) surface on a
                    // 65 x 65 lattice of (u, v) and 1025 points along each edge. From inside the wave volume
                    // (h < maxD) the grid must also reach the base points under crests that rise in front of
                    // the camera, which can lie behind it: there every grid point must be in front for some
                    // displacement within the bound (w is linear in z, so one of the two bounds).
                    const bool inside = h < desc.maxDisplacement;
                    auto clipW = [&](glm::dvec2 uv) {
                        const glm::dvec2 p = f.gridPoint(uv);
                        const double z = -h - (R > 0.0 ? glm::dot(p, p) / (2.0 * R) : 0.0);
                        const double w = (vp * glm::dvec4(p, z, 1.0)).w;
                        if (!inside)
                            return w;
                        const double D = desc.maxDisplacement;
                        return std::max((vp * glm::dvec4(p, z - D, 1.0)).w,
                                        (vp * glm::dvec4(p, z + D, 1.0)).w);
                    };
                    double minW = 1e300;
                    for (int j = 0; j <= 64; ++j)
                        for (int i = 0; i <= 64; ++i)
                            minW = std::min(minW, clipW({i / 64.0, j / 64.0}));
                    for (int i = 0; i <= 1024; ++i) {
                        const double s = i / 1024.0;
                        minW = std::min(
                            {minW, clipW({s, 0.0}), clipW({s, 1.0}), clipW({0.0, s}), clipW({1.0, s})});
                    }
                    if (!(minW > 0.0)) {
                        ++st.behind;
                        report("grid point behind the camera (clip w = " + std::to_string(minW) + ") at " +
                               pose);
                    }
                }
    return st;
}

void print(const char* name, const SweepStats& s) {
    std::printf(
        "[%s] %d poses, %d visible; %lld sea samples on the 64x36 grids + %lld just below the "
        "horizon; uncovered %lld; visible mismatches %lld; frames with a grid point behind the camera "
        "%lld; smallest (u, v) margin of a sea sample %.3g\n",
        name, s.frames, s.visibleFrames, s.seaSamples, s.horizonSamples, s.uncovered, s.visibleMismatch,
        s.behind, s.minMargin);
    std::printf("  smallest margin at %s\n", s.minMarginAt.c_str());
}

void expectClean(const SweepStats& s) {
    EXPECT_EQ(s.uncovered, 0);
    EXPECT_EQ(s.visibleMismatch, 0);
    EXPECT_EQ(s.behind, 0);
    EXPECT_GT(s.seaSamples, 0);
    EXPECT_GT(s.horizonSamples, 0);
    EXPECT_GT(s.visibleFrames, 0);
    EXPECT_LT(s.visibleFrames, s.frames); // some poses look only at the sky
}

} // namespace

TEST(ProjectedGrid, MeshIsARegularUVGridWoundCounterClockwise) {
    const ProjectedGrid grid(ProjectedGridDesc{.resolutionX = 5, .resolutionY = 7});
    const unsigned rows = 7 + ProjectedGrid::HORIZON_ROWS;
    ASSERT_EQ(grid.vertexCount(), 5u * rows);
    ASSERT_EQ(grid.indices().size(), 6u * 4u * (rows - 1));
    const std::vector<float>& v = grid.vertices();
    EXPECT_FLOAT_EQ(v[0], 0.0f);
    EXPECT_FLOAT_EQ(v[1], 0.0f);
    EXPECT_FLOAT_EQ(v[2 * 4], 1.0f); // end of the first row: u = 1, v = 0
    EXPECT_FLOAT_EQ(v[2 * (5 * rows - 1) + 1], 1.0f);
    // Evenly spaced rows up to v = 5/6, then the last cell subdivided towards v = 1, strictly increasing.
    EXPECT_FLOAT_EQ(v[2 * 5 * 5 + 1], 5.0f / 6.0f);
    for (unsigned r = 1; r < rows; ++r)
        EXPECT_LT(v[2 * 5 * (r - 1) + 1], v[2 * 5 * r + 1]) << "row " << r;
    for (size_t t = 0; t < grid.indices().size(); t += 3) {
        const uint32_t a = grid.indices()[t], b = grid.indices()[t + 1], c = grid.indices()[t + 2];
        ASSERT_LT(std::max({a, b, c}), grid.vertexCount());
        const double cross = (v[2 * b] - v[2 * a]) * (v[2 * c + 1] - v[2 * a + 1]) -
                             (v[2 * b + 1] - v[2 * a + 1]) * (v[2 * c] - v[2 * a]);
        EXPECT_GT(cross, 0.0) << "triangle " << t / 3;
    }
    const ProjectedGrid defaults{ProjectedGridDesc{}};
    EXPECT_EQ(defaults.vertexCount(), 256u * (512u + ProjectedGrid::HORIZON_ROWS));
}

TEST(ProjectedGrid, InvalidDescriptionsAndFramesNameTheField) {
    auto message = [](auto&& fn) {
        try {
            fn();
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    auto desc = [&](const ProjectedGridDesc& d) { return message([&] { ProjectedGrid g(d); }); };
    EXPECT_NE(desc({.resolutionX = 1}).find("ProjectedGridDesc.resolutionX"), std::string::npos);
    EXPECT_NE(desc({.resolutionY = 9000}).find("ProjectedGridDesc.resolutionY"), std::string::npos);
    EXPECT_NE(desc({.maxDisplacement = -1.0}).find("ProjectedGridDesc.maxDisplacement"), std::string::npos);
    EXPECT_NE(desc({.maxDisplacement = NAN}).find("ProjectedGridDesc.maxDisplacement"), std::string::npos);
    EXPECT_NE(desc({.guardBand = -0.1}).find("ProjectedGridDesc.guardBand"), std::string::npos);
    EXPECT_NE(desc({.guardBand = INFINITY}).find("ProjectedGridDesc.guardBand"), std::string::npos);
    EXPECT_EQ(desc({}), "no error");

    const ProjectedGrid grid({});
    const CameraFrame cam = makeCamera({0, 0}, 100.0, 0, -10, 0);
    EXPECT_NE(message([&] { grid.frame(cam, -1.0); }).find("curvatureRadius"), std::string::npos);
    EXPECT_NE(message([&] { grid.frame(cam, NAN); }).find("curvatureRadius"), std::string::npos);
    CameraFrame bad = cam;
    bad.origin.z = INFINITY;
    EXPECT_NE(message([&] { grid.frame(bad, 0.0); }).find("camera.origin.z"), std::string::npos);
    bad = cam;
    bad.proj = glm::mat4(1.0f); // orthographic identity: not a perspective projection
    EXPECT_NE(message([&] { grid.frame(bad, 0.0); }).find("camera.proj"), std::string::npos);
}

TEST(ProjectedGrid, SameGridAnywhereOnThePlane) {
    // Only the camera's height enters: the grid 10^7 m from the origin is bit-identical to the one above it.
    const ProjectedGrid grid({});
    for (double pitch : {-90.0, -20.0, 0.0, 10.0}) {
        const ProjectedGrid::Frame a = grid.frame(makeCamera({0, 0}, 320.0, 40.0, pitch, 15.0), 6371000.0);
        const ProjectedGrid::Frame b =
            grid.frame(makeCamera({1e7, -1e7}, 320.0, 40.0, pitch, 15.0), 6371000.0);
        ASSERT_TRUE(a.visible && b.visible);
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 4; ++k)
                EXPECT_EQ(a.corners[i][k], b.corners[i][k]);
    }
}

TEST(ProjectedGrid, GridPointAndFloatUniformsAgreeWithTheHomography) {
    const ProjectedGrid grid({});
    const ProjectedGrid::Frame f = grid.frame(makeCamera({0, 0}, 50.0, 200.0, -5.0, 20.0), 6371000.0);
    ASSERT_TRUE(f.visible);
    // Counter-clockwise in (u, v) is counter-clockwise seen from above (+z): u runs to the right, v away.
    const glm::dvec2 a = f.gridPoint({0.0, 0.0}), b = f.gridPoint({1.0, 0.0}), c = f.gridPoint({1.0, 1.0});
    EXPECT_GT((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x), 0.0);
    const std::array<glm::vec4, 4> u = f.cornerUniforms();
    for (double uu : {0.0, 0.3, 1.0})
        for (double vv : {0.0, 0.5, 0.99, 1.0}) {
            const glm::dvec2 p = f.gridPoint({uu, vv});
            const std::optional<glm::dvec2> back = uvOf(f, p);
            ASSERT_TRUE(back.has_value());
            EXPECT_NEAR(back->x, uu, 1e-9);
            EXPECT_NEAR(back->y, vv, 1e-9);
            // What the shader computes in float: the blend of the float corners, divided by w. Float
            // rounding of the corners (2^-24 relative) and of the blend move the point by ~1e-6 relative.
            const glm::vec4 hq =
                glm::mix(glm::mix(u[0], u[1], float(uu)), glm::mix(u[2], u[3], float(uu)), float(vv));
            const glm::dvec2 pf = glm::dvec2(hq.x, hq.y) / double(hq.w);
            EXPECT_LT(glm::length(pf - p), 1e-5 * glm::length(p) + 1e-6) << uu << " " << vv;
        }
}

TEST(ProjectedGrid, LookingUpFromAboveTheWavesSeesNothing) {
    const ProjectedGrid grid({});
    EXPECT_FALSE(grid.frame(makeCamera({0, 0}, 10.0, 0.0, 90.0, 0.0), 6371000.0).visible);
    EXPECT_FALSE(grid.frame(makeCamera({0, 0}, 100.0, 30.0, 45.0, 0.0), 0.0).visible);
    // Inside the wave volume (0.5 m < 3 m), a crest could rise into any view: the grid is drawn.
    EXPECT_TRUE(grid.frame(makeCamera({0, 0}, 0.5, 0.0, 90.0, 0.0), 6371000.0).visible);
    // Without the wave bound, straight up from 0.5 m sees no sea.
    const ProjectedGrid calm(ProjectedGridDesc{.maxDisplacement = 0.0});
    EXPECT_FALSE(calm.frame(makeCamera({0, 0}, 0.5, 0.0, 90.0, 0.0), 6371000.0).visible);
}

TEST(ProjectedGrid, CoversTheCurvedSeaWithWaveBound) {
    const SweepStats s = sweep(ProjectedGridDesc{}, pacifica::ocean::EARTH_RADIUS);
    print("curved, maxDisplacement 3", s);
    expectClean(s);
}

TEST(ProjectedGrid, CoversTheFlatSeaWithWaveBound) {
    const SweepStats s = sweep(ProjectedGridDesc{}, 0.0);
    print("flat, maxDisplacement 3", s);
    expectClean(s);
}

TEST(ProjectedGrid, CoversTheCalmCurvedSeaAndVisibleMeansSeaInView) {
    // With no wave bound the volume is the sea surface itself: visible == some sample hits the sea. With no
    // guard band either, the grid's edges are the screen's: the samples on the screen's edges land on them,
    // up to the rounding of the float camera matrices (~1e-7), hence the 1e-6 tolerance in (u, v).
    const SweepStats s = sweep(ProjectedGridDesc{.maxDisplacement = 0.0, .guardBand = 0.0},
                               pacifica::ocean::EARTH_RADIUS, 1e-6);
    print("curved, calm, no guard band", s);
    expectClean(s);
}

TEST(ProjectedGrid, CoversTheCalmFlatSea) {
    // As above: no guard band, so the edge samples lie on the grid's edges (1e-6 for float rounding).
    const SweepStats s = sweep(ProjectedGridDesc{.maxDisplacement = 0.0, .guardBand = 0.0}, 0.0, 1e-6);
    print("flat, calm, no guard band", s);
    expectClean(s);
}

TEST(ProjectedGrid, OtherFieldsOfView) {
    // Narrow (telephoto) and wide square views, curved sea, a smaller sweep of attitudes.
    const ProjectedGrid grid({});
    long long checked = 0;
    for (double fov : {10.0, 100.0})
        for (double h : {0.5, 30.0, 15000.0})
            for (double pitch : {-90.0, -45.0, -5.0, 0.0, 20.0})
                for (double roll : {0.0, 50.0}) {
                    const CameraFrame cam =
                        makeCamera({3e6, 2e6}, h, 70.0, pitch, roll, fov, fov > 50 ? 1.0 : 2.4);
                    const double R = pacifica::ocean::EARTH_RADIUS;
                    const ProjectedGrid::Frame f = grid.frame(cam, R);
                    const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.viewProj));
                    for (int j = 0; j <= 40; ++j)
                        for (int i = 0; i <= 40; ++i) {
                            const glm::dvec3 d = rayThroughNdc(inv, -1.0 + i / 20.0, -1.0 + j / 20.0);
                            const std::optional<glm::dvec2> hit = seaHit(d, h, R);
                            if (!hit)
                                continue;
                            ++checked;
                            ASSERT_TRUE(f.visible) << fov << " " << h << " " << pitch << " " << roll;
                            const std::optional<glm::dvec2> uv = uvOf(f, *hit);
                            ASSERT_TRUE(uv.has_value());
                            EXPECT_TRUE(uv->x >= 0.0 && uv->x <= 1.0 && uv->y >= 0.0 && uv->y <= 1.0)
                                << "fov " << fov << " h " << h << " pitch " << pitch << " roll " << roll
                                << " uv " << uv->x << ", " << uv->y;
                        }
                }
    EXPECT_GT(checked, 10000);
}

TEST(ProjectedGrid, GuardBandExtendsCoverageBeyondTheScreen) {
    // Sea seen through NDC up to 1 + 0.99 g beyond the centre is covered with guardBand g, and without a
    // guard band some of it is not (the grid then ends at the screen's edges).
    const double R = pacifica::ocean::EARTH_RADIUS, g = 0.2;
    const ProjectedGrid guarded(ProjectedGridDesc{.guardBand = g});
    const ProjectedGrid bare(ProjectedGridDesc{.maxDisplacement = 0.0, .guardBand = 0.0});
    long long inGuard = 0, missedWithout = 0;
    for (double h : {0.5, 40.0, 3000.0})
        for (double pitch : {-90.0, -35.0, -4.0, 8.0})
            for (double roll : {0.0, -35.0}) {
                const CameraFrame cam = makeCamera({0, 0}, h, 10.0, pitch, roll);
                const ProjectedGrid::Frame f = guarded.frame(cam, R), b = bare.frame(cam, R);
                const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.viewProj));
                for (int j = 0; j <= 60; ++j)
                    for (int i = 0; i <= 60; ++i) {
                        const double x = (1.0 + 0.99 * g) * (-1.0 + i / 30.0),
                                     y = (1.0 + 0.99 * g) * (-1.0 + j / 30.0);
                        if (std::abs(x) <= 1.0 && std::abs(y) <= 1.0)
                            continue;
                        const std::optional<glm::dvec2> hit = seaHit(rayThroughNdc(inv, x, y), h, R);
                        if (!hit)
                            continue;
                        ++inGuard;
                        ASSERT_TRUE(f.visible);
                        const std::optional<glm::dvec2> uv = uvOf(f, *hit);
                        ASSERT_TRUE(uv.has_value());
                        EXPECT_TRUE(uv->x >= 0.0 && uv->x <= 1.0 && uv->y >= 0.0 && uv->y <= 1.0)
                            << "h " << h << " pitch " << pitch << " roll " << roll << " ndc " << x << ", "
                            << y;
                        const std::optional<glm::dvec2> uvBare = b.visible ? uvOf(b, *hit) : std::nullopt;
                        const glm::dvec2 at = uvBare.value_or(glm::dvec2(-1.0));
                        missedWithout += !(at.x >= 0.0 && at.x <= 1.0 && at.y >= 0.0 && at.y <= 1.0);
                    }
            }
    EXPECT_GT(inGuard, 1000);
    EXPECT_GT(missedWithout, inGuard / 2);
}
