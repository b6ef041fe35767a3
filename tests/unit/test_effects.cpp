// Effects on the CPU (ocean/include/ocean/Effects.h): the explosion ring and the Kelvin wake as functions
// (finite at r = 0 and t = 0, slopes equal to finite differences, the 19.47 degree wedge, a turning ship's
// curved wake), and the system (events -> components, lifetimes with EffectEnded, caps with counted drops,
// bad data rejected without throwing).
#include "engine/Ecs.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanHost.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

using namespace pacifica;
using namespace pacifica::ocean;

namespace {

Explosion makeExplosion(glm::dvec2 c, double t0, double strength = 1.0) {
    Explosion e;
    e.center = c;
    e.startTime = t0;
    e.strength = strength;
    e.params = explosionParams(strength);
    return e;
}

TEST(Explosion, FlatAtTheStartAndFiniteAtTheCentre) {
    const Explosion e = makeExplosion({100.0, 200.0}, 10.0);
    // tau = 0 and before: no displacement anywhere, nothing to draw.
    for (double t : {0.0, 9.99, 10.0}) {
        const ExplosionState s = explosionState(e, t);
        EXPECT_EQ(s.radius, 0.0) << t;
        EXPECT_EQ(explosionWave(e.params, s, {0.0, 0.0}), glm::dvec3(0.0));
    }
    // r = 0 a moment later: finite, bounded by I0, and the slope vanishes (the field is smooth there).
    for (double t : {10.0 + 1e-9, 10.001, 10.5, 12.0, 40.0}) {
        const ExplosionState s = explosionState(e, t);
        const glm::dvec3 w = explosionWave(e.params, s, {0.0, 0.0});
        ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z)) << t;
        EXPECT_LE(std::abs(w.x), e.params.amplitude) << t;
        EXPECT_EQ(w.y, 0.0);
        EXPECT_EQ(w.z, 0.0);
    }
}

TEST(Explosion, SlopeEqualsFiniteDifferences) {
    const Explosion e = makeExplosion({0.0, 0.0}, 0.0, 2.0);
    const ExplosionState s = explosionState(e, 6.0);
    ASSERT_GT(s.radius, 20.0);
    const double h = 1e-4;
    for (glm::dvec2 q :
         {glm::dvec2(0.3, -0.2), glm::dvec2(7.0, 3.0), glm::dvec2(-15.0, 9.0), glm::dvec2(2.0, 25.0)}) {
        const glm::dvec3 w = explosionWave(e.params, s, q);
        const double dx = (explosionWave(e.params, s, q + glm::dvec2(h, 0)).x -
                           explosionWave(e.params, s, q - glm::dvec2(h, 0)).x) /
                          (2 * h);
        const double dy = (explosionWave(e.params, s, q + glm::dvec2(0, h)).x -
                           explosionWave(e.params, s, q - glm::dvec2(0, h)).x) /
                          (2 * h);
        EXPECT_NEAR(w.y, dx, 1e-6 + 1e-5 * std::abs(dx)) << q.x << "," << q.y;
        EXPECT_NEAR(w.z, dy, 1e-6 + 1e-5 * std::abs(dy)) << q.x << "," << q.y;
    }
}

TEST(Explosion, NoWaveAheadOfTheFrontAndZeroAtTheRim) {
    const Explosion e = makeExplosion({0.0, 0.0}, 0.0);
    const ExplosionState s = explosionState(e, 8.0);
    // Group front r0 + c_g tau with c_g = sqrt(g / k) / 2.
    const double cg = 0.5 * std::sqrt(GRAVITY / e.params.wavenumber);
    EXPECT_NEAR(s.front, e.params.coreRadius + cg * 8.0, 1e-9);
    EXPECT_EQ(explosionWave(e.params, s, {s.front + s.frontWidth + 0.5, 0.0}).x, 0.0);
    EXPECT_EQ(explosionWave(e.params, s, {0.0, s.radius}).x, 0.0);
    // Inside the front there is a wave of the expected size (spreading r0 / sqrt(r0^2 + r^2)).
    double peak = 0.0;
    for (double r = 0.0; r < s.front - s.frontWidth; r += 0.25)
        peak = std::max(peak, std::abs(explosionWave(e.params, s, {r, 0.0}).x));
    EXPECT_GT(peak, 0.3 * s.amplitude); // the crest near the centre at this instant: cos(phase) ~ 0.6
    EXPECT_LE(peak, s.amplitude + 1e-12);
}

TEST(Explosion, StrengthScalesWithTheCubeRootAndBadStrengthThrows) {
    const ExplosionParams a = explosionParams(1.0), b = explosionParams(8.0);
    EXPECT_NEAR(b.amplitude / a.amplitude, 2.0, 1e-12);
    EXPECT_NEAR(a.wavenumber / b.wavenumber, 2.0, 1e-12);
    EXPECT_THROW(explosionParams(0.0), std::invalid_argument);
    EXPECT_THROW(explosionParams(-1.0), std::invalid_argument);
    EXPECT_THROW(explosionParams(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

/// A ship that has sailed `seconds` at `speed` m/s along heading direction `dir` (or turning at `turnRate`
/// rad/s), recorded by the system at 10 Hz. Returns the ship entity.
ecs::Entity sail(ecs::Registry& reg, ecs::EventQueue& events, EffectsSystem& fx, double seconds, double speed,
                 double turnRate, double t0 = 0.0) {
    const ecs::Entity ship = reg.create();
    reg.emplace<Ship>(ship, Ship{{0.0, 0.0}, 60.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    double heading = 0.0;
    glm::dvec2 p(0.0);
    for (int i = 0; i <= static_cast<int>(seconds * 10); ++i) {
        const double t = t0 + i * 0.1;
        if (i > 0) {
            heading += turnRate * 0.1;
            p += 0.1 * speed * glm::dvec2(std::cos(heading), std::sin(heading));
        }
        reg.get<Ship>(ship).position = p;
        events.dispatch();
        fx.update(t, {0.0, 0.0, 100.0});
    }
    return ship;
}

/// The wake of a ship that has sailed `seconds` (sail()) as it stands at the end, t = seconds.
WakeState sailedWake(double seconds, double speed, double turnRate) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    const ecs::Entity ship = sail(reg, events, fx, seconds, speed, turnRate);
    return wakeState(reg.get<Ship>(ship), reg.get<ShipTrail>(ship), seconds);
}

TEST(Wake, KelvinWedgeOnAStraightCourse) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    const ecs::Entity ship = sail(reg, events, fx, 120.0, 10.0, 0.0);
    const double t = 120.0;
    const WakeState s = wakeState(reg.get<Ship>(ship), reg.get<ShipTrail>(ship), t);
    ASSERT_GE(s.offsets.size(), 2u);
    EXPECT_NEAR(s.sigma.back(), 1200.0, 1.0);
    EXPECT_NEAR(s.k0.front(), GRAVITY / 100.0, 1e-6); // k0 = g / U^2
    // The ship sails +x; behind it is -x. Inside the wedge there are waves, outside none.
    const double x = 400.0;
    double inside = 0.0;
    for (double y = -0.3 * x; y <= 0.3 * x; y += 1.0)
        inside = std::max(inside, std::abs(wakeWave(s, {-x, y}).x));
    EXPECT_GT(inside, 0.05);
    const double tanKelvin = std::sqrt(KELVIN_TAN2); // tan 19.47 deg
    for (double y : {tanKelvin * x + 1.0, 0.45 * x, -0.5 * x})
        EXPECT_EQ(wakeWave(s, {-x, y}).x, 0.0) << y;
    // Ahead of the ship: nothing.
    EXPECT_EQ(wakeWave(s, {50.0, 0.0}).x, 0.0);
    // Transverse waves on the track have wavelength 2 pi U^2 / g (62.9 m): zero crossings that far apart.
    std::vector<double> crossings;
    double prev = wakeWave(s, {-150.0, 0.0}).x;
    for (double xx = 150.25; xx < 450.0; xx += 0.25) {
        const double h = wakeWave(s, {-xx, 0.0}).x;
        if ((h > 0) != (prev > 0))
            crossings.push_back(xx);
        prev = h;
    }
    ASSERT_GE(crossings.size(), 6u);
    const double spacing = (crossings.back() - crossings.front()) / (crossings.size() - 1);
    EXPECT_NEAR(spacing, std::numbers::pi * 100.0 / GRAVITY, 0.5);
}

// The Kelvin systems are the stationary points of the phase over the wave direction (the method of stationary
// phase): d(phase)/dT = 0 at both roots of 2 tan(a) T^2 - T + tan(a) = 0, across the wedge.
TEST(Wake, KelvinPhaseIsStationaryAtItsRoots) {
    for (double a : {0.02, 0.1, 0.2, 0.3, 0.35}) {
        const double x = 250.0, y = a * x, k0 = 0.1;
        const double sd = std::sqrt(1.0 - 8.0 * a * a);
        for (double t : {2.0 * a / (1.0 + sd), (1.0 + sd) / (4.0 * a)}) {
            const double e = 1e-5;
            const double d = (kelvinPhase(k0, x, y, t + e) - kelvinPhase(k0, x, y, t - e)) / (2.0 * e);
            EXPECT_NEAR(d, 0.0, 1e-6 * k0 * x) << "tan a " << a << ", T " << t;
            EXPECT_EQ(kelvinPhase(k0, x, -y, t), kelvinPhase(k0, x, y, t)); // the wake is symmetric
        }
        // Not stationary elsewhere: a direction between the roots.
        const double mid = 0.5 * (2.0 * a / (1.0 + sd) + (1.0 + sd) / (4.0 * a));
        EXPECT_GT(std::abs(kelvinPhase(k0, x, y, mid + 1e-5) - kelvinPhase(k0, x, y, mid - 1e-5)) / 2e-5,
                  1e-3 * k0 * x);
    }
}

// kelvinWave()'s analytic gradient against central differences of kelvinHeight() (e = 1 mm) over the wedge of
// a 60 m ship at 8 m/s (waves from 3 m up), across the band limit, near the cusp, just behind the stern and
// on the track: within 1e-3 of the largest slope, and the same height.
TEST(Wake, KelvinWaveGradientIsTheHeightsDerivative) {
    const WakeState s = sailedWake(120.0, 8.0, 0.0);
    double worst = 0.0, largest = 0.0;
    int points = 0;
    for (double kMax : {EFFECT_K_MAX, 0.2})
        for (double x = 0.5; x < 900.0; x *= 1.37)
            for (double a = -0.36; a <= 0.36; a += 0.0237) {
                const WakeCoords c = wakeCoords(s, glm::dvec2(-x, a * x)); // heading +x: behind is -x
                const double lateral = c.lateral, behind = c.behind;
                const glm::dvec3 w = kelvinWave(s, c, behind, lateral, kMax);
                ASSERT_EQ(w.x, kelvinHeight(s, c, behind, lateral, kMax));
                const double e = 1e-3;
                const double dx = (kelvinHeight(s, c, behind + e, lateral, kMax) -
                                   kelvinHeight(s, c, behind - e, lateral, kMax)) /
                                  (2.0 * e);
                const double dy = (kelvinHeight(s, c, behind, lateral + e, kMax) -
                                   kelvinHeight(s, c, behind, lateral - e, kMax)) /
                                  (2.0 * e);
                if (std::abs(lateral) < 2.0 * e)
                    continue; // |lateral| has a kink on the track: central differences straddle it
                worst = std::max({worst, std::abs(w.y - dx), std::abs(w.z - dy)});
                largest = std::max({largest, std::abs(dx), std::abs(dy)});
                ++points;
            }
    std::printf("kelvinWave vs central differences: worst %.3g, largest slope %.3g, %d points\n", worst,
                largest, points);
    EXPECT_GT(largest, 0.01);
    EXPECT_LT(worst, 1e-3 * largest);
}

TEST(Wake, TurningShipLeavesACurvedWake) {
    // 90 degrees over 60 s at 8 m/s: radius 305 m.
    const double rate = (std::numbers::pi / 2.0) / 60.0;
    const WakeState s = sailedWake(60.0, 8.0, rate);
    // The foam strip follows the path: a point on the path 45 degrees back is white, the point where a
    // straight wake (behind the current heading) would be is not.
    const double radius = 8.0 / rate;
    const glm::dvec2 centre(0.0, radius); // turning left from heading +x around (0, R)
    const glm::dvec2 onPath =
        centre + radius * glm::dvec2(std::sin(std::numbers::pi / 4), -std::cos(std::numbers::pi / 4));
    const WakeCoords c = wakeCoords(s, onPath - s.ship);
    EXPECT_NEAR(c.lateral, 0.0, 2.0);
    EXPECT_NEAR(c.behind, radius * std::numbers::pi / 4.0, 5.0);
    EXPECT_GT(wakeFoam(s, c), 0.5);
    const glm::dvec2 heading(0.0, 1.0); // now sailing +y
    const glm::dvec2 straight = s.ship - c.behind * heading;
    EXPECT_LT(wakeFoam(s, wakeCoords(s, straight - s.ship)), 1e-3);
}

TEST(Wake, FrameOnAKeptPointKeepsTheTravelDirection) {
    // Regression: when a frame lands exactly where the head is frozen into a kept point, the head and the
    // point coincide; the zero-length first segment used to send the wake near the ship along +x (a kink
    // seen in replays of recorded ships). A ship going south-east at ~9.8 m/s keeps a point every ~5 s.
    ecs::Registry reg;
    ecs::EventQueue ev;
    EffectsSystem fx(reg, ev);
    const ecs::Entity e = reg.create();
    reg.emplace<Ship>(e, Ship{{0.0, 0.0}, 60.0});
    ev.enqueue(AttachShipTrail{e, WakeParams{}});
    for (double t = 0.0; t <= 120.0; t += 0.5) {
        reg.get<Ship>(e).position = {7.4 * t, -6.4 * t};
        ev.dispatch();
        fx.update(t, {0.0, 0.0, 100.0});
    }
    const ShipTrail& trail = reg.get<ShipTrail>(e);
    ASSERT_GE(trail.history.size(), 3u);
    ASSERT_EQ(trail.history[0].position, trail.history[1].position); // the case: a point kept at t = 120
    const WakeState s = wakeState(reg.get<Ship>(e), trail, 120.0);
    const glm::dvec2 travel = glm::normalize(glm::dvec2(7.4, -6.4));
    for (double behind : {5.0, 30.0, 200.0}) {
        const WakeCoords c = wakeCoords(s, -behind * travel);
        EXPECT_NEAR(glm::dot(c.direction, travel), 1.0, 1e-9) << behind;
        EXPECT_NEAR(c.behind, behind, 1e-6) << behind;
        EXPECT_NEAR(c.lateral, 0.0, 1e-6) << behind;
    }
    // 40 m east of the ship is ahead of it and to its left, not on the track (the old path walk said
    // behind = 0, lateral = 0 there: the foam strip ran east from the ship).
    const glm::dvec2 q(40.0, 0.0);
    const WakeCoords ahead = wakeCoords(s, q);
    EXPECT_NEAR(ahead.behind, -glm::dot(q, travel), 1e-6);
    EXPECT_NEAR(std::abs(ahead.lateral), std::abs(travel.x * q.y - travel.y * q.x), 1e-6);
}

TEST(Wake, TightCircleStaysFinite) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    // Radius 25 m at 5 m/s, five full turns.
    const ecs::Entity ship = sail(reg, events, fx, 5 * 2 * std::numbers::pi * 5.0, 5.0, 0.2);
    const ShipTrail& trail = reg.get<ShipTrail>(ship);
    EXPECT_LE(trail.history.size(), static_cast<size_t>(MAX_WAKE_POINTS));
    const WakeState s = wakeState(reg.get<Ship>(ship), trail, 157.0);
    for (double x = -60.0; x <= 60.0; x += 0.7)
        for (double y = -60.0; y <= 60.0; y += 0.7) {
            const glm::dvec3 w = wakeWave(s, {x, y});
            ASSERT_TRUE(std::isfinite(w.x) && std::isfinite(w.y) && std::isfinite(w.z)) << x << "," << y;
            ASSERT_LT(std::abs(w.x), 5.0);
        }
}

TEST(EffectGrids, BadDescriptionsNameTheField) {
    auto message = [](const OceanDesc& d) {
        try {
            (void)makeOcean(d);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_EQ(message(OceanDesc{}), "(accepted)");
    OceanDesc d;
    d.effectGrids.explosionSegments = 0;
    EXPECT_EQ(message(d), "OceanDesc.effectGrids.explosionSegments must be in [3, 4096], got 0");
    d = {};
    d.effectGrids.wakeRings = -3;
    EXPECT_EQ(message(d), "OceanDesc.effectGrids.wakeRings must be in [1, 1024], got -3");
    d = {};
    d.effectGrids.wakeExponent = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(message(d).find("OceanDesc.effectGrids.wakeExponent must be in [0.25, 8]"), std::string::npos);
}

TEST(EffectField, BadDescriptionsNameTheField) {
    auto message = [](const EffectFieldDesc& d) {
        try {
            validate(d);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("(accepted)");
    };
    EXPECT_EQ(message({}), "(accepted)");
    EXPECT_EQ(message({.size = 100}), "EffectFieldDesc.size must be a multiple of 8 in 16..2048, got 100");
    EXPECT_EQ(message({.levels = 0}), "EffectFieldDesc.levels must be in 1..16, got 0");
    EXPECT_EQ(message({.finestTexel = std::numeric_limits<double>::quiet_NaN()}),
              "EffectFieldDesc.finestTexel must be in 0.01..100 m");
    OceanDesc d;
    d.effectField.levels = 17;
    EXPECT_THROW((void)makeOcean(d), std::invalid_argument);
}

// The clipmap around a camera far from the origin: each level's centre on its texel grid within a texel of
// the camera, texels 0.5 m doubling, the band limit 4 texels a wavelength (the finest level keeps the
// analytic 3 m), and a point reads the finest level that holds it, blending into the next at its edge.
TEST(EffectField, LevelsAreSnappedNestedAndPickedFinestFirst) {
    const glm::dvec2 cam(1.0e7 + 0.37, -1.0e7 + 0.81);
    const EffectFieldLayout layout({}, cam);
    ASSERT_EQ(layout.levels(), 9);
    for (int l = 0; l < layout.levels(); ++l) {
        const EffectFieldLevel& level = layout.level(l);
        EXPECT_DOUBLE_EQ(level.texel, 0.5 * std::ldexp(1.0, l));
        EXPECT_EQ(std::fmod(level.centre.x, level.texel), 0.0) << l;
        EXPECT_EQ(std::fmod(level.centre.y, level.texel), 0.0) << l;
        EXPECT_GE(cam.x - level.centre.x, 0.0);
        EXPECT_LT(cam.x - level.centre.x, level.texel);
        EXPECT_DOUBLE_EQ(level.kMax, std::min(EFFECT_K_MAX, 2.0 * std::numbers::pi / (4.0 * level.texel)));
        EXPECT_DOUBLE_EQ(level.inner, 254.0 * level.texel);
        EXPECT_DOUBLE_EQ(level.band, 64.0 * level.texel);
    }
    EXPECT_DOUBLE_EQ(layout.level(0).kMax, EFFECT_K_MAX);
    // Texel (i, j)'s centre.
    EXPECT_EQ(layout.texelCentre(2, 256, 256), layout.level(2).centre + glm::dvec2(1.0));
    EXPECT_EQ(layout.texelCentre(0, 0, 511), layout.level(0).centre + glm::dvec2(-127.75, 127.75));
    // Picks: at the camera the finest alone; 150 m out level 0's edge blends into level 1; 300 m: level 2.
    EXPECT_EQ(layout.pick(cam).level, 0);
    EXPECT_EQ(layout.pick(cam).blend, 0.0);
    const EffectFieldLayout::Pick edge = layout.pick(layout.level(0).centre + glm::dvec2(100.0, 0.0));
    EXPECT_EQ(edge.level, 0);
    EXPECT_NEAR(edge.blend, (100.0 - 95.0) / 32.0, 1e-12);
    EXPECT_EQ(layout.pick(layout.level(0).centre + glm::dvec2(0.0, -300.0)).level, 2);
    EXPECT_EQ(layout.pick(layout.level(8).centre + glm::dvec2(32000.0, 0.0)).level, 8);
    EXPECT_EQ(layout.pick(layout.level(8).centre + glm::dvec2(32600.0, 0.0)).level, -1);
    // From altitude the finest level is the coarsest texel no larger than a pixel's footprint below.
    EXPECT_EQ(EffectFieldLayout({}, cam, 0.3).level(0).texel, 0.5);
    EXPECT_EQ(EffectFieldLayout({}, cam, 1.3).level(0).texel, 1.0);
    EXPECT_EQ(EffectFieldLayout({}, cam, 8.6).level(0).texel, 8.0);
    EXPECT_EQ(EffectFieldLayout({}, cam, 8.6).level(8).texel, 2048.0);
}

// The CPU twin of the GPU's read: at a texel centre of the level a point reads alone it is the texel's value
// (the analytic field band-limited to the level); between texels it is bilinear; across a level's blend band
// it is continuous; outside the field it is 0.
TEST(EffectField, TwinReadsTexelsBilinearlyAndBlendsLevelsContinuously) {
    ecs::Registry reg;
    const glm::dvec2 cam(20.0, -30.0);
    const Explosion e = makeExplosion({60.0, -10.0}, 0.0);
    reg.emplace<Explosion>(reg.create(), e);
    const double t = 6.0;
    const EffectFieldLayout layout({}, cam);
    const glm::dvec2 texel = layout.texelCentre(0, 300, 280);
    const glm::dvec4 v = sampleEffectField(reg, layout, texel, t);
    const glm::dvec4 exact = effectsFieldAt(reg, texel, t, layout.level(0).kMax, layout.level(0).foamFilter2);
    EXPECT_NEAR(v.x, exact.x, 1e-12);
    EXPECT_NEAR(v.y, exact.y, 1e-12);
    EXPECT_NEAR(v.w, exact.w, 1e-12);
    // Level 0 holds the analytic field (its band limit is the analytic one); bilinear error <= A k^2 T^2 / 8.
    const glm::dvec3 analytic = effectsAt(reg, texel, t);
    EXPECT_NEAR(v.x, analytic.x, 1e-12);
    const double a = e.params.amplitude, k = e.params.wavenumber;
    double worst = 0.0;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec2 p = e.center + glm::dvec2(std::cos(i * 0.7), std::sin(i * 0.7)) * (0.3 * i);
        if (layout.pick(p).level != 0 || layout.pick(p).blend > 0.0)
            continue;
        worst = std::max(worst, std::abs(sampleEffectField(reg, layout, p, t).x - effectsAt(reg, p, t).x));
    }
    EXPECT_GT(worst, 0.0);
    EXPECT_LE(worst, a * k * k * 0.25 / 8.0 * 1.5) << "bilinear error at 0.5 m texels";
    // Continuity across level 0's blend band and its outer edge into level 1 (steps of 1 cm), at t = 30 s
    // when the ring (0.33 m, slopes <= 0.07) has spread past them: no step beyond the slope's 0.7 mm.
    double jump = 0.0;
    const double later = 30.0;
    glm::dvec4 prev = sampleEffectField(reg, layout, cam + glm::dvec2(80.0, 0.5), later);
    for (double x = 80.01; x < 140.0; x += 0.01) {
        const glm::dvec4 next = sampleEffectField(reg, layout, cam + glm::dvec2(x, 0.5), later);
        jump = std::max(jump, std::abs(next.x - prev.x));
        prev = next;
    }
    EXPECT_GT(jump, 0.0);
    EXPECT_LT(jump, 1e-3) << "largest change over 1 cm";
    EXPECT_EQ(sampleEffectField(reg, layout, cam + glm::dvec2(4.0e4, 0.0), t), glm::dvec4(0.0));
}

// The foam's prefilter for a coarse level keeps a crown's and a strip's area (their coverage summed over the
// sea), so a crown smaller than a texel does not fall between texel centres.
TEST(EffectField, FoamPrefilterKeepsTheCoverage) {
    const Explosion e = makeExplosion({0.0, 0.0}, 0.0);
    const ExplosionState s = explosionState(e, 3.0);
    auto area = [&](double filter2) {
        double sum = 0.0;
        for (double x = -60.0; x <= 60.0; x += 0.25)
            for (double y = -60.0; y <= 60.0; y += 0.25)
                sum += 0.0625 * explosionFoam(e.params,
                                              ExplosionState{s.tau, 0.0, s.phase, s.front, s.frontWidth,
                                                             s.radius, s.foam, s.crownRadius},
                                              {x, y}, 0.0, filter2);
        return sum;
    };
    const double sharp = area(0.0), coarse = area(16.0 * 16.0 / 6.0);
    EXPECT_NEAR(sharp, s.foam * std::numbers::pi * s.crownRadius * s.crownRadius, 0.01 * sharp);
    EXPECT_NEAR(coarse, sharp, 0.01 * sharp);
    EXPECT_LT(explosionFoam(e.params, s, {0.0, 0.0}, 0.0, 256.0 / 6.0),
              explosionFoam(e.params, s, {0.0, 0.0}, 0.0));
}

// Band limit: a level whose texels cannot carry a ring leaves it out (effectBandFade), the foam stays.
TEST(EffectField, CoarseLevelsLeaveOutWavesTheyCannotCarry) {
    EXPECT_EQ(effectBandFade(1.0, 4.0), 1.0);
    EXPECT_EQ(effectBandFade(4.0, 4.0), 0.0);
    EXPECT_NEAR(effectBandFade(3.0, 4.0), 0.5, 1e-12);
    const Explosion e = makeExplosion({0.0, 0.0}, 0.0);
    const ExplosionState s = explosionState(e, 5.0);
    const glm::dvec2 q(20.0, 5.0);
    const double kMax16 = 2.0 * std::numbers::pi / (4.0 * 16.0); // 16 m texels: 0.098 rad/m < k = 0.2
    EXPECT_EQ(explosionWave(e.params, s, q, kMax16), glm::dvec3(0.0));
    EXPECT_NE(explosionWave(e.params, s, q).x, 0.0);
    ecs::Registry reg;
    reg.emplace<Explosion>(reg.create(), e);
    EXPECT_GT(effectsFieldAt(reg, {0.0, 0.0}, 5.0, kMax16).w, 0.5) << "the crown's foam is kept";
}

TEST(EffectsSystem, StoppedShipsWakeEndsWithAnEvent) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    std::vector<EffectEnded> ended;
    events.subscribe<EffectEnded>([&](const EffectEnded& e) { ended.push_back(e); });
    const ecs::Entity ship = sail(reg, events, fx, 60.0, 10.0, 0.0); // sails 60 s, then stops at x = 600
    EXPECT_EQ(fx.counters().activeWakes, 1);
    // Stopped: no new waves (speed < minSpeed), the old ones decay (waves e^(-age/90 s) from 0.5 m under
    // 1 cm after ~350 s; the foam strip e^(-age/150 s) under 0.01 after ~690 s): the wake goes quiet then.
    double endTime = -1.0;
    for (double t = 61.0; t < 1200.0; t += 1.0) {
        events.dispatch();
        fx.update(t, {0.0, 0.0, 100.0});
        if (fx.counters().ended == 1 && endTime < 0.0)
            endTime = t;
    }
    events.dispatch();
    ASSERT_EQ(ended.size(), 1u);
    EXPECT_EQ(ended[0].kind, EffectKind::Wake);
    EXPECT_EQ(ended[0].entity, ship);
    EXPECT_FALSE(ended[0].dropped);
    // At most 690 s (full-strength foam laid at the stop); earlier by how much the last points' strength
    // (speed^2) and age had already fallen (the newest kept point is up to 10 s old).
    EXPECT_GT(endTime - 60.0, 550.0);
    EXPECT_LE(endTime - 60.0, 691.0);
    EXPECT_EQ(fx.counters().activeWakes, 0);
    EXPECT_FALSE(reg.get<ShipTrail>(ship).active);
    EXPECT_EQ(effectsAt(reg, {300.0, 0.0}, 1199.0), glm::dvec3(0.0));
}

TEST(EffectsSystem, WakeCapDrawsTheMostVisibleAndCountsTheRest) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsDesc desc;
    desc.maxWakes = 3;
    EffectsSystem fx(reg, events, desc);
    // Five ships sailing east in lanes 0, 1, 2, 3 and 4 km north of the camera at the origin.
    std::vector<ecs::Entity> ships;
    for (int i = 0; i < 5; ++i) {
        ships.push_back(reg.create());
        reg.emplace<Ship>(ships.back(), Ship{{0.0, 1000.0 * i}, 60.0});
        events.enqueue(AttachShipTrail{ships.back(), WakeParams{}});
    }
    for (int k = 0; k <= 300; ++k) {
        for (int i = 0; i < 5; ++i)
            reg.get<Ship>(ships[size_t(i)]).position = {k * 1.0, 1000.0 * i};
        events.dispatch();
        fx.update(k * 0.1, {0.0, 0.0, 100.0});
    }
    EXPECT_EQ(fx.counters().activeWakes, 3);
    EXPECT_EQ(fx.counters().droppedWakes, 2);
    for (int i = 0; i < 5; ++i) // the nearest three are drawn and queried
        EXPECT_EQ(reg.get<ShipTrail>(ships[size_t(i)]).active, i < 3) << i;
    EXPECT_EQ(effectsFoamAt(reg, {250.0, 4000.0}, 30.0), 0.0); // dropped this frame: not in the queries
    EXPECT_GT(effectsFoamAt(reg, {250.0, 0.0}, 30.0), 0.3);    // drawn: its foam strip
}

TEST(EffectsSystem, EventsCreateExplosionsThatEndWithAnEvent) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    int endedEvents = 0;
    events.subscribe<EffectEnded>([&](const EffectEnded& e) {
        EXPECT_EQ(e.kind, EffectKind::Explosion);
        EXPECT_FALSE(e.dropped);
        ++endedEvents;
    });
    events.enqueue(SpawnExplosion{{10.0, 20.0}, 1.0, 1.0});
    events.dispatch();
    fx.update(1.0, {0, 0, 50});
    EXPECT_EQ(fx.counters().spawned, 1);
    auto view = reg.view<Explosion>();
    ASSERT_NE(view.begin(), view.end());
    EXPECT_EQ(reg.get<Explosion>(*view.begin()).center, glm::dvec2(10.0, 20.0));
    // The nominal explosion's waves decay as e^(-0.06 tau) from 2 m: under 1 cm after ~88 s; its crown's foam
    // sooner; its slick, 0.6 e^(-tau / 120 s), stays white for minutes (0.22 at 2 minutes) and falls under
    // 0.01 after 120 ln 60 = 491 s: then it ends.
    double endTime = -1.0;
    for (double t = 1.0; t < 700.0; t += 0.5) {
        events.dispatch();
        fx.update(t, {0, 0, 50});
        if (fx.counters().ended == 1)
            endTime = t;
        if (t == 121.0) {
            EXPECT_NEAR(effectsFoamAt(reg, {10.0, 20.0}, t), 0.6 * (1.0 - std::exp(-24.0)) * std::exp(-1.0),
                        1e-9);
        }
    }
    events.dispatch();
    EXPECT_EQ(endedEvents, 1);
    EXPECT_GT(endTime - 1.0, 485.0);
    EXPECT_LT(endTime - 1.0, 495.0);
    EXPECT_EQ(reg.view<Explosion>().begin(), reg.view<Explosion>().end());
}

// The host loop's effects step (EffectsTimeline): ships follow their tracks, explosions spawn at the first
// step at or after their time and in time order whatever order they were given, and the warm-up lays a
// ship's wake before the first frame, one recorded point per 0.5 s step.
TEST(EffectsTimeline, MovesShipsSpawnsDueExplosionsAndWarmsUpWakes) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    EffectsTimeline timeline(reg, events, fx);
    const ecs::Entity ship =
        timeline.addShip({-100.0, 0.0}, 60.0, [](double t) { return glm::dvec2(10.0 * t, 0.0); });
    timeline.scheduleExplosions({SpawnExplosion{{5.0, 5.0}, 7.0, 1.0}, SpawnExplosion{{1.0, 1.0}, 2.0, 1.0},
                                 SpawnExplosion{{2.0, 2.0}, 2.0, 1.5}});
    std::vector<double> spawnedAt; // the explosions' centres' x, in the order they were created
    timeline.warmUp(-10.0, 0.0, {0.0, 0.0, 100.0});
    ASSERT_TRUE(reg.has<ShipTrail>(ship));
    EXPECT_EQ(reg.get<Ship>(ship).position, glm::dvec2(-5.0, 0.0)); // the last warm-up step, t = -0.5
    EXPECT_EQ(timeline.explosionsSpawned(), 0u);
    EXPECT_EQ(reg.view<Explosion>().begin(), reg.view<Explosion>().end());
    // 20 steps of 0.5 s at 10 m/s: the trail holds points along the 95 m sailed, the newest at x = -5.
    const ShipTrail& trail = reg.get<ShipTrail>(ship);
    ASSERT_GE(trail.history.size(), 2u);
    EXPECT_EQ(trail.history.front().position, glm::dvec2(-5.0, 0.0));
    EXPECT_EQ(trail.history.front().time, -0.5);

    timeline.step(1.9, {0.0, 0.0, 100.0});
    EXPECT_EQ(reg.get<Ship>(ship).position, glm::dvec2(19.0, 0.0));
    EXPECT_EQ(timeline.explosionsSpawned(), 0u);
    timeline.step(2.0, {0.0, 0.0, 100.0}); // both t = 2 explosions, in the order given, not the t = 7 one
    EXPECT_EQ(timeline.explosionsSpawned(), 2u);
    EXPECT_EQ(fx.counters().spawned, 2);
    reg.view<Explosion>().each([&](ecs::Entity, Explosion& e) { spawnedAt.push_back(e.center.x); });
    ASSERT_EQ(spawnedAt.size(), 2u);
    EXPECT_EQ(spawnedAt[0] + spawnedAt[1], 3.0);
    timeline.step(6.99, {0.0, 0.0, 100.0});
    EXPECT_EQ(timeline.explosionsSpawned(), 2u);
    timeline.step(7.5, {0.0, 0.0, 100.0});
    EXPECT_EQ(timeline.explosionsSpawned(), 3u);
    EXPECT_EQ(fx.counters().spawned, 1);
    ASSERT_EQ(timeline.ships().size(), 1u);
    EXPECT_EQ(timeline.ships()[0], ship);
}

// A host that moves its ships itself (the game) runs its own placement before each warm-up step.
TEST(EffectsTimeline, WarmUpRunsTheHostsStepFirst) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    EffectsTimeline timeline(reg, events, fx);
    const ecs::Entity ship = reg.create();
    reg.emplace<Ship>(ship, Ship{{0.0, 0.0}, 40.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    std::vector<double> times;
    timeline.warmUp(-2.0, 0.0, {0.0, 0.0, 50.0}, [&](double t) {
        times.push_back(t);
        reg.get<Ship>(ship).position = {0.0, 8.0 * t};
    });
    EXPECT_EQ(times, (std::vector<double>{-2.0, -1.5, -1.0, -0.5}));
    EXPECT_EQ(reg.get<ShipTrail>(ship).history.front().position, glm::dvec2(0.0, -4.0));
}

TEST(EffectsSystem, CapDropsTheLeastVisibleAndCountsIt) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsDesc desc;
    desc.maxExplosions = 4;
    EffectsSystem fx(reg, events, desc);
    int droppedEvents = 0;
    events.subscribe<EffectEnded>([&](const EffectEnded& e) { droppedEvents += e.dropped ? 1 : 0; });
    // Four near the camera, then one far away (least visible: dropped itself), then a near one that
    // replaces the farthest of the four.
    for (int i = 0; i < 4; ++i)
        events.enqueue(SpawnExplosion{{100.0 + 50.0 * i, 0.0}, 0.0, 1.0});
    events.enqueue(SpawnExplosion{{30000.0, 0.0}, 0.0, 1.0});
    events.enqueue(SpawnExplosion{{50.0, 0.0}, 0.0, 1.0});
    events.dispatch();
    fx.update(0.0, {0.0, 0.0, 100.0});
    EXPECT_EQ(fx.counters().spawned, 5);
    EXPECT_EQ(fx.counters().droppedExplosions, 2);
    EXPECT_EQ(fx.counters().totalDroppedExplosions, 2);
    std::vector<double> xs;
    reg.view<Explosion>().each([&](ecs::Entity, Explosion& e) { xs.push_back(e.center.x); });
    std::sort(xs.begin(), xs.end());
    EXPECT_EQ(xs, (std::vector<double>{50.0, 100.0, 150.0, 200.0}));
    events.dispatch();
    EXPECT_EQ(droppedEvents, 2);
}

TEST(EffectsSystem, TenThousandSpawnsInOneSecondStayCapped) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    long long dropped = 0;
    for (int frame = 0; frame < 60; ++frame) {
        const double t = frame / 60.0;
        for (int i = 0; i < 10000 / 60 + (frame < 10000 % 60 ? 1 : 0); ++i)
            events.enqueue(
                SpawnExplosion{{std::fmod(i * 37.0, 900.0), std::fmod(i * 53.0, 700.0)}, t, 1.0 + (i % 5)});
        events.dispatch();
        fx.update(t, {0.0, 0.0, 300.0});
        dropped += fx.counters().droppedExplosions;
        size_t n = 0;
        reg.view<Explosion>().each([&](ecs::Entity, Explosion&) { ++n; });
        ASSERT_LE(n, 1024u); // EffectsDesc::maxExplosions
    }
    EXPECT_EQ(EffectsDesc{}.maxExplosions, 1024);
    EXPECT_EQ(dropped, 10000 - 1024);
    EXPECT_EQ(fx.counters().totalDroppedExplosions, 10000 - 1024);
    const glm::dvec3 e = effectsAt(reg, {450.0, 350.0}, 1.5);
    EXPECT_TRUE(std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z));
    EXPECT_LE(std::abs(e.x), EFFECT_HEIGHT_LIMIT);
}

// The cap's heap keeps exactly what dropping the least visible spawn by spawn keeps: 5000 equal charges at
// 1..5000 m from the camera, spawned in one frame in a scrambled order under a cap of 100, leave the 100
// nearest.
TEST(EffectsSystem, OneFrameStormKeepsTheMostVisible) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsDesc desc;
    desc.maxExplosions = 100;
    EffectsSystem fx(reg, events, desc);
    for (int i = 0; i < 5000; ++i) {
        const int d = 1 + (i * 2963) % 5000; // 2963 is prime to 5000: every distance once
        events.enqueue(SpawnExplosion{{static_cast<double>(d), 0.0}, 0.0, 1.0});
    }
    events.dispatch();
    fx.update(0.0, {0.0, 0.0, 0.0});
    EXPECT_EQ(fx.counters().droppedExplosions, 4900);
    std::vector<double> xs;
    reg.view<Explosion>().each([&](ecs::Entity, Explosion& e) { xs.push_back(e.center.x); });
    std::sort(xs.begin(), xs.end());
    ASSERT_EQ(xs.size(), 100u);
    EXPECT_EQ(xs.front(), 1.0);
    EXPECT_EQ(xs.back(), 100.0);
}

// Values no scene means are rejected and counted like NaN, interleaved with good ones in one stream.
TEST(EffectsSystem, HugeSpawnValuesAreRejectedAndCounted) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    const double inf = std::numeric_limits<double>::infinity();
    events.enqueue(SpawnExplosion{{0.0, 0.0}, 0.0, 1.0});
    events.enqueue(SpawnExplosion{{1e300, 0.0}, 0.0, 1.0});    // beyond MAX_EFFECT_DISTANCE
    events.enqueue(SpawnExplosion{{0.0, -2e9}, 0.0, 1.0});     // the same
    events.enqueue(SpawnExplosion{{10.0, 0.0}, 0.0, 1e300});   // beyond MAX_EXPLOSION_STRENGTH
    events.enqueue(SpawnExplosion{{20.0, 0.0}, 1e12, 1.0});    // starts 30 000 years later
    events.enqueue(SpawnExplosion{{30.0, 0.0}, -inf, 1.0});    // not finite
    events.enqueue(SpawnExplosion{{9.9e8, 0.0}, 3599.0, 1e6}); // at the bounds: kept
    events.dispatch();
    EXPECT_NO_THROW(fx.update(0.0, {0, 0, 10}));
    EXPECT_EQ(fx.counters().rejected, 5);
    EXPECT_EQ(fx.counters().spawned, 2);
}

TEST(EffectsSystem, BadSpawnDataIsRejectedNotThrown) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    events.enqueue(SpawnExplosion{{nan, 0.0}, 0.0, 1.0});
    events.enqueue(SpawnExplosion{{0.0, 0.0}, 0.0, -2.0});
    events.enqueue(SpawnExplosion{{0.0, 0.0}, std::numeric_limits<double>::infinity(), 1.0});
    events.enqueue(AttachShipTrail{reg.create(), WakeParams{}}); // no Ship component
    events.dispatch();
    EXPECT_NO_THROW(fx.update(0.0, {0, 0, 10}));
    EXPECT_EQ(fx.counters().rejected, 4);
    EXPECT_EQ(fx.counters().spawned, 0);
    EXPECT_EQ(reg.view<Explosion>().begin(), reg.view<Explosion>().end());
}

// A ship whose track is lost for a frame (a NaN position): counted as rejected, its path kept, and left out
// of the registry's EffectsView that frame -- the renderer refuses a non-finite scene, so one lost track must
// not cost the whole frame -- then back once its position is finite again.
TEST(EffectsSystem, ALostShipTrackCostsItsWakeOneFrameNotTheFrame) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsSystem fx(reg, events);
    const ecs::Entity ship = reg.create(), other = reg.create();
    reg.emplace<Ship>(ship, Ship{{0.0, 0.0}, 60.0});
    reg.emplace<Ship>(other, Ship{{500.0, 0.0}, 60.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    events.enqueue(AttachShipTrail{other, WakeParams{}});
    for (int k = 0; k <= 40; ++k) {
        reg.get<Ship>(ship).position = {0.0, 8.0 * 0.5 * k};
        reg.get<Ship>(other).position = {500.0, 8.0 * 0.5 * k};
        events.dispatch();
        fx.update(0.5 * k, {0, 0, 100});
    }
    const size_t pathBefore = reg.get<ShipTrail>(ship).history.size();
    ASSERT_EQ(RegistryEffects(reg).view().wakes.size(), 2u);
    reg.get<Ship>(ship).position.x = std::numeric_limits<double>::quiet_NaN();
    events.dispatch();
    fx.update(20.5, {0, 0, 100});
    EXPECT_EQ(fx.counters().rejected, 1);
    EXPECT_EQ(reg.get<ShipTrail>(ship).history.size(), pathBefore) << "a NaN position never enters the path";
    const RegistryEffects lost(reg);
    ASSERT_EQ(lost.view().wakes.size(), 1u);
    EXPECT_EQ(lost.view().wakes[0].ship, &reg.get<Ship>(other));
    reg.get<Ship>(ship).position = {0.0, 8.0 * 20.5};
    events.dispatch();
    fx.update(21.0, {0, 0, 100});
    EXPECT_EQ(fx.counters().rejected, 0);
    EXPECT_EQ(RegistryEffects(reg).view().wakes.size(), 2u);
}

TEST(EffectsSystem, ThousandOverlappingExplosionsSaturate) {
    ecs::Registry reg;
    ecs::EventQueue events;
    EffectsDesc desc;
    desc.maxExplosions = 1000;
    EffectsSystem fx(reg, events, desc);
    for (int i = 0; i < 1000; ++i)
        events.enqueue(SpawnExplosion{{0.0, 0.0}, 0.0, 1.0});
    events.dispatch();
    fx.update(0.0, {0, 0, 100});
    EXPECT_EQ(fx.counters().spawned, 1000);
    double worst = 0.0;
    for (double r = 0.0; r < 60.0; r += 0.5) {
        const glm::dvec3 e = effectsAt(reg, {r, 0.3 * r}, 3.0);
        ASSERT_TRUE(std::isfinite(e.x) && std::isfinite(e.y) && std::isfinite(e.z));
        worst = std::max(worst, std::abs(e.x));
    }
    EXPECT_LE(worst, EFFECT_HEIGHT_LIMIT);
    EXPECT_GT(worst, 0.9 * EFFECT_HEIGHT_LIMIT); // 1000 x ~1.7 m, saturated
}

} // namespace

// The wake's white water (wakeFoam, Effects.h WAKE_*): a 60 m ship (beam 12 m) after 120 s at 10 m/s (Froude
// number 10 / sqrt(9.81 * 60) = 0.41: a breaking bow wave). 100 m behind the stern the propeller wash is a
// bright core (half-width 0.3 B sqrt(1 + 100 / 120) = 4.9 m) over the paler turbulent strip (0.45 as white,
// half-width 15 m); beside the bow the bow wave's line leaves the shoulder (6 m out) at the Kelvin angle;
// under the hull's forward half and ahead of the bow there is none; a ship at Froude 0.1 breaks no bow wave.
TEST(Wake, WhiteWaterHasAWashCoreAStripAndABowWave) {
    const WakeState s = sailedWake(120.0, 10.0, 0.0);
    auto foamAt = [&](const WakeState& w, double behind, double lateral) {
        return wakeFoam(w, wakeCoords(w, glm::dvec2(-behind, lateral)));
    };
    const double L = 60.0, B = 12.0;
    const double aged = std::exp(-13.0 / WakeParams{}.foamLife); // 100 m + L/2 behind: laid 13 s ago
    const double core = foamAt(s, 0.5 * L + 100.0, 0.0), edge = foamAt(s, 0.5 * L + 100.0, 8.0);
    EXPECT_NEAR(core, aged, 0.01) << "the wash is white on the track";
    EXPECT_NEAR(edge, 0.45 * std::exp(-std::pow(8.0 / (B * 1.25), 2.0)) * aged, 0.01) << "the strip, paler";
    EXPECT_GT(core, 2.5 * edge);
    EXPECT_LT(foamAt(s, 0.5 * L + 100.0, 50.0), 1e-3) << "beyond 3 strip widths";
    // The bow wave 20 m behind the bow: its line at 6 + 20 / sqrt(8) = 13.1 m out, e^(-20 / 21) strong.
    const double bow = foamAt(s, -0.5 * L + 20.0, 13.07);
    EXPECT_NEAR(bow, std::exp(-20.0 / (0.35 * L)), 0.03);
    EXPECT_GT(bow, 5.0 * foamAt(s, -0.5 * L + 20.0, 20.0)) << "a line, not a sheet";
    EXPECT_LT(foamAt(s, -0.5 * L + 20.0, 0.0), 1e-6) << "none under the hull's forward half";
    EXPECT_LT(foamAt(s, -0.5 * L - 10.0, 6.0), 1e-6) << "none ahead of the bow";
    EXPECT_LT(foamAt(s, 2.0 * L, 40.0), 1e-3) << "the bow wave is gone a ship length behind the bow";
    // A slow ship (2.4 m/s: Froude 0.1) pushes a smooth bow wave; its stern still leaves wash.
    const WakeState slow = sailedWake(120.0, 0.1 * std::sqrt(GRAVITY * L), 0.0);
    EXPECT_EQ(foamAt(slow, -0.5 * L + 20.0, 13.07), 0.0);
    EXPECT_GT(foamAt(slow, 0.5 * L + 20.0, 0.0), 0.05);
}
