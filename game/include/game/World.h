// World: the game's simulation -- the player's aircraft, the carrier it takes off from, target ships sailing
// their routes, bombs and rockets on ballistic paths -- driving the ocean through its public ECS API only:
// ships are entities with ocean::Ship components and trails (AttachShipTrail), impacts are SpawnExplosion
// events, and heights come from ocean::SeaQuery (the batched CPU queries that match what the GPU draws).
// Fixed steps in double precision: the same inputs give the same sortie, bit for bit.
//
// The mission: take off from the carrier, sink the target ships (one bomb within BOMB_LETHAL_M of a hull
// or ROCKET_HITS_TO_SINK rocket hits), don't fly into the sea. Ditching ends the sortie with a splash.
#pragma once

#include "game/FlightModel.h"

#include <engine/Ecs.h>
#include <engine/Pose.h>
#include <ocean/SeaQuery.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace pacifica::game {

enum class WeaponKind { Bomb, Rocket };
const char* toString(WeaponKind kind);

/// Explosion strengths (1 = a nominal 500 kg charge) -- the values `pacifica replay` gives the same object
/// types in a recording (recording::explosionStrengthFor; a unit test keeps them equal).
inline constexpr double BOMB_STRENGTH = 1.0;     ///< Weapon+Bomb
inline constexpr double ROCKET_STRENGTH = 0.05;  ///< Weapon+Rocket
inline constexpr double AIRCRAFT_STRENGTH = 0.8; ///< Air+FixedWing
inline constexpr double BOMB_LETHAL_M = 15.0;    ///< a bomb this close to a hull sinks the ship
inline constexpr int ROCKET_HITS_TO_SINK = 3;

/// The mission's score: points per hit and per ship sunk, a time bonus for finishing the mission (per second
/// under MISSION_PAR_S), a penalty for ditching.
inline constexpr int SCORE_HIT = 200;
inline constexpr int SCORE_SUNK = 1000;
inline constexpr int SCORE_PER_SECOND_UNDER_PAR = 10;
inline constexpr double MISSION_PAR_S = 300.0;
inline constexpr int SCORE_DITCHED = -500;

struct Weapon {
    uint64_t id = 0;
    WeaponKind kind = WeaponKind::Bomb;
    glm::dvec3 position{0.0}, velocity{0.0};
    double launchTime = 0.0;
    bool declared = false; ///< the recorder has written its properties
};

/// One step of a free weapon: gravity, quadratic drag a = -k |v| v (k = rho Cd A / 2m: Mk-82 ~5e-5 /m,
/// a 70 mm rocket ~2e-4 /m) and, for a rocket, motor thrust along its velocity for ROCKET_BURN_S.
void stepWeapon(Weapon& w, double time, double dt);
inline constexpr double ROCKET_BURN_S = 1.1;
inline constexpr double ROCKET_THRUST = 230.0; ///< m/s^2 during the burn

/// A closed (loop) or open polyline sailed at constant speed from t = 0 (t < 0 runs the route backwards in
/// time, so a ship already has a wake at the start). A pure function of t.
struct Route {
    std::vector<glm::dvec2> waypoints; ///< world metres, >= 2
    double speed = 10.0;               ///< m/s
    bool loop = true;
    glm::dvec2 positionAt(double t) const;
    double headingDegAt(double t) const; ///< compass heading of travel
    double length() const;
};

struct ShipSpec {
    std::string name;
    double length = 120.0; ///< metres
    bool carrier = false;
    bool target = true;
    Route route;
};

inline constexpr double SINK_S = 25.0; ///< a sunk ship is drawn settling for this long

struct ShipState {
    ShipSpec spec;
    ecs::Entity entity;
    uint64_t id = 0; ///< recording id
    Pose pose;       ///< world pose (z = sinking depth below the sea when sunk)
    int hits = 0;
    std::optional<double> sunkAt; ///< time it was sunk (it stops, settles and is gone after SINK_S)
    glm::dvec2 velocity{0.0};
    /// Afloat, or still settling (drawn) at time t.
    bool visibleAt(double t) const { return !sunkAt || t - *sunkAt < SINK_S; }
};

enum class SortieState { Flying, Ditched, Complete };
const char* toString(SortieState s);

/// What happened this step, for the HUD, the recorder and the tests.
struct GameEvent {
    enum class Kind { Launch, Impact, WeaponLost, ShipHit, ShipSunk, Ditched, MissionComplete };
    Kind kind = Kind::Launch;
    double time = 0.0;
    glm::dvec3 position{0.0};
    uint64_t weapon = 0; ///< Launch, Impact: the weapon's id
    WeaponKind weaponKind = WeaponKind::Bomb;
    int ship = -1;         ///< ShipHit, ShipSunk: index into ships(); Impact: the ship hit or -1
    double strength = 0.0; ///< Impact, Ditched: the explosion's strength
};

const char* toString(GameEvent::Kind kind);

struct WorldDesc {
    glm::dvec3 origin{1.0e6, -2.0e6, 0.0}; ///< the carrier's start (far from 0: camera-relative rendering)
    double carrierHeadingDeg = 80.0;
    double carrierSpeed = 10.0;
    int bombs = 6, rockets = 19;
    AircraftParams aircraft;
};

class World {
public:
    /// ocean: the entity holding the OceanComponent (for height queries). Creates the ship entities and
    /// enqueues their trails.
    World(ecs::Registry& registry, ecs::EventQueue& events, ecs::Entity ocean, const WorldDesc& desc = {});

    /// Puts the ships where their routes have them at time t (before the first step: the wake's history)
    /// and floats them on the sea at t: heave, pitch and roll of the plane fitted through the sea's heights
    /// under a 3 x 3 grid of each hull's points (ocean/Buoyancy.h: quasi-static, the hull's length and beam
    /// average the short waves out). floatOnSea false: positions only (the wakes' history before the first
    /// frame, where a pose is not drawn and the FFT sea would be transformed for every time).
    void placeShips(double t, bool floatOnSea = true);
    /// One fixed step of dt seconds with the player's controls. Does nothing once ditched.
    void step(const FlightControls& controls, double dt);
    /// Releases a weapon now if one is left and the last release is old enough; returns its id or 0.
    uint64_t fire(WeaponKind kind);

    double time() const { return mTime; }
    SortieState state() const { return mState; }
    const AircraftState& player() const { return mPlayer; }
    const AircraftParams& params() const { return mDesc.aircraft; }
    const std::vector<ShipState>& ships() const { return mShips; }
    const std::vector<Weapon>& weapons() const { return mWeapons; }
    int bombsLeft() const { return mBombs; }
    int rocketsLeft() const { return mRockets; }
    int targetsLeft() const;
    /// The afloat target ship nearest to xy (index into ships()), else the carrier (0): the ship camera's.
    int nearestAfloatTarget(const glm::dvec2& xy) const;
    /// The score so far (SCORE_* above), from the events since the start.
    int score() const;
    /// The carrier's deck now (for the flight model).
    Deck deck() const;
    /// Sea height under a point at the current time (ocean + effects), metres; NaN for a non-finite point.
    double seaHeight(const glm::dvec2& xy) const;
    /// seaHeight() of every point in one batched query (heights as long as points).
    void seaHeights(std::span<const glm::dvec2> points, std::span<double> heights) const;
    /// Height of the player's wheels above the waves (or the deck) under it.
    double altitudeAboveWaves() const;
    /// Events since the last call.
    std::vector<GameEvent> takeEvents();
    /// Every event since the start (tests, summaries).
    const std::vector<GameEvent>& history() const { return mHistory; }

private:
    void emit(GameEvent e);
    void floatShips(double t);
    void checkDitching(double seaUnderPlayer);
    void seaHeightsAt(double t, std::span<const glm::dvec2> points, std::span<double> heights,
                      bool wakes = true) const;
    void impact(Weapon& w, int shipHit, double seaUnder);
    int shipHitBy(const glm::dvec3& p, double reach, double topMargin = 0.0) const;
    ecs::Registry& mRegistry;
    ecs::EventQueue& mEvents;
    ecs::Entity mOcean;
    WorldDesc mDesc;
    double mTime = 0.0;
    SortieState mState = SortieState::Flying;
    AircraftState mPlayer;
    std::vector<ShipState> mShips;
    std::vector<Weapon> mWeapons;
    /// The sea's batched queries (ocean/SeaQuery.h), moved to the time asked for: the FFT sea samples its
    /// tiles once per time. Mutable: a query keeps counters and the sampled time, not the world's state.
    mutable ocean::SeaQuery mSea;
    mutable std::vector<glm::dvec2> mPoints; // the hull points and weapon positions of a step (reused)
    mutable std::vector<double> mHeights;
    int mBombs = 0, mRockets = 0;
    double mLastRelease = -1e9;
    uint64_t mNextWeaponId = 0x1000;
    std::vector<GameEvent> mPending, mHistory;
};

} // namespace pacifica::game
