// Effects on the GPU (ctest labels gl, effects, stability):
// - only what the scene calls for: a frame without effects has no effect pass, draw, upload or shader
//   variant; with explosions only, the wake kind does nothing; removing the effects returns the frame to
//   exactly the plain ocean's counters;
// - readback: the secondary grids' displaced vertices equal the CPU twin of what the GPU draws (the base
//   surface plus sampleEffectField(): the effects field's texels evaluated in double, read as the shaders
//   read them) within 1e-3 m, and the analytic oceanHeightAt() within the field's stated interpolation
//   bound, for an explosion near the camera, at r = 0 just after t = 0, 40 km away (outside the field: no
//   effect drawn), at 10^7 m from the origin at t = 10^6 s, 64 overlapping ones, a ship in a tight circle;
//   every captured value and every pixel finite;
// - the field's view cull changes no pixel, for every surface model, looking along, across and away;
// - a wake is visible from 10 km altitude; a carrier's wake foam runs along its track from 3 km and follows
//   the CPU's field;
// - the component's API: spans in draw what the registry adapter draws; bad scenes are refused as a Status
//   naming the field, before any GL work.
#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanDebug.h"
#include "ocean/OceanHost.h"
#include "ocean/RadialGrid.h"

#include "OceanTestFrame.h"

#include "GlLayerTest.h"
#include <epoxy/gl.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

using namespace pacifica;
using namespace pacifica::ocean;

namespace {

constexpr int W = 320, H = 180;
/// |GPU - analytic| of a wake read from the effects field 200-500 m from the camera (2 m texels there):
/// Kelvin's divergent waves shorter than 8 texels fade out of the level (EffectFieldLevel::kMax) and
/// bilinear reading smooths the rest (measured 0.21 m straight, 0.07 m in a tight circle).
constexpr double WAKE_FIELD_BOUND = 0.3;

class EffectsGl : public gltest::GlTest {
protected:
    ecs::Registry registry;
    ecs::EventQueue events;
    ecs::Entity oceanEntity = registry.create();
    OceanRenderer renderer;
    gl::FrameTargets targets{W, H};

    // Most tests here are about the secondary grids: every effect in view gets one (by default only the few
    // next to the eye do: DefaultGridsOnlyNextToTheEye).
    EffectsGl() { registry.emplace<OceanComponent>(oceanEntity, makeOcean(gridsDesc())); }

    static OceanDesc gridsDesc() {
        OceanDesc d;
        d.effectGrids.minAngularSize = d.effectGrids.minAmplitudePixels = 0.0;
        d.effectGrids.maxExplosionGrids = d.effectGrids.maxWakeGrids = 1024;
        return d;
    }

    /// The largest |GPU - analytic oceanHeightAt()| of the last compareWithCpu() call.
    double analyticError = 0.0;

    OceanFrame frameAt(const glm::dvec3& camera, double headingDeg, double pitchDeg, double t) const {
        return gltest::oceanFrameAt(camera, headingDeg, pitchDeg, t, targets.sceneFramebuffer().id(), W, H);
    }

    size_t nonFinitePixels() const {
        std::vector<float> rgba;
        targets.readScene(rgba);
        size_t bad = 0;
        for (float v : rgba)
            bad += !std::isfinite(v);
        return bad;
    }

    /// Every captured vertex of `kind` at its grid's centre + vLocal (double) against the CPU twin: the base
    /// surface plus sampleEffectField(). Returns the largest error (and the largest against the analytic
    /// oceanHeightAt() in analyticError); fails on a non-finite value.
    double compareWithCpu(const OceanFrame& frame, EffectKind kind, size_t expectedGrids) {
        const auto vertices = ocean::debug::effectVertices(renderer, registry, oceanEntity, frame, kind);
        EXPECT_FALSE(vertices.empty());
        if (vertices.empty())
            return 0.0;
        const size_t perInstance = vertices.size() / expectedGrids;
        EXPECT_EQ(perInstance * expectedGrids, vertices.size());
        const glm::dvec3 cam = frame.camera.origin;
        const OceanComponent& ocean = registry.get<OceanComponent>(oceanEntity);
        const EffectFieldLayout layout = effectFieldLayout(ocean.desc.effectField, frame);
        const RegistryEffects effects(registry);
        double worst = 0.0;
        analyticError = 0.0;
        for (size_t i = 0; i < vertices.size(); ++i) {
            const auto& v = vertices[i];
            if (!(std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z) &&
                  std::isfinite(v.local.x) && std::isfinite(v.local.y))) {
                ADD_FAILURE() << "non-finite vertex " << i;
                return 1e30;
            }
            const glm::dvec2 centre = v.centre;
            const glm::dvec2 world = centre + glm::dvec2(v.local);
            // Undo the curvature drop the shader applied at the undisplaced point (octaves: = displaced).
            const glm::dvec2 rel = glm::dvec2(glm::vec2(centre - glm::dvec2(cam)) + v.local);
            const double gpu = double(v.position.z) + cam.z + curvatureDrop(glm::length(rel));
            const double sea = ocean.surface->heightAt(world, frame.time);
            const double twin = sea + sampleEffectField(effects.view(), layout, world, frame.time).x;
            worst = std::max(worst, std::abs(gpu - twin));
            const double analytic = sea + effectsAt(effects.view(), world, frame.time).x;
            analyticError = std::max(analyticError, std::abs(gpu - analytic));
        }
        return worst;
    }

    std::vector<glm::dvec2> explosionCentres(double t) {
        std::vector<glm::dvec2> c;
        registry.view<Explosion>().each([&](ecs::Entity, Explosion& e) {
            if (explosionState(e, t).radius > 0.0)
                c.push_back(e.center);
        });
        return c;
    }

    /// 1e-3 m (the required readback bound) plus one float spacing of the camera height and of the
    /// curvature drop (the GPU's z is camera-relative float).
    static double bound(const glm::dvec3& cam, double dropAtEffect) {
        const float z = static_cast<float>(std::abs(cam.z) + dropAtEffect);
        return 1e-3 + 2.0 * (double(std::nextafter(z, 2.0f * z + 1.0f)) - double(z));
    }
};

TEST_F(EffectsGl, AbsentEffectsCostNothingAndOnlyPresentKindsWork) {
    EffectsSystem fx(registry, events);
    const glm::dvec3 cam(0.0, 0.0, 60.0);
    // 1. Plain ocean, twice (the second frame is the steady state).
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 1.0));
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 1.1));
    const OceanStats plain = renderer.lastStats();
    EXPECT_EQ(plain.programsBuilt, 0);
    for (const EffectKindStats& k : {plain.explosions, plain.wakes}) {
        EXPECT_EQ(k.active, 0);
        EXPECT_EQ(k.passes, 0);
        EXPECT_EQ(k.draws, 0);
        EXPECT_EQ(k.uploads, 0);
        EXPECT_EQ(k.vertices, 0);
    }
    // 2. One explosion ahead: the field's compute pass and the explosion's grid pass, one extra draw,
    // uploads for its data (+ its grid mesh, the field's texture once) and the field's tile lists and grid
    // list; four new shader variants (the field pass; under compute shading, the default: the sea's G-buffer
    // reading the field with holes, the explosion grid's G-buffer, the shading pass reading the field -- by
    // tiles, as on llvmpipe, its two kinds with sea, the sky's kinds being shared); wakes nothing.
    events.enqueue(SpawnExplosion{{300.0, 0.0}, 1.0, 1.0});
    events.dispatch();
    fx.update(3.0, cam);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 3.0));
    OceanStats s = renderer.lastStats();
    ASSERT_TRUE(s.computeShaded);
    EXPECT_EQ(s.programsBuilt, s.shadeTiled ? 5 : 4);
    EXPECT_EQ(s.explosions.active, 1);
    EXPECT_EQ(s.explosions.drawn, 1);
    EXPECT_EQ(s.explosions.passes, 1);
    EXPECT_EQ(s.explosions.draws, 1);
    EXPECT_EQ(s.explosions.uploads, 3);            // vertex + index buffer of the grid, the explosion data
    EXPECT_EQ(s.explosions.vertices, 1 + 49 * 96); // centre, 48 rings, the skirt ring
    EXPECT_EQ(s.wakes.active + s.wakes.passes + s.wakes.draws + s.wakes.uploads, 0);
    EXPECT_EQ(s.wakes.vertices, 0);
    EXPECT_EQ(s.effectField.passes, 1);
    EXPECT_GT(s.effectField.tiles, 0);
    EXPECT_EQ(s.effectField.texels, 64LL * s.effectField.tiles);
    EXPECT_EQ(s.effectField.uploads, 4); // the texture cleared once, the tiles, their lists, the grid list
    EXPECT_EQ(s.passes, plain.passes + 2);
    EXPECT_EQ(s.draws, plain.draws + 1);
    EXPECT_EQ(s.uploads, plain.uploads + 7);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 3.1));
    EXPECT_EQ(renderer.lastStats().explosions.uploads, 1); // steady state: the data
    EXPECT_EQ(renderer.lastStats().effectField.uploads, 3);
    EXPECT_EQ(renderer.lastStats().programsBuilt, 0);
    EXPECT_EQ(nonFinitePixels(), 0u);
    // 3. Behind the camera: its field is evaluated (active) but its grid is not drawn.
    render(renderer, registry, frameAt(cam, 270.0, -15.0, 3.2));
    s = renderer.lastStats();
    EXPECT_GT(s.effectField.tiles, 0);
    EXPECT_EQ(s.explosions.active, 1);
    EXPECT_EQ(s.explosions.drawn, 0);
    EXPECT_EQ(s.explosions.draws, 0);
    EXPECT_EQ(s.explosions.vertices, 0);
    // 4. All effects gone: exactly the plain ocean's counters again.
    registry.clear();
    oceanEntity = registry.create();
    registry.emplace<OceanComponent>(oceanEntity, makeOcean(gridsDesc()));
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 4.0)); // new entity: rebuilds its grid
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 4.1));
    s = renderer.lastStats();
    EXPECT_EQ(s.passes, plain.passes);
    EXPECT_EQ(s.draws, plain.draws);
    EXPECT_EQ(s.uploads, plain.uploads);
    EXPECT_EQ(s.vertices, plain.vertices);
    EXPECT_EQ(s.programsBuilt, 0);
    EXPECT_EQ(s.explosions.uploads + s.wakes.uploads + s.explosions.draws + s.wakes.draws, 0);
    EXPECT_EQ(s.effectField.passes + s.effectField.tiles + s.effectField.uploads, 0);
}

// Pass timing (docs/PERFORMANCE.md): off by default (nothing measured, no query); on, every present pass
// has time, absent passes ~none, the passes add up to no more than the frame, and the image is unchanged.
TEST_F(EffectsGl, PassTimingMeasuresPresentPassesAndChangesNoPixel) {
    EffectsSystem fx(registry, events);
    const glm::dvec3 cam(0.0, 0.0, 60.0);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 1.0));
    EXPECT_FALSE(renderer.lastStats().passTimes.measured);
    EXPECT_STREQ(renderer.passTimingClock(), "");
    std::vector<float> untimed, timed;
    targets.readScene(untimed);

    renderer.setPassTiming(PassClock::WallAroundFinish);
    EXPECT_TRUE(std::string(renderer.passTimingClock()).find("glFinish") != std::string::npos);
    glFinish();
    const auto t0 = std::chrono::steady_clock::now();
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 1.0));
    const double frameMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    targets.readScene(timed);
    EXPECT_EQ(timed, untimed) << "timing must not change what is drawn";
    OceanPassTimes p = renderer.lastStats().passTimes;
    ASSERT_TRUE(p.measured);
    ASSERT_TRUE(renderer.lastStats().computeShaded); // the default: the sky is lit in the shading pass
    EXPECT_GT(p.shadeMs, 0.0);
    EXPECT_GT(p.seaMs, 0.0);
    EXPECT_LE(p.totalMs(), frameMs);
    // No effects: the effects span is a glFinish with nothing queued, far below the sea's draw.
    EXPECT_LT(p.effectsMs, 0.25 * p.seaMs) << p.effectsMs << " vs sea " << p.seaMs;

    // An explosion in view: its secondary grid's draw shows up in the effects span.
    events.enqueue(SpawnExplosion{{300.0, 0.0}, 1.0, 1.0});
    events.dispatch();
    fx.update(3.0, cam);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 3.0));
    p = renderer.lastStats().passTimes;
    ASSERT_EQ(renderer.lastStats().explosions.draws, 1);
    EXPECT_GT(p.effectsMs, 0.0);
    EXPECT_GT(p.seaMs, 0.0);

    // Shaded forward: the sky is a pass of its own again, and the shading span is ~empty.
    OceanDesc forward = gridsDesc();
    forward.computeShading = false;
    registry.emplaceOrReplace<OceanComponent>(oceanEntity, makeOcean(forward));
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 3.05));
    p = renderer.lastStats().passTimes;
    ASSERT_FALSE(renderer.lastStats().computeShaded);
    EXPECT_GT(p.skyMs, 0.0);
    EXPECT_LT(p.shadeMs, 0.25 * p.seaMs) << p.shadeMs << " vs sea " << p.seaMs;

    // Off again: no new measurement.
    renderer.setPassTiming(std::nullopt);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 3.1));
    EXPECT_FALSE(renderer.lastStats().passTimes.measured);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(EffectsGl, WakeOnlySceneDoesNoExplosionWork) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 60.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    for (int i = 0; i <= 600; ++i) { // 60 s at 10 m/s heading east
        registry.get<Ship>(ship).position = {i * 1.0, 0.0};
        events.dispatch();
        fx.update(i * 0.1, {0.0, -400.0, 200.0});
    }
    const OceanFrame f = frameAt({300.0, -400.0, 200.0}, 0.0, -35.0, 60.0);
    render(renderer, registry, f);
    const OceanStats s = renderer.lastStats();
    EXPECT_EQ(s.wakes.active, 1);
    EXPECT_EQ(s.wakes.draws, 1);
    EXPECT_EQ(s.wakes.vertices, 1 + 97 * 192);
    EXPECT_EQ(s.explosions.active + s.explosions.passes + s.explosions.draws + s.explosions.uploads, 0);
    EXPECT_EQ(nonFinitePixels(), 0u);
    const double err = compareWithCpu(f, EffectKind::Wake, 1);
    std::printf("[wake straight] max |GPU - twin| = %.3g m, |GPU - analytic| = %.3g m\n", err, analyticError);
    EXPECT_LT(err, bound(f.camera.origin, 0.0));
    EXPECT_LT(analyticError, WAKE_FIELD_BOUND);
}

struct ExplosionCase {
    const char* name;
    glm::dvec3 camera;
    double heading, pitch;
    glm::dvec2 at;
    double spawnTime, time;
    int count;
    double analyticBound; ///< |GPU - analytic| allowed: the field's interpolation and band limit (m)
};

class ExplosionReadback : public EffectsGl, public ::testing::WithParamInterface<ExplosionCase> {};

TEST_P(ExplosionReadback, GridHeightsEqualTheCpuQuery) {
    const ExplosionCase c = GetParam();
    EffectsSystem fx(registry, events);
    for (int i = 0; i < c.count; ++i)
        events.enqueue(
            SpawnExplosion{c.at + glm::dvec2(3.0 * (i % 7), 2.0 * (i % 5)), c.spawnTime, 1.0 + (i % 3)});
    events.dispatch();
    fx.update(c.time, c.camera);
    const OceanFrame f = frameAt(c.camera, c.heading, c.pitch, c.time);
    render(renderer, registry, f);
    const OceanStats s = renderer.lastStats();
    EXPECT_EQ(nonFinitePixels(), 0u);
    const std::vector<glm::dvec2> centres = explosionCentres(c.time);
    ASSERT_FALSE(centres.empty());
    EXPECT_EQ(s.explosions.active, static_cast<int>(centres.size()));
    ASSERT_EQ(s.explosions.drawn, s.explosions.active) << "every explosion of the case must be in view";
    const double err = compareWithCpu(f, EffectKind::Explosion, centres.size());
    const double dist = glm::length(c.at - glm::dvec2(c.camera));
    std::printf("[%s] %zu explosions, max |GPU - twin| = %.3g m, |GPU - analytic| = %.3g m\n", c.name,
                centres.size(), err, analyticError);
    EXPECT_LT(err, bound(c.camera, curvatureDrop(dist)));
    EXPECT_LT(analyticError, c.analyticBound);
    const EffectFieldDesc field = registry.get<OceanComponent>(oceanEntity).desc.effectField;
    const double reach = effectFieldLayout(field, f).level(field.levels - 1).inner;
    if (dist > reach + 1000.0)
        EXPECT_EQ(s.effectField.tiles, 0) << "outside the field: no tile to evaluate";
    else
        EXPECT_GT(s.effectField.tiles, 0);
}

// Cases. Against the twin all bounds are 1e-3 m + float spacing of the camera-relative z (see bound()).
// Against the analytic field, the bilinear read's error A k^2 T^2 / 8 for a ring of amplitude A and wave
// number k on texels of T metres: 250-300 m away the sea reads 1-2 m texels, A = 2 m, k = 0.2: <= 0.04 m
// (near_tau5 measured 0.014, origin_1e7_t1e6 0.018); r = 0 at t = 0 is flat; 64 rings summed at 2 m
// texels: <= 2.6 m by the same bound, measured 0.78; 40 km away is outside the field (+-32 km): nothing of
// the explosion is drawn (its whole 2 m).
INSTANTIATE_TEST_SUITE_P(
    HardCases, ExplosionReadback,
    ::testing::Values(
        ExplosionCase{"near_tau5", {0.0, 0.0, 40.0}, 90.0, -12.0, {250.0, 10.0}, 0.0, 5.0, 1, 0.03},
        // r = 0 and t = 0: the camera right above the centre, 10 ms after the blast.
        ExplosionCase{"centre_t0", {500.0, 500.0, 30.0}, 0.0, -89.0, {500.0, 500.0}, 2.0, 2.01, 1, 1e-3},
        ExplosionCase{"far_40km", {0.0, 0.0, 30.0}, 90.0, -0.5, {39900.0, 0.0}, 0.0, 12.0, 1, 2.1},
        ExplosionCase{"origin_1e7_t1e6",
                      {1.0e7 + 0.37, -1.0e7 + 0.81, 60.0},
                      90.0,
                      -10.0,
                      {1.0e7 + 300.0, -1.0e7},
                      1.0e6,
                      1.0e6 + 7.5,
                      1,
                      0.03},
        ExplosionCase{"overlapping_64", {0.0, 0.0, 120.0}, 90.0, -25.0, {300.0, 0.0}, 0.0, 4.0, 64, 1.0}),
    [](const ::testing::TestParamInfo<ExplosionCase>& p) { return std::string(p.param.name); });

// No crack between the base grid (which leaves out 0.98 of each effect's disc) and the effect grids: with
// the sky pass off and the target cleared to a marker colour, every pixel of a view that sees only sea is
// drawn over, for an explosion and a wake seen from above and at a grazing angle.
TEST_F(EffectsGl, NoGapBetweenTheBaseGridAndTheEffectGrids) {
    OceanDesc desc = gridsDesc();
    desc.drawSky = false;
    registry.get<OceanComponent>(oceanEntity) = makeOcean(desc);
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 60.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    events.enqueue(SpawnExplosion{{1200.0, -400.0}, 0.0, 2.0}); // outside the wake's disc (radius ~900 m)
    for (int i = 0; i <= 600; ++i) { // the ship sails 60 s north at 10 m/s, ending at (0, 600)
        registry.get<Ship>(ship).position = {0.0, i * 1.0};
        events.dispatch();
        fx.update(i * 0.1 - 50.0, {0.0, 300.0, 300.0});
    }
    struct View {
        const char* name;
        glm::dvec3 camera;
        double heading, pitch;
    };
    for (const View& v : {View{"explosion from above", {1200.0, -500.0, 120.0}, 0.0, -50.0},
                          View{"wake's rim from above", {0.0, -300.0, 400.0}, 0.0, -60.0},
                          View{"explosion, low and grazing", {1050.0, -550.0, 15.0}, 45.0, -2.0}}) {
        const OceanFrame f = frameAt(v.camera, v.heading, v.pitch, 10.0);
        // Negative: no lit pixel is (a sun glint in scene-linear HDR can exceed any positive marker).
        const float marker[4] = {-1000.0f, 0.0f, -1000.0f, 1.0f};
        glClearNamedFramebufferfv(targets.sceneFramebuffer().id(), GL_COLOR, 0, marker);
        render(renderer, registry, f);
        const OceanStats st = renderer.lastStats();
        EXPECT_GE(st.explosions.drawn + st.wakes.drawn, 1) << v.name;
        std::vector<float> rgba;
        targets.readScene(rgba);
        // Rows below the horizon (+3 rows): the horizon is -pitch above the centre (60 degree vertical fov).
        const double horizonRow =
            0.5 * H *
            (1.0 - std::tan(-v.pitch * std::numbers::pi / 180.0) / std::tan(std::numbers::pi / 6.0));
        const int firstRow = std::max(0, static_cast<int>(horizonRow) + 3);
        size_t gaps = 0;
        for (int y = firstRow; y < H; ++y)
            for (int x = 0; x < W; ++x)
                if (rgba[(static_cast<size_t>(y) * W + x) * 4] <= -999.0f) {
                    if (gaps == 0)
                        std::printf("[%s] first gap at pixel (%d, %d), rows from %d\n", v.name, x, y,
                                    firstRow);
                    ++gaps;
                }
        EXPECT_EQ(gaps, 0u) << v.name << ": pixels left at the marker colour";
    }
}

TEST_F(EffectsGl, ExplosionAtTimeZeroDrawsNothingAndStaysFinite) {
    EffectsSystem fx(registry, events);
    events.enqueue(SpawnExplosion{{0.0, 0.0}, 5.0, 1.0});
    events.dispatch();
    fx.update(5.0, {0.0, 0.0, 20.0});
    render(renderer, registry, frameAt({0.0, 0.0, 20.0}, 0.0, -60.0, 5.0));
    EXPECT_EQ(renderer.lastStats().explosions.active, 0); // tau = 0: flat, nothing to draw
    EXPECT_EQ(nonFinitePixels(), 0u);
    EXPECT_EQ(oceanHeightAt(registry, oceanEntity, {0.0, 0.0}, 5.0),
              registry.get<OceanComponent>(oceanEntity).surface->heightAt({0.0, 0.0}, 5.0));
}

TEST_F(EffectsGl, TenThousandSpawnsInOneSecondRenderCappedAndFinite) {
    EffectsSystem fx(registry, events);
    const glm::dvec3 cam(0.0, 0.0, 150.0);
    long long dropped = 0;
    for (int frame = 0; frame < 60; ++frame) { // 10 000 spawns over 60 frames of one second
        const double t = frame / 60.0;
        for (int i = 0; i < 10000 / 60 + (frame < 10000 % 60 ? 1 : 0); ++i)
            events.enqueue(SpawnExplosion{
                {200.0 + std::fmod(i * 37.0, 400.0), std::fmod(i * 53.0, 300.0) - 150.0}, t, 1.0});
        events.dispatch();
        fx.update(t, cam);
        dropped += fx.counters().droppedExplosions;
    }
    EXPECT_EQ(dropped, 10000 - 1024);
    registry.get<OceanComponent>(oceanEntity).desc.effectGrids = EffectGridDesc{}; // the default grids
    render(renderer, registry, frameAt(cam, 90.0, -20.0, 2.0));
    const OceanStats s = renderer.lastStats();
    // Bounded cost: every explosion in the field, evaluated once per texel it touches; at most
    // maxExplosionGrids grids.
    EXPECT_EQ(s.explosions.active, 1024);
    EXPECT_LE(s.explosions.drawn, EffectGridDesc{}.maxExplosionGrids);
    EXPECT_LE(s.explosions.vertices, EffectGridDesc{}.maxExplosionGrids * (1LL + 49 * 96));
    EXPECT_EQ(s.effectField.passes, 1);
    EXPECT_EQ(nonFinitePixels(), 0u);
}

TEST_F(EffectsGl, TightCircleWakeMatchesCpuAndStaysFinite) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 40.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    double heading = 0.0;
    glm::dvec2 p(0.0);
    for (int i = 0; i <= 1200; ++i) { // 120 s at 6 m/s turning 0.2 rad/s: radius 30 m, ~4 circles
        if (i > 0) {
            heading += 0.02;
            p += 0.6 * glm::dvec2(std::cos(heading), std::sin(heading));
        }
        registry.get<Ship>(ship).position = p;
        events.dispatch();
        fx.update(i * 0.1, {0.0, -150.0, 120.0});
    }
    const OceanFrame f = frameAt({0.0, -150.0, 120.0}, 0.0, -40.0, 120.0);
    render(renderer, registry, f);
    EXPECT_EQ(nonFinitePixels(), 0u);
    EXPECT_EQ(renderer.lastStats().wakes.drawn, 1);
    const double err = compareWithCpu(f, EffectKind::Wake, 1);
    std::printf("[wake tight circle] max |GPU - twin| = %.3g m, |GPU - analytic| = %.3g m\n", err,
                analyticError);
    EXPECT_LT(err, bound(f.camera.origin, 0.0));
    EXPECT_LT(analyticError, WAKE_FIELD_BOUND);
}

// The effect grids' per-vertex frustum test (effects.vert uCull, docs/PERFORMANCE.md): a wake seen from its
// side at 30 m, mostly outside the view, draws exactly the pixels it draws with every vertex evaluated
// (OceanDesc::cullVertices = false), and the time of its pass falls (printed, not asserted: llvmpipe
// evaluates wake vertices on one thread, ~5x less work in the replay's demo view at t = 20 s).
TEST_F(EffectsGl, EffectCullingChangesNoPixel) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 80.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    for (int i = 0; i <= 120; ++i) { // 120 s at 10 m/s heading north
        registry.get<Ship>(ship).position = {0.0, i * 10.0};
        events.dispatch();
        fx.update(i, {-300.0, 1100.0, 30.0});
    }
    // 300 m west of the bow, looking north-east: the ship and the first ~100 m of its wake in view.
    const OceanFrame f = frameAt({-300.0, 1100.0, 30.0}, 60.0, -8.0, 120.0);
    std::vector<float> culled, full;
    gl::GpuTimer timer(gl::GpuTimer::Clock::WallAroundFinish);
    render(renderer, registry, f); // builds the programs
    timer.begin();
    render(renderer, registry, f);
    timer.end();
    ASSERT_EQ(renderer.lastStats().wakes.drawn, 1);
    targets.readScene(culled);
    registry.get<OceanComponent>(oceanEntity).desc.cullVertices = false;
    render(renderer, registry, f);
    timer.begin();
    render(renderer, registry, f);
    timer.end();
    targets.readScene(full);
    std::printf("[effect culling] frame %.1f ms culled, %.1f ms every vertex\n", timer.samples()[0],
                timer.samples()[1]);
    ASSERT_EQ(culled.size(), full.size());
    size_t differing = 0;
    for (size_t i = 0; i < culled.size(); ++i)
        differing += culled[i] != full[i];
    EXPECT_EQ(differing, 0u) << "values differ with effect culling";
    EXPECT_EQ(nonFinitePixels(), 0u);
}

// EffectFieldDesc::viewCull: the field's tiles out of reach of the view sector (and of every drawn grid's
// disc) are not evaluated. A trail that runs back past the camera and explosions all around it, seen by
// each surface model (Gerstner and the FFT move the sea sideways), from cameras that look along the trail,
// across it and from right above an explosion behind: the same pixels with the cull as without it, and
// fewer tiles where the trail leaves the sector.
TEST_F(EffectsGl, FieldViewCullChangesNoPixel) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 80.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    for (int i = 0; i <= 120; ++i) { // 120 s at 10 m/s heading north: a 1.2 km trail
        registry.get<Ship>(ship).position = {0.0, i * 10.0};
        events.dispatch();
        fx.update(i, {-150.0, 600.0, 40.0});
    }
    // Explosions around the camera at (-150, 600): ahead, abeam, behind, and one 30 m behind it.
    for (const glm::dvec2 at : {glm::dvec2{-150.0, 900.0},
                                {150.0, 600.0},
                                {-450.0, 600.0},
                                {-150.0, 300.0},
                                {-150.0, 570.0},
                                {-350.0, 350.0}})
        events.enqueue(SpawnExplosion{at, 40.0, 1.0});
    events.dispatch();
    fx.update(117.0, {-150.0, 600.0, 40.0});
    struct View {
        const char* name;
        glm::dvec3 camera;
        double heading, pitch;
        bool fewerTiles; // the trail leaves the sector: the cull must evaluate fewer tiles
        bool wide;       // the sector is wider than a half-plane (the other branch of the tile test)
    };
    const View views[] = {
        {"along the trail, its end behind", {-150.0, 600.0, 40.0}, 0.0, -10.0, true, false},
        {"across the trail", {-150.0, 600.0, 40.0}, 90.0, -15.0, true, false},
        {"away from the trail, an explosion just behind", {-150.0, 600.0, 12.0}, 270.0, -5.0, true, false},
        {"steeply down, a sector wider than a half-plane", {-150.0, 600.0, 120.0}, 0.0, -58.0, true, true},
        {"straight down (every azimuth: no cull)", {-150.0, 600.0, 300.0}, 0.0, -89.0, false, false},
    };
    for (SurfaceKind kind : {SurfaceKind::Octaves, SurfaceKind::Gerstner, SurfaceKind::Fft}) {
        for (bool everyGrid : {false, true}) {
            OceanDesc desc = everyGrid ? gridsDesc() : OceanDesc{};
            desc.model = kind;
            const OceanComponent base = makeOcean(desc); // the surface built once: the cull is a desc flag
            OceanComponent& ocean = registry.get<OceanComponent>(oceanEntity);
            for (const View& v : views) {
                SCOPED_TRACE(std::string(toString(kind)) + (everyGrid ? ", every grid, " : ", ") + v.name);
                const OceanFrame f = frameAt(v.camera, v.heading, v.pitch, 120.0);
                const double half =
                    computeViewSector(f.camera, desc.sectorGuardDeg * std::numbers::pi / 180.0).halfWidth;
                if (v.wide) {
                    ASSERT_TRUE(half > 0.5 * std::numbers::pi && half < std::numbers::pi) << half;
                } else if (v.fewerTiles) {
                    ASSERT_LE(half, 0.5 * std::numbers::pi);
                }
                std::vector<float> culled, full;
                ocean = base;
                // Each setting rendered twice: the second frame's tiles are this setting's alone (the first
                // also clears what the frame before it wrote).
                ocean.desc.effectField.viewCull = true;
                render(renderer, registry, f);
                render(renderer, registry, f);
                const OceanStats withCull = renderer.lastStats();
                targets.readScene(culled);
                ocean.desc.effectField.viewCull = false;
                render(renderer, registry, f);
                render(renderer, registry, f);
                const OceanStats without = renderer.lastStats();
                targets.readScene(full);
                ASSERT_EQ(without.explosions.active, 6);
                ASSERT_EQ(without.wakes.active, 1);
                ASSERT_GT(without.effectField.tiles, 0);
                // With a grid for every effect the wake's disc (its whole trail) is read: no fewer tiles.
                if (!v.fewerTiles)
                    EXPECT_EQ(withCull.effectField.tiles, without.effectField.tiles);
                else if (!everyGrid)
                    EXPECT_LT(withCull.effectField.tiles, without.effectField.tiles);
                else
                    EXPECT_LE(withCull.effectField.tiles, without.effectField.tiles);
                std::printf("[field view cull] %s%s, %s: %d tiles, %d without the cull\n", toString(kind),
                            everyGrid ? ", every grid" : "", v.name, withCull.effectField.tiles,
                            without.effectField.tiles);
                ASSERT_EQ(culled.size(), full.size());
                size_t differing = 0;
                for (size_t i = 0; i < culled.size(); ++i)
                    differing += culled[i] != full[i];
                EXPECT_EQ(differing, 0u) << "tiles " << withCull.effectField.tiles << " culled, "
                                         << without.effectField.tiles << " without";
            }
        }
    }
    EXPECT_EQ(nonFinitePixels(), 0u);
}

// An ocean whose grid changes kind between frames (radial, then projected) draws what a fresh renderer draws:
// nothing of the radial grid (its index ranges, its view sector's field reads) is left behind.
TEST_F(EffectsGl, GridKindSwitchDrawsWhatAFreshRendererDraws) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 80.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    for (int i = 0; i <= 60; ++i) { // 60 s at 10 m/s heading north
        registry.get<Ship>(ship).position = {0.0, i * 10.0};
        events.dispatch();
        fx.update(i, {-150.0, 300.0, 30.0});
    }
    OceanDesc desc = OceanDesc{};
    desc.grid.minRingPixels = 1.0; // ring thinning: the radial grid's own index ranges
    registry.get<OceanComponent>(oceanEntity) = makeOcean(desc);
    const OceanFrame f = frameAt({-150.0, 300.0, 30.0}, 20.0, -10.0, 60.0);
    render(renderer, registry, f);
    ASSERT_GT(renderer.lastStats().effectField.tiles, 0);
    registry.get<OceanComponent>(oceanEntity).desc.gridKind = GridKind::Projected;
    render(renderer, registry, f);
    render(renderer, registry, f);
    std::vector<float> switched, fresh;
    targets.readScene(switched);
    OceanRenderer other;
    render(other, registry, f);
    render(other, registry, f);
    targets.readScene(fresh);
    ASSERT_EQ(switched.size(), fresh.size());
    EXPECT_EQ(std::memcmp(switched.data(), fresh.data(), switched.size() * sizeof(float)), 0);
    EXPECT_EQ(renderer.lastStats().vertices, other.lastStats().vertices);
    EXPECT_EQ(renderer.lastStats().effectField.tiles, other.lastStats().effectField.tiles);
}

TEST_F(EffectsGl, WakeIsVisibleFromTenKilometres) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 80.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    for (int i = 0; i <= 240; ++i) { // 240 s at 12 m/s heading north
        registry.get<Ship>(ship).position = {0.0, i * 12.0};
        events.dispatch();
        fx.update(i, {0.0, 1500.0, 10000.0});
    }
    // Straight down from 10 km over the middle of the wake: at 320 x 180 and 60 degrees a pixel is ~64 m.
    const OceanFrame f = frameAt({0.0, 1500.0, 10000.0}, 0.0, -90.0, 240.0);
    render(renderer, registry, f);
    ASSERT_EQ(renderer.lastStats().wakes.drawn, 1);
    std::vector<float> rgba;
    targets.readScene(rgba);
    auto luminance = [&](const glm::dvec2& world) {
        const glm::vec4 clip = f.camera.viewProj * glm::vec4(glm::vec2(world - glm::dvec2(f.camera.origin)),
                                                             static_cast<float>(-f.camera.origin.z), 1.0f);
        const int px = static_cast<int>((clip.x / clip.w * 0.5f + 0.5f) * W);
        const int py = static_cast<int>((0.5f - clip.y / clip.w * 0.5f) * H); // rows top-down
        const float* c = &rgba[(static_cast<size_t>(py) * W + px) * 4];
        return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    };
    // On the track 0.5, 1 and 1.5 km behind the ship vs 400 m beside it.
    for (double behind : {500.0, 1000.0, 1500.0}) {
        const double onTrack = luminance({0.0, 2880.0 - behind});
        const double beside = luminance({400.0, 2880.0 - behind});
        std::printf("[wake from 10 km] %.0f m behind: on track %.4g (foam %.3f), beside %.4g\n", behind,
                    onTrack, effectsFoamAt(registry, {0.0, 2880.0 - behind}, 240.0), beside);
        EXPECT_GT(onTrack, 1.5 * beside) << behind << " m behind the ship";
    }
}

// A carrier's turbulent wake is a white trail seen from 3 km: a 300 m ship at 15 m/s heading north for 200 s,
// looked at straight down from 3 km (~19 m pixels). Each pixel's foam opacity comes from renders without
// foam, with the defaults and with whitecap foam at full coverage. Beyond 1.5 km the whitecaps fade
// (FOAM_FADE_START..END), so the last render covers only a share a = meanFoamOpacity(fade) of a pixel, and
// the opacity is a (Y - Y_none) / (Y_full - Y_none). Along the track 0.5, 1 and 1.5 km behind the ship the
// opacity (mean over 5 pixels) must be >= 10x that 800 m beside the track (clear of the strip's 3-width cut),
// and across the strip it must follow the CPU's field (sampleEffectField) within 0.05 + 10 % wherever the
// field's foam is below 0.9 a (above, the full-coverage render, max(whitecaps, wake), is the wake's own foam,
// and the measure saturates at a): the rendered foam is the field's share at every footprint (foamCover).
// Measured (llvmpipe): on the track >= 0.55 (saturated; CPU 0.80) / 0.62 (CPU 0.64) / 0.51 (CPU 0.51),
// beside <= 0.0003.
TEST_F(EffectsGl, CarrierWakeFoamRunsAlongTheTrackFromThreeKilometres) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 300.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    const glm::dvec3 camera{0.0, 1500.0, 3000.0};
    for (int i = 0; i <= 200; ++i) {
        registry.get<Ship>(ship).position = {0.0, i * 15.0};
        events.dispatch();
        fx.update(i, camera);
    }
    const OceanFrame f = frameAt(camera, 0.0, -90.0, 200.0);
    std::vector<float> px[3]; // no foam, the defaults, whitecaps at full coverage
    for (int mode = 0; mode < 3; ++mode) {
        OceanDesc d;
        d.lighting.foamIntensity = mode == 0 ? 0.0f : 1.0f;
        if (mode == 2) {
            d.lighting.foamHeightStart = -100.0f;
            d.lighting.foamHeightFull = -99.0f;
        }
        registry.get<OceanComponent>(oceanEntity) = makeOcean(d);
        render(renderer, registry, f);
        targets.readScene(px[mode]);
    }
    const EffectFieldLayout layout = effectFieldLayout(OceanDesc{}.effectField, f);
    double full = 0.0;                            // of the last opacity() call
    auto opacity = [&](const glm::dvec2& world) { // mean over the pixel and its 4 neighbours
        const glm::vec4 clip = f.camera.viewProj * glm::vec4(glm::vec2(world - glm::dvec2(f.camera.origin)),
                                                             static_cast<float>(-f.camera.origin.z), 1.0f);
        const int cx = static_cast<int>((clip.x / clip.w * 0.5f + 0.5f) * W);
        const int cy = static_cast<int>((0.5f - clip.y / clip.w * 0.5f) * H); // rows top-down
        const double dist = glm::length(glm::dvec3(world, 0.0) - camera);
        const double s = std::clamp((dist - FOAM_FADE_START) / (FOAM_FADE_END - FOAM_FADE_START), 0.0, 1.0);
        full = meanFoamOpacity(1.0 - s * s * (3.0 - 2.0 * s)); // ocean.frag nearFade
        double sum = 0.0;
        for (const glm::ivec2 o : {glm::ivec2(0, 0), {1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
            const size_t i = static_cast<size_t>(cy + o.y) * W + static_cast<size_t>(cx + o.x);
            auto y = [&](int mode) {
                const float* c = &px[mode][i * 4];
                return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
            };
            sum += std::clamp(full * (y(1) - y(0)) / std::max(y(2) - y(0), 1e-6), 0.0, 1.0);
        }
        return sum / 5.0;
    };
    for (double behind : {500.0, 1000.0, 1500.0}) {
        const double y = 3000.0 - behind;
        const double on = opacity({0.0, y}), beside = std::max(opacity({-800.0, y}), opacity({800.0, y}));
        std::printf(
            "[carrier wake from 3 km] %.0f m behind: foam on the track %.3f (CPU %.3f), 800 m beside %.4f\n",
            behind, on, sampleEffectField(registry, layout, {0.0, y}, 200.0).w, beside);
        EXPECT_GT(on, 0.3) << behind << " m behind";
        EXPECT_GE(on, 10.0 * beside) << behind << " m behind";
        for (double lateral : {0.0, 100.0, 200.0, 300.0}) {
            const double cpu = sampleEffectField(registry, layout, {lateral, y}, 200.0).w;
            const double rendered = opacity({lateral, y});
            // Above 0.9 a the full-coverage render, max(whitecaps, wake), shows the wake's own foam.
            if (cpu < 0.9 * full) {
                EXPECT_NEAR(rendered, cpu, 0.05 + 0.1 * cpu)
                    << behind << " m behind, " << lateral << " m beside";
            }
        }
    }
    EXPECT_EQ(nonFinitePixels(), 0u);
}

// The defaults: the field draws every effect (the base grid reads it) and a secondary grid is drawn only for
// an effect next to the eye (radius / distance >= 0.2): an explosion 300 m ahead of a camera 60 m up changes
// the picture through the field alone, one below the camera gets its grid.
TEST_F(EffectsGl, DefaultGridsOnlyNextToTheEye) {
    registry.get<OceanComponent>(oceanEntity) = makeOcean({});
    EffectsSystem fx(registry, events);
    const glm::dvec3 cam(0.0, 0.0, 60.0);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 4.0));
    std::vector<float> plain, far, near;
    targets.readScene(plain);
    events.enqueue(SpawnExplosion{{300.0, 0.0}, 1.0, 1.0});
    events.dispatch();
    fx.update(4.0, cam);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 4.0));
    OceanStats s = renderer.lastStats();
    EXPECT_EQ(s.explosions.active, 1);
    EXPECT_EQ(s.explosions.drawn, 0);
    EXPECT_EQ(s.explosions.draws + s.explosions.vertices, 0);
    EXPECT_EQ(s.effectField.passes, 1);
    targets.readScene(far);
    size_t changed = 0;
    for (size_t i = 0; i < plain.size(); ++i)
        changed += plain[i] != far[i];
    EXPECT_GT(changed, 400u) << "the field alone draws the explosion (> 100 pixels of 320 x 180 change)";
    events.enqueue(SpawnExplosion{{40.0, 0.0}, 1.0, 1.0});
    events.dispatch();
    fx.update(4.0, cam);
    render(renderer, registry, frameAt(cam, 90.0, -15.0, 4.0));
    s = renderer.lastStats();
    EXPECT_EQ(s.explosions.active, 2);
    EXPECT_EQ(s.explosions.drawn, 1) << "only the one next to the eye has a grid";
    EXPECT_EQ(nonFinitePixels(), 0u);
}

// EffectGridDesc::minAmplitudePixels: a wake's grid spans its whole trail, so its angular size is large from
// anywhere near it; the grid is drawn only where its waves are tall enough on screen to need more geometry
// than the base grid has. A 10 m/s ship's waves (peak ~0.5 m) seen from 450 m away and 100 m up are ~0.2
// pixels tall at 320 x 180 (focal length ~156 pixels): no grid (the field draws the wake); from 30 m away and
// 20 m up, ~2 pixels: a grid; with the criterion off, a grid from 450 m too.
TEST_F(EffectsGl, DefaultWakeGridOnlyWhereItsWavesShow) {
    registry.get<OceanComponent>(oceanEntity) = makeOcean({});
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 60.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    for (int i = 0; i <= 240; ++i) { // 120 s at 10 m/s along +x
        registry.get<Ship>(ship).position = {5.0 * i, 0.0};
        events.dispatch();
        fx.update(0.5 * i, {1200.0, 0.0, 100.0});
    }
    const glm::dvec2 at = registry.get<Ship>(ship).position;
    auto wakeGrids = [&](double distance, double height, double minPixels) {
        registry.get<OceanComponent>(oceanEntity).desc.effectGrids.minAmplitudePixels = minPixels;
        // Looking at the ship across its track (heading +y), from `distance` on its -y side.
        const double pitch = -std::atan2(height, distance) * 180.0 / std::numbers::pi;
        render(renderer, registry, frameAt({at.x, at.y - distance, height}, 0.0, pitch, 120.0));
        const OceanStats& s = renderer.lastStats();
        EXPECT_EQ(s.wakes.active, 1);
        EXPECT_EQ(s.effectField.passes, 1);
        EXPECT_EQ(nonFinitePixels(), 0u);
        return s.wakes.drawn;
    };
    const double byDefault = EffectGridDesc{}.minAmplitudePixels;
    EXPECT_EQ(wakeGrids(450.0, 100.0, byDefault), 0) << "waves a fraction of a pixel tall: no grid";
    EXPECT_EQ(wakeGrids(30.0, 20.0, byDefault), 1) << "next to the ship: a grid";
    EXPECT_EQ(wakeGrids(450.0, 100.0, 0.0), 1) << "the angular size alone draws it";
}

// The component's own API (Ocean.h): plain spans in, the same pixels as the registry adapter; bad input
// refused as a Status naming the field, before any GL work.
TEST_F(EffectsGl, SpansDrawWhatTheRegistryDraws) {
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 80.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    events.enqueue(SpawnExplosion{{150.0, 250.0}, 55.0, 1.0});
    for (int i = 0; i <= 120; ++i) { // 60 s at 10 m/s along +x
        registry.get<Ship>(ship).position = {5.0 * i, 0.0};
        events.dispatch();
        fx.update(0.5 * i, {300.0, -400.0, 150.0});
    }
    const OceanFrame f = frameAt({300.0, -400.0, 150.0}, 0.0, -25.0, 60.0);
    render(renderer, registry, f);
    const OceanStats viaRegistry = renderer.lastStats();
    ASSERT_EQ(viaRegistry.explosions.active, 1);
    ASSERT_EQ(viaRegistry.wakes.active, 1);
    std::vector<float> expected, actual;
    targets.readScene(expected);
    // The host's own copies: nothing of the registry is read.
    const OceanComponent ocean = registry.get<OceanComponent>(oceanEntity);
    Explosion explosion;
    registry.view<Explosion>().each([&](ecs::Entity, Explosion& e) { explosion = e; });
    const Ship hull = registry.get<Ship>(ship);
    const ShipTrail trail = registry.get<ShipTrail>(ship);
    const OceanInstance oceans[] = {{oceanId(oceanEntity), &ocean}};
    const WakeRef wakes[] = {{&hull, &trail}};
    const Status s = renderer.render({oceans, {{&explosion, 1}, wakes}}, f);
    ASSERT_TRUE(s.ok()) << s.message;
    targets.readScene(actual);
    EXPECT_EQ(renderer.lastStats().draws, viaRegistry.draws);
    EXPECT_EQ(renderer.lastStats().vertices, viaRegistry.vertices);
    ASSERT_EQ(actual.size(), expected.size());
    EXPECT_EQ(std::memcmp(actual.data(), expected.data(), actual.size() * sizeof(float)), 0);
}

TEST_F(EffectsGl, BadScenesAreRefusedNamingTheField) {
    const OceanComponent& ocean = registry.get<OceanComponent>(oceanEntity);
    const OceanFrame good = frameAt({0.0, 0.0, 50.0}, 0.0, -20.0, 10.0);
    const OceanInstance oceans[] = {{1, &ocean}};
    ASSERT_TRUE(renderer.render({oceans, {}}, good).ok());
    const OceanInstance nullOcean[] = {{1, nullptr}};
    Explosion nanExplosion;
    nanExplosion.center = {std::nan(""), 0.0};
    const Ship ship;
    const WakeRef noTrail[] = {{&ship, nullptr}};
    OceanFrame nanTime = good, noPixels = good, nanCamera = good;
    nanTime.time = std::nan("");
    noPixels.height = 0;
    nanCamera.camera.origin.x = std::numeric_limits<double>::infinity();
    struct Case {
        OceanScene scene;
        OceanFrame frame;
        const char* field;
    };
    const Case cases[] = {
        {{oceans, {}}, nanTime, "OceanFrame.time must be finite"},
        {{oceans, {}}, noPixels, "OceanFrame.width and .height must be > 0"},
        {{oceans, {}}, nanCamera, "OceanFrame.camera.origin must be finite"},
        {{nullOcean, {}}, good, "OceanScene.oceans[0].ocean is null"},
        {{oceans, {{&nanExplosion, 1}, {}}}, good, "OceanScene.effects.explosions[0] centre and startTime"},
        {{oceans, {{}, noTrail}}, good, "OceanScene.effects.wakes[0]: ship and trail must not be null"},
    };
    for (const Case& c : cases) {
        const Status s = renderer.render(c.scene, c.frame);
        EXPECT_EQ(s.code, ErrorCode::InvalidArgument) << c.field;
        EXPECT_NE(s.message.find(c.field), std::string::npos) << s.message;
        EXPECT_EQ(renderer.lastStats().draws + renderer.lastStats().passes, 0) << "no GL work: " << c.field;
    }
    EXPECT_TRUE(renderer.render({oceans, {}}, good).ok()) << "a good frame after the refused ones";
    EXPECT_GT(renderer.lastStats().draws, 0);
    // Pacifica's hosts (OceanHost.h) get the same as an exception.
    EXPECT_THROW(render(renderer, registry, nanTime), std::invalid_argument);
    OceanComponent unchanged;
    OceanDesc bad;
    bad.grid.rings = 0;
    const Status refused = makeOcean(bad, unchanged);
    EXPECT_EQ(refused.code, ErrorCode::InvalidArgument);
    EXPECT_NE(refused.message.find("rings"), std::string::npos) << refused.message;
    EXPECT_FALSE(unchanged.surface);
    // Queries: the surface plus the effects, refused for a NaN point.
    const glm::dvec2 points[] = {{10.0, 20.0}, {-300.0, 40.0}};
    double heights[2] = {};
    ASSERT_TRUE(heightsAt(ocean, {}, points, 10.0, heights).ok());
    EXPECT_DOUBLE_EQ(heights[1], ocean.surface->heightAt(points[1], 10.0));
    const glm::dvec2 nanPoint[] = {{0.0, std::nan("")}};
    EXPECT_EQ(heightsAt(ocean, {}, nanPoint, 10.0, heights).code, ErrorCode::InvalidArgument);
    EXPECT_DOUBLE_EQ(heights[1], ocean.surface->heightAt(points[1], 10.0)) << "unchanged on error";
}

} // namespace
