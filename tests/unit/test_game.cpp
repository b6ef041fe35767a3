// The game's core (game/): flight model physics, weapon ballistics, routes, the sortie rules, the autopilot
// flying a whole sortie, determinism, and the ACMI session read back by the replay's own readers.
#include <game/Autopilot.h>
#include <game/FlightModel.h>
#include <game/Night.h>
#include <game/SessionRecorder.h>
#include <game/World.h>

#include <ocean/Effects.h>
#include <ocean/Ocean.h>
#include <ocean/OceanHost.h>
#include <recording/EarthFrame.h>
#include <recording/Recording.h>
#include <recording/SeaDrivers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>

using namespace pacifica;
using namespace pacifica::game;

namespace {

/// A registry with an ocean, an event queue and the effects system, as the game has them.
struct Scene {
    ecs::Registry registry;
    ecs::EventQueue events;
    ecs::Entity ocean;
    std::unique_ptr<ocean::EffectsSystem> effects;
    std::unique_ptr<World> world;
    explicit Scene(const WorldDesc& desc = {}) {
        ocean = registry.create();
        registry.emplace<ocean::OceanComponent>(ocean, ocean::makeOcean({}));
        effects = std::make_unique<ocean::EffectsSystem>(registry, events);
        world = std::make_unique<World>(registry, events, ocean, desc);
    }
    /// Steps at 120 Hz for `seconds`, flown by f(world) -> controls; effects updated at 30 Hz.
    template <class F>
    void fly(double seconds, F&& f) {
        const int n = static_cast<int>(std::lround(seconds * 120.0));
        for (int i = 0; i < n; ++i) {
            world->step(f(*world), 1.0 / 120.0);
            if (i % 4 == 0) {
                events.dispatch();
                effects->update(world->time(), world->player().pose.position);
            }
        }
    }
};

AircraftState levelAt(double speed, double z) {
    AircraftState s;
    s.pose.position = {0.0, 0.0, z};
    s.pose.headingDeg = 90.0;
    s.velocity = {speed, 0.0, 0.0};
    s.throttle = 0.0;
    return s;
}

} // namespace

TEST(FlightModel, LiftCurveIsLinearToTheStallThenFalls) {
    const AircraftParams p;
    const double stall = p.stallAlphaDeg * M_PI / 180.0;
    EXPECT_DOUBLE_EQ(liftCoefficient(p, 0.0), p.cl0);
    EXPECT_NEAR(liftCoefficient(p, stall), p.clMax(), 1e-12);
    EXPECT_NEAR(liftCoefficient(p, stall + 1e-9), p.clMax(), 1e-6); // continuous at the stall
    EXPECT_NEAR(liftCoefficient(p, stall + 10.0 * M_PI / 180.0), 0.45 * p.clMax(), 1e-12);
    EXPECT_LT(liftCoefficient(p, stall + 5.0 * M_PI / 180.0), p.clMax());
    // Stall speed sqrt(2 m g / (rho0 S CLmax)) for the default jet: ~52 m/s.
    EXPECT_NEAR(p.stallSpeed(), std::sqrt(2.0 * 9000.0 * 9.81 / (1.225 * 38.0 * p.clMax())), 1e-9);
    EXPECT_NEAR(p.stallSpeed(), 52.0, 1.0);
    EXPECT_NEAR(airDensity(0.0), 1.225, 1e-12);
    EXPECT_NEAR(airDensity(8500.0), 1.225 / M_E, 1e-9);
}

TEST(FlightModel, GlidingWithoutThrustLosesEnergyToDrag) {
    const AircraftParams p;
    AircraftState s = levelAt(150.0, 1000.0);
    auto energy = [](const AircraftState& a) {
        return 0.5 * glm::dot(a.velocity, a.velocity) + GRAVITY * a.pose.position.z;
    };
    double e = energy(s);
    for (int i = 0; i < 120 * 30; ++i) {
        stepAircraft(s, {}, p, 1.0 / 120.0, std::nullopt);
        const double e2 = energy(s);
        ASSERT_LE(e2, e + 1e-6) << "energy rose at step " << i;
        e = e2;
    }
    // Lost at least what the zero-lift drag alone takes at >= 60 m/s for 30 s (a loose lower bound).
    EXPECT_LT(e,
              energy(levelAt(150.0, 1000.0)) - 0.5 * 1.0 * 60.0 * 60.0 * 38.0 * p.cd0 * 60.0 * 30.0 / p.mass);
    EXPECT_FALSE(s.stalled);
}

TEST(FlightModel, FullThrottleLevelFlightAcceleratesAndFullAftStickStalls) {
    const AircraftParams p;
    AircraftState s = levelAt(120.0, 2000.0);
    s.throttle = 1.0;
    for (int i = 0; i < 120 * 5; ++i)
        stepAircraft(s, {0.0, 0.0, 0.0, 1.0}, p, 1.0 / 120.0, std::nullopt);
    EXPECT_GT(s.airspeed(), 125.0);
    // Slow, then pull the stick fully back: the angle of attack passes the stall and height is lost.
    AircraftState slow = levelAt(60.0, 2000.0);
    bool stalled = false;
    for (int i = 0; i < 120 * 8; ++i) {
        stepAircraft(slow, {1.0, 0.0, 0.0, 0.0}, p, 1.0 / 120.0, std::nullopt);
        stalled = stalled || slow.stalled;
    }
    EXPECT_TRUE(stalled);
    EXPECT_LT(slow.pose.position.z, 2000.0);
}

TEST(FlightModel, BankedPullTurnsTowardTheLoweredWing) {
    const AircraftParams p;
    AircraftState s = levelAt(150.0, 2000.0); // heading 90 (east)
    s.throttle = 0.8;
    for (int i = 0; i < 120 * 1; ++i) // roll right
        stepAircraft(s, {0.0, 0.5, 0.0, 0.8}, p, 1.0 / 120.0, std::nullopt);
    EXPECT_GT(s.pose.rollDeg, 30.0);
    for (int i = 0; i < 120 * 3; ++i)
        stepAircraft(s, {0.4, 0.0, 0.0, 0.8}, p, 1.0 / 120.0, std::nullopt);
    EXPECT_GT(s.pose.headingDeg, 110.0); // turned right (clockwise)
    EXPECT_GT(s.loadFactor, 1.2);
}

TEST(FlightModel, NonFiniteControlsAreIgnored) {
    const AircraftParams p;
    AircraftState s = levelAt(150.0, 1000.0);
    stepAircraft(s, {NAN, INFINITY, -INFINITY, NAN}, p, 1.0 / 120.0, std::nullopt);
    EXPECT_TRUE(std::isfinite(s.pose.position.x) && std::isfinite(s.pose.headingDeg) &&
                std::isfinite(s.pose.rollDeg) && std::isfinite(s.throttle));
    EXPECT_EQ(s.throttle, 0.0);
}

TEST(Weapons, BombFallsAsBallisticsSayAndRocketBurnsOut) {
    Weapon b;
    b.position = {0.0, 0.0, 500.0};
    double t = 0.0;
    while (b.position.z > 0.0) {
        stepWeapon(b, t, 1.0 / 120.0);
        t += 1.0 / 120.0;
    }
    // sqrt(2 h / g) = 10.10 s in vacuum; drag of k = 5e-5 /m adds a little.
    EXPECT_GT(t, 10.09);
    EXPECT_LT(t, 10.4);
    Weapon r;
    r.kind = WeaponKind::Rocket;
    r.velocity = {100.0, 0.0, 0.0};
    r.position = {0.0, 0.0, 3000.0};
    for (double tt = 0.0; tt < ROCKET_BURN_S; tt += 1.0 / 120.0)
        stepWeapon(r, tt, 1.0 / 120.0);
    // 100 + 230 * 1.1 = 353 m/s without drag; with k = 2e-4 /m it burns out somewhat slower.
    EXPECT_GT(r.velocity.x, 250.0);
    EXPECT_LT(r.velocity.x, 353.0);
}

TEST(Routes, LoopsRepeatAndOpenRoutesExtendBothWays) {
    Route loop{{{0, 0}, {1000, 0}, {1000, 1000}}, 10.0, true};
    const double period = loop.length() / loop.speed;
    EXPECT_NEAR(loop.length(), 2000.0 + std::sqrt(2.0) * 1000.0, 1e-9);
    EXPECT_NEAR(glm::distance(loop.positionAt(period + 5.0), loop.positionAt(5.0)), 0.0, 1e-6);
    EXPECT_NEAR(glm::distance(loop.positionAt(-5.0), loop.positionAt(period - 5.0)), 0.0, 1e-6);
    EXPECT_NEAR(loop.headingDegAt(5.0), 90.0, 1e-9); // east along the first leg
    Route open{{{0, 0}, {0, 1000}}, 5.0, false};
    EXPECT_NEAR(open.positionAt(-10.0).y, -50.0, 1e-9);
    EXPECT_NEAR(open.positionAt(300.0).y, 1500.0, 1e-9);
}

TEST(World, StartsOnTheCarrierDeckMovingWithIt) {
    Scene s;
    const World& w = *s.world;
    ASSERT_EQ(w.ships().size(), 4u);
    EXPECT_TRUE(w.ships()[0].spec.carrier);
    EXPECT_EQ(w.targetsLeft(), 3);
    EXPECT_TRUE(w.deck().contains(glm::dvec2(w.player().pose.position)));
    EXPECT_NEAR(w.altitudeAboveWaves(), 0.0, 1e-9); // on the deck
    EXPECT_NEAR(glm::length(glm::dvec2(w.player().velocity)), 10.0, 1e-9);
    // Weapons cannot be released on the deck.
    EXPECT_EQ(s.world->fire(WeaponKind::Bomb), 0u);
}

TEST(World, IdleOnTheDeckTheAircraftRidesTheCarrier) {
    Scene s;
    s.fly(10.0, [](const World&) { return FlightControls{}; });
    const World& w = *s.world;
    EXPECT_EQ(w.state(), SortieState::Flying);
    EXPECT_TRUE(w.player().onDeck);
    EXPECT_TRUE(w.deck().contains(glm::dvec2(w.player().pose.position)));
    EXPECT_NEAR(w.altitudeAboveWaves(), 0.0, 0.06);
}

TEST(World, DivingIntoTheSeaDitchesWithASplash) {
    Scene s;
    Autopilot ap;
    // Take off and climb a little, then push the nose down.
    s.fly(25.0, [&](const World& w) { return ap.decide(w).controls; });
    ASSERT_FALSE(s.world->player().onDeck);
    ASSERT_EQ(s.world->state(), SortieState::Flying);
    s.world->takeEvents();
    for (int i = 0; i < 120 * 60 && s.world->state() == SortieState::Flying; ++i)
        s.world->step({-1.0, 0.0, 0.0, 1.0}, 1.0 / 120.0);
    const World& w = *s.world;
    EXPECT_EQ(w.state(), SortieState::Ditched);
    const auto events = s.world->takeEvents();
    const auto it = std::find_if(events.begin(), events.end(),
                                 [](const GameEvent& e) { return e.kind == GameEvent::Kind::Ditched; });
    ASSERT_NE(it, events.end());
    EXPECT_EQ(it->strength, AIRCRAFT_STRENGTH);
    EXPECT_EQ(w.score(), SCORE_DITCHED);
    EXPECT_NEAR(it->position.z, w.seaHeight(glm::dvec2(it->position)), 1e-9);
    // The splash is an explosion in the ocean's ECS, and the sortie is over: steps change nothing.
    s.events.dispatch();
    s.effects->update(w.time(), w.player().pose.position);
    EXPECT_EQ(s.effects->counters().spawned, 1);
    s.effects->update(w.time() + 1.0, w.player().pose.position);
    EXPECT_EQ(s.effects->counters().activeExplosions, 1);
    const glm::dvec3 at = w.player().pose.position;
    s.fly(1.0, [](const World&) { return FlightControls{0.0, 0.0, 0.0, 1.0}; });
    EXPECT_EQ(w.player().pose.position, at);
}

TEST(World, ExplosionStrengthsAreTheReplays) {
    recording::RecordedObject o;
    o.type = "Weapon+Bomb";
    EXPECT_EQ(recording::explosionStrengthFor(o), BOMB_STRENGTH);
    o.type = "Weapon+Rocket";
    EXPECT_EQ(recording::explosionStrengthFor(o), ROCKET_STRENGTH);
    o.type = "Air+FixedWing";
    EXPECT_EQ(recording::explosionStrengthFor(o), AIRCRAFT_STRENGTH);
}

namespace {
struct SortieResult {
    double liftOff = -1.0, firstSunk = -1.0;
    int sunk = 0, bombs = 0, hits = 0, score = 0;
    SortieState state = SortieState::Flying;
    glm::dvec3 finalPosition{0.0};
    std::vector<GameEvent> history;
    int watched = -1; ///< the ship camera's hull at the end (World::nearestAfloatTarget)
};

SortieResult flySortie(double seconds, SessionRecorder* rec = nullptr) {
    Scene s;
    Autopilot ap;
    SortieResult r;
    if (rec)
        for (double t = -60.0; t < 0.0; t += 1.0)
            rec->recordShips(*s.world, t);
    const int n = static_cast<int>(seconds * 120.0);
    for (int i = 0; i < n && s.world->state() == SortieState::Flying; ++i) {
        const AutopilotDecision d = ap.decide(*s.world);
        if (d.releaseBomb)
            ap.released(s.world->fire(WeaponKind::Bomb), s.world->time());
        s.world->step(d.controls, 1.0 / 120.0);
        if (r.liftOff < 0.0 && !s.world->player().onDeck)
            r.liftOff = s.world->time();
        if (i % 4 == 0) {
            s.events.dispatch();
            s.effects->update(s.world->time(), s.world->player().pose.position);
            const auto ev = s.world->takeEvents();
            if (rec)
                rec->record(*s.world, ev);
        }
    }
    if (rec)
        rec->record(*s.world, s.world->takeEvents());
    r.history = s.world->history();
    for (const GameEvent& e : r.history) {
        if (e.kind == GameEvent::Kind::ShipSunk && r.firstSunk < 0.0)
            r.firstSunk = e.time;
        r.sunk += e.kind == GameEvent::Kind::ShipSunk;
        r.bombs += e.kind == GameEvent::Kind::Launch;
        r.hits += e.kind == GameEvent::Kind::ShipHit;
    }
    r.score = s.world->score();
    r.state = s.world->state();
    r.finalPosition = s.world->player().pose.position;
    r.watched = s.world->nearestAfloatTarget(glm::dvec2(r.finalPosition));
    return r;
}
} // namespace

TEST(Autopilot, TakesOffFromTheDeckAndSinksATargetWithABomb) {
    const SortieResult r = flySortie(150.0);
    EXPECT_GT(r.liftOff, 0.0) << "never left the deck";
    EXPECT_LT(r.liftOff, 20.0);
    EXPECT_NE(r.state, SortieState::Ditched);
    EXPECT_GE(r.sunk, 1) << "no target sunk in 150 s";
    EXPECT_GT(r.firstSunk, r.liftOff);
    EXPECT_GE(r.bombs, r.sunk);
    // Score: 200 per hit, 1000 per ship sunk (a bomb hit sinks: 1200 each), no ditching, mission not over.
    EXPECT_EQ(r.score, SCORE_HIT * r.hits + SCORE_SUNK * r.sunk);
    EXPECT_EQ(r.score, 1200 * r.sunk);
}

TEST(Autopilot, TheSortieIsDeterministic) {
    const SortieResult a = flySortie(70.0), b = flySortie(70.0);
    EXPECT_EQ(a.finalPosition, b.finalPosition); // bit for bit
    ASSERT_EQ(a.history.size(), b.history.size());
    for (size_t i = 0; i < a.history.size(); ++i) {
        EXPECT_EQ(a.history[i].time, b.history[i].time);
        EXPECT_EQ(a.history[i].position, b.history[i].position);
    }
}

TEST(SessionRecorder, TheReplaysReadersSeeTheSameImpactsAndShips) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "pacifica_test_game_rec";
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / "sortie.txt.acmi";
    std::filesystem::remove(file);
    SortieResult r;
    RecorderDesc rd;
    {
        SessionRecorder rec(file.string(), rd);
        r = flySortie(150.0, &rec);
        EXPECT_FALSE(std::filesystem::exists(file)); // only FILE.tmp until finish()
        rec.finish();
    }
    ASSERT_TRUE(std::filesystem::exists(file));
    const recording::Recording rec = recording::readRecording(file);
    const recording::EarthFrame frame(rec.referenceLatitude, rec.referenceLongitude);
    const recording::SeaDrivers drivers = recording::seaDrivers(rec, frame);
    EXPECT_EQ(drivers.ships.size(), 4u);
    std::vector<GameEvent> impacts;
    for (const GameEvent& e : r.history)
        if (e.kind == GameEvent::Kind::Impact)
            impacts.push_back(e);
    ASSERT_GE(impacts.size(), 1u);
    ASSERT_EQ(drivers.impacts.size(), impacts.size());
    // The recording's frame is at (originLat, originLon) <-> world point worldOrigin.
    for (size_t i = 0; i < impacts.size(); ++i) {
        const recording::SeaImpact& x = drivers.impacts[i];
        EXPECT_NEAR(x.time, impacts[i].time + rd.timeOffset, 1e-3); // ACMI keeps the frame time to 1 ms
        const glm::dvec2 world = x.position + glm::dvec2(rd.worldOrigin);
        EXPECT_NEAR(glm::distance(world, glm::dvec2(impacts[i].position)), 0.0, 0.05);
        EXPECT_EQ(x.strength, impacts[i].strength);
    }
    const auto destroyed =
        std::count_if(rec.events.begin(), rec.events.end(),
                      [](const recording::RecordedEvent& e) { return e.type == "Destroyed"; });
    EXPECT_EQ(destroyed, r.sunk);
    std::filesystem::remove_all(dir);
}

TEST(SessionRecorder, AnUnfinishedSessionLeavesNoFile) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "pacifica_test_game_rec2";
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / "s.txt.acmi";
    {
        Scene s;
        SessionRecorder rec(file.string());
        rec.record(*s.world, {});
    }
    EXPECT_FALSE(std::filesystem::exists(file));
    EXPECT_FALSE(std::filesystem::exists(file.string() + ".tmp"));
    EXPECT_THROW(SessionRecorder((dir / "no/such/dir/x.acmi").string()), std::runtime_error);
    std::filesystem::remove_all(dir);
}

TEST(Autopilot, SinksAllThreeTargetsAndCompletesTheMissionWithATimeBonus) {
    const SortieResult r = flySortie(600.0);
    ASSERT_EQ(r.state, SortieState::Complete) << r.sunk << " sunk in 600 s";
    EXPECT_EQ(r.sunk, 3);
    EXPECT_EQ(r.watched, 0); // no target afloat: the ship camera watches the carrier
    const auto done = std::find_if(r.history.begin(), r.history.end(), [](const GameEvent& e) {
        return e.kind == GameEvent::Kind::MissionComplete;
    });
    ASSERT_NE(done, r.history.end());
    EXPECT_EQ(r.score, SCORE_HIT * r.hits + SCORE_SUNK * 3 +
                           SCORE_PER_SECOND_UNDER_PAR *
                               static_cast<int>(std::max(0.0, std::floor(MISSION_PAR_S - done->time))));
}

TEST(World, TheShipCameraWatchesTheNearestAfloatTargetThenTheCarrier) {
    Scene s;
    World& w = *s.world;
    for (size_t i = 1; i < w.ships().size(); ++i) { // standing on each target, that one is the nearest
        SCOPED_TRACE(w.ships()[i].spec.name);
        EXPECT_EQ(w.nearestAfloatTarget(glm::dvec2(w.ships()[i].pose.position)), static_cast<int>(i));
    }
    // From the carrier's deck: the nearest of the three by distance.
    const glm::dvec2 deck(w.ships()[0].pose.position);
    size_t nearest = 1;
    for (size_t i = 2; i < w.ships().size(); ++i)
        if (glm::length(glm::dvec2(w.ships()[i].pose.position) - deck) <
            glm::length(glm::dvec2(w.ships()[nearest].pose.position) - deck))
            nearest = i;
    EXPECT_EQ(w.nearestAfloatTarget(deck), static_cast<int>(nearest));
    // With every target sunk it is the carrier (SinksAllThreeTargetsAndCompletesTheMissionWithATimeBonus).
}

TEST(World, ShipsFloatOnTheSeaTheySail) {
    // Heave, pitch and roll are the least-squares plane through the sea's heights under each hull's 3 x 3
    // points (World::placeShips), checked here against the surface model's own heights, and they move.
    Scene s;
    const ocean::SurfaceModel& sea = *s.registry.get<ocean::OceanComponent>(s.ocean).surface;
    std::vector<double> heave, pitch;
    s.fly(12.0, [&](const World& w) {
        heave.push_back(w.ships()[1].pose.position.z);
        pitch.push_back(w.ships()[1].pose.pitchDeg);
        return FlightControls{};
    });
    const World& w = *s.world;
    for (const ShipState& ship : w.ships()) {
        SCOPED_TRACE(ship.spec.name);
        const double deg = std::numbers::pi / 180.0;
        const glm::dvec2 f(std::sin(ship.pose.headingDeg * deg), std::cos(ship.pose.headingDeg * deg));
        const glm::dvec2 right(f.y, -f.x);
        const double beam = (ship.spec.carrier ? 0.1 : 0.07) * ship.spec.length;
        double mean = 0.0, along = 0.0, across = 0.0;
        for (double a : {-0.4, 0.0, 0.4})
            for (double c : {-0.8, 0.0, 0.8}) {
                const glm::dvec2 p =
                    glm::dvec2(ship.pose.position) + a * ship.spec.length * f + c * beam * right;
                const double h = sea.heightAt(p, w.time()); // no explosion yet: the sea alone
                mean += h / 9.0;
                along += h * a / (6.0 * 0.16 * ship.spec.length);
                across += h * c / (6.0 * 0.64 * beam);
            }
        EXPECT_NEAR(ship.pose.position.z, mean, 1e-9);
        EXPECT_NEAR(ship.pose.pitchDeg, std::atan(along) / deg, 1e-9);
        EXPECT_NEAR(ship.pose.rollDeg, -std::atan(across) / deg, 1e-9);
    }
    // The frigate (130 m) heaves and pitches on the default sea: measured ranges 2.2 m, 0.7 deg.
    const auto [hLo, hHi] = std::minmax_element(heave.begin(), heave.end());
    const auto [pLo, pHi] = std::minmax_element(pitch.begin(), pitch.end());
    std::printf("frigate over 12 s: heave %.3f .. %.3f m, pitch %.3f .. %.3f deg\n", *hLo, *hHi, *pLo, *pHi);
    EXPECT_GT(*hHi - *hLo, 0.2);
    EXPECT_GT(*pHi - *pLo, 0.1);
    // The player sits on the carrier's heaving deck.
    EXPECT_NEAR(w.altitudeAboveWaves(), 0.0, 0.06);
}

// The night sortie's lamps ride the carrier: four, near it, scaled by the pre-exposure; the bow searchlight
// sweeps about the heading; the night sea is moonlit, hazy and pre-exposed, and valid.
TEST(Night, TheCarrierLampsRideItAndTheSearchlightSweeps) {
    Scene s;
    const World& w = *s.world;
    const ShipState& carrier = w.ships()[0];
    const std::vector<ocean::SpotLight> lamps = carrierLights(w, 2.0);
    ASSERT_EQ(lamps.size(), 4u);
    for (const ocean::SpotLight& l : lamps) {
        EXPECT_LT(glm::length(glm::dvec2(l.position - carrier.pose.position)), 0.6 * carrier.spec.length);
        EXPECT_GT(l.position.z, carrier.pose.position.z + 10.0);
        EXPECT_NO_THROW(ocean::validateSpotLight(l, 0));
    }
    EXPECT_FLOAT_EQ(lamps[3].intensity, 2.0f * 2.0e4f) << "the searchlight, scaled by the exposure";
    // At t = 0 the sweep is at its centre: the searchlight points along the heading, 2 degrees down.
    const double h = carrier.pose.headingDeg * std::numbers::pi / 180.0;
    EXPECT_NEAR(
        glm::dot(glm::normalize(glm::dvec2(lamps[3].direction)), glm::dvec2(std::sin(h), std::cos(h))), 1.0,
        1e-9);
    EXPECT_NEAR(lamps[3].direction.z, -std::sin(2.0 * std::numbers::pi / 180.0), 1e-9);
    s.fly(10.0,
          [](const World&) { return FlightControls{}; }); // a quarter of the sweep: 30 degrees to starboard
    const ocean::SpotLight later = carrierLights(w, 1.0)[3];
    const double h10 = w.ships()[0].pose.headingDeg * std::numbers::pi / 180.0;
    const double along =
        glm::dot(glm::normalize(glm::dvec2(later.direction)), glm::dvec2(std::sin(h10), std::cos(h10)));
    EXPECT_NEAR(along, std::cos(30.0 * std::numbers::pi / 180.0), 1e-6);

    const ocean::OceanDesc night = nightSea({});
    EXPECT_NO_THROW(ocean::validateLighting(night.lighting));
    EXPECT_EQ(night.lighting.fogDensity, NIGHT_FOG_DENSITY);
    EXPECT_NEAR(night.lighting.sunIntensity / ocean::LightingDesc{}.sunIntensity,
                ocean::moonIlluminanceLux(NIGHT_MOON_PHASE_DEG) / ocean::SUN_ILLUMINANCE_LUX *
                    std::exp2(NIGHT_EXPOSURE_EV),
                1e-6);
    EXPECT_GT(night.lighting.sunDirection.z, 0.4); // the Moon 25 degrees up
}
