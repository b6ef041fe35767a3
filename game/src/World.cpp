// World: the game's fixed-step simulation (World.h).
#include "game/World.h"

#include <ocean/Buoyancy.h>
#include <ocean/Effects.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace pacifica::game {

namespace {
constexpr double DEG = std::numbers::pi / 180.0;
constexpr double WEAPON_MAX_LIFE_S = 120.0;

glm::dvec2 compass(double headingDeg) {
    return {std::sin(headingDeg * DEG), std::cos(headingDeg * DEG)};
}

/// Freeboard and the top of anything on the deck, as fractions of the length (the game's ship meshes:
/// hull top 0.05 L, carrier flight deck 0.065 L, a warship's superstructure to 0.12 L).
double hullTop(const ShipSpec& s) {
    return (s.carrier ? 0.065 : 0.12) * s.length;
}
double halfBeam(const ShipSpec& s) {
    return (s.carrier ? 0.1 : 0.07) * s.length;
}
} // namespace

const char* toString(WeaponKind kind) {
    return kind == WeaponKind::Bomb ? "bomb" : "rocket";
}

const char* toString(SortieState s) {
    switch (s) {
    case SortieState::Flying:
        return "flying";
    case SortieState::Ditched:
        return "ditched";
    case SortieState::Complete:
        return "complete";
    }
    return "?";
}

const char* toString(GameEvent::Kind kind) {
    switch (kind) {
    case GameEvent::Kind::Launch:
        return "launch";
    case GameEvent::Kind::Impact:
        return "impact";
    case GameEvent::Kind::WeaponLost:
        return "weapon_lost";
    case GameEvent::Kind::ShipHit:
        return "ship_hit";
    case GameEvent::Kind::ShipSunk:
        return "ship_sunk";
    case GameEvent::Kind::Ditched:
        return "ditched";
    case GameEvent::Kind::MissionComplete:
        return "mission_complete";
    }
    return "?";
}

void stepWeapon(Weapon& w, double time, double dt) {
    const double k = w.kind == WeaponKind::Bomb ? 5e-5 : 2e-4;
    const double speed = glm::length(w.velocity);
    glm::dvec3 a(0.0, 0.0, -GRAVITY);
    a -= k * speed * w.velocity;
    if (w.kind == WeaponKind::Rocket && time - w.launchTime < ROCKET_BURN_S && speed > 1e-6)
        a += ROCKET_THRUST * w.velocity / speed;
    w.velocity += a * dt;
    w.position += w.velocity * dt;
}

double Route::length() const {
    double l = 0.0;
    for (size_t i = 0; i + 1 < waypoints.size(); ++i)
        l += glm::distance(waypoints[i], waypoints[i + 1]);
    if (loop && waypoints.size() > 2)
        l += glm::distance(waypoints.back(), waypoints.front());
    return l;
}

glm::dvec2 Route::positionAt(double t) const {
    if (waypoints.size() < 2)
        return waypoints.empty() ? glm::dvec2(0.0) : waypoints.front();
    const double total = length();
    double s = speed * t;
    const size_t n = waypoints.size();
    const size_t segments = loop && n > 2 ? n : n - 1;
    if (loop && n > 2) {
        s = std::fmod(s, total);
        if (s < 0.0)
            s += total;
    } else if (s < 0.0) { // an open route extends backwards along its first leg
        return waypoints[0] + s * glm::normalize(waypoints[1] - waypoints[0]);
    }
    for (size_t i = 0; i < segments; ++i) {
        const glm::dvec2 a = waypoints[i], b = waypoints[(i + 1) % n];
        const double l = glm::distance(a, b);
        if (s <= l || i + 1 == segments) {
            if (l <= 0.0)
                return a;
            if (!loop && i + 1 == segments && s > l) // past the end: carry on along the last leg
                return b + (s - l) * (b - a) / l;
            return a + (b - a) * (s / l);
        }
        s -= l;
    }
    return waypoints.back();
}

double Route::headingDegAt(double t) const {
    const glm::dvec2 d = positionAt(t + 0.5) - positionAt(t - 0.5);
    if (glm::length(d) < 1e-9)
        return 0.0;
    return std::fmod(std::atan2(d.x, d.y) / DEG + 360.0, 360.0);
}

World::World(ecs::Registry& registry, ecs::EventQueue& events, ecs::Entity ocean, const WorldDesc& desc)
    : mRegistry(registry), mEvents(events), mOcean(ocean), mDesc(desc), mBombs(desc.bombs),
      mRockets(desc.rockets) {
    const auto* sea = registry.tryGet<ocean::OceanComponent>(ocean);
    if (!sea)
        throw std::invalid_argument("World: entity " + ecs::toString(ocean) + " has no OceanComponent");
    // The FFT sea transformed every 0.1 s of game time and extrapolated between (up to 3 cm, RMS 9 mm at the
    // interval's end, against ~10 cm between any CPU query and the drawn sea: docs/ACCURACY.md): ~1 ms a
    // step.
    if (const ocean::Status s =
            mSea.init(*sea, {.fields = ocean::SeaField::Height, .fftResampleInterval = 0.1});
        !s)
        throw std::invalid_argument("World: " + s.message);
    const glm::dvec2 o(desc.origin);
    const glm::dvec2 ahead = compass(desc.carrierHeadingDeg);
    const glm::dvec2 right(ahead.y, -ahead.x);
    auto at = [&](double fwd, double side) { return o + fwd * ahead + side * right; };
    std::vector<ShipSpec> specs;
    specs.push_back({"Carrier", 330.0, true, false, {{o, at(200e3, 0.0)}, desc.carrierSpeed, false}});
    specs.push_back({"Frigate Alpha",
                     130.0,
                     false,
                     true,
                     {{at(5000, -800), at(6500, 600), at(8200, -300), at(6000, -1800)}, 9.0, true}});
    specs.push_back({"Frigate Bravo",
                     120.0,
                     false,
                     true,
                     {{at(9000, 1500), at(11000, 2500), at(12000, 500), at(9500, -200)}, 7.0, true}});
    specs.push_back({"Tanker Charlie", 180.0, false, true, {{at(4000, 3500), at(12000, 4500)}, 5.0, false}});
    uint64_t id = 0x200;
    for (ShipSpec& s : specs) {
        ShipState st;
        st.spec = std::move(s);
        st.id = id++;
        st.entity = mRegistry.create();
        mRegistry.emplace<ocean::Ship>(st.entity, ocean::Ship{st.spec.route.positionAt(0.0), st.spec.length});
        mEvents.enqueue(ocean::AttachShipTrail{st.entity, ocean::WakeParams{}});
        mShips.push_back(std::move(st));
    }
    placeShips(0.0);
    // The player: on the carrier's deck, 35% of its length aft of the centre, pointing along it.
    const ShipState& carrier = mShips[0];
    mPlayer.pose.headingDeg = carrier.pose.headingDeg;
    const glm::dvec2 start = glm::dvec2(carrier.pose.position) - 0.35 * carrier.spec.length * ahead;
    mPlayer.pose.position =
        glm::dvec3(start, carrier.pose.position.z + hullTop(carrier.spec) + desc.aircraft.gearHeight);
    mPlayer.velocity = glm::dvec3(carrier.velocity, 0.0);
    mPlayer.onDeck = true;
}

void World::placeShips(double t, bool floatOnSea) {
    for (ShipState& s : mShips) {
        const double tt = s.sunkAt ? *s.sunkAt : t;
        const glm::dvec2 p = s.spec.route.positionAt(tt);
        s.pose.position = glm::dvec3(p, 0.0);
        s.pose.headingDeg = s.spec.route.headingDegAt(tt);
        s.pose.pitchDeg = s.pose.rollDeg = 0.0;
        s.velocity = s.sunkAt ? glm::dvec2(0.0) : s.spec.route.speed * compass(s.pose.headingDeg);
        if (s.sunkAt) { // settles by a tenth of its length, listing, then is gone
            const double f = std::clamp((t - *s.sunkAt) / SINK_S, 0.0, 1.0);
            s.pose.position.z = -0.12 * s.spec.length * f;
            s.pose.rollDeg = 18.0 * f;
        }
        mRegistry.get<ocean::Ship>(s.entity).position = p;
    }
    if (floatOnSea)
        floatShips(t);
}

void World::floatShips(double t) {
    // Every afloat hull's points in one batched query, on the sea and its explosions: the wakes are the
    // ships' own waves (part of a hull's trim, not a sea that pitches it), and the costliest field to sample.
    using ocean::HULL_POINTS;
    mPoints.clear();
    for (const ShipState& s : mShips) {
        if (s.sunkAt)
            continue;
        mPoints.resize(mPoints.size() + HULL_POINTS);
        ocean::hullPoints(glm::dvec2(s.pose.position), s.pose.headingDeg, s.spec.length, halfBeam(s.spec),
                          std::span<glm::dvec2, HULL_POINTS>(mPoints.end() - HULL_POINTS, HULL_POINTS));
    }
    mHeights.resize(mPoints.size());
    seaHeightsAt(t, mPoints, mHeights, false);
    size_t k = 0;
    for (ShipState& s : mShips) {
        if (s.sunkAt)
            continue;
        const ocean::HullPose p =
            ocean::floatHull(std::span<const double, HULL_POINTS>(mHeights.data() + k, HULL_POINTS),
                             s.spec.length, halfBeam(s.spec));
        k += HULL_POINTS;
        s.pose.position.z = p.heave;
        s.pose.pitchDeg = p.pitchDeg;
        s.pose.rollDeg = p.rollDeg;
    }
}

Deck World::deck() const {
    const ShipState& c = mShips[0];
    Deck d;
    d.centre = glm::dvec2(c.pose.position);
    d.forward = compass(c.pose.headingDeg);
    d.halfLength = 0.49 * c.spec.length;
    d.halfBeam = halfBeam(c.spec);
    d.top = hullTop(c.spec) + c.pose.position.z;
    d.velocity = c.velocity;
    return d;
}

void World::seaHeightsAt(double t, std::span<const glm::dvec2> points, std::span<double> heights,
                         bool wakes) const {
    // The effects as the registry holds them now (a fresh view each call: their storage moves when effects
    // come and go); the FFT sea is sampled again only when t changes.
    const ocean::RegistryEffects effects(mRegistry);
    ocean::EffectsView view = effects.view();
    if (!wakes)
        view.wakes = {};
    ocean::Status s = mSea.update(t, view);
    if (s)
        s = mSea.heights(points, heights);
    (void)mSea.update(t,
                      {}); // let the registry's effects go (their storage moves); the same t: no resampling
    // A non-finite point's height is NaN (reported, not fatal: a host game is never aborted over bad data).
    if (!s && s.code != ocean::ErrorCode::InvalidArgument)
        throw std::runtime_error("World: sea query failed: " + s.message);
}

double World::seaHeight(const glm::dvec2& xy) const {
    double h = 0.0;
    seaHeightsAt(mTime, {&xy, 1}, {&h, 1});
    return h;
}

void World::seaHeights(std::span<const glm::dvec2> points, std::span<double> heights) const {
    seaHeightsAt(mTime, points, heights);
}

double World::altitudeAboveWaves() const {
    const glm::dvec2 xy(mPlayer.pose.position);
    double ground = seaHeight(xy);
    const Deck d = deck();
    if (d.contains(xy))
        ground = std::max(ground, d.top);
    return mPlayer.pose.position.z - mDesc.aircraft.gearHeight - ground;
}

int World::targetsLeft() const {
    int n = 0;
    for (const ShipState& s : mShips)
        n += s.spec.target && !s.sunkAt;
    return n;
}

int World::nearestAfloatTarget(const glm::dvec2& xy) const {
    int best = 0;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < mShips.size(); ++i) {
        const ShipState& s = mShips[i];
        const double d = glm::length(glm::dvec2(s.pose.position) - xy);
        if (s.spec.target && !s.sunkAt && d < bestDistance) {
            best = static_cast<int>(i);
            bestDistance = d;
        }
    }
    return best;
}

int World::score() const {
    int points = 0;
    for (const GameEvent& e : mHistory) {
        if (e.kind == GameEvent::Kind::ShipHit)
            points += SCORE_HIT;
        else if (e.kind == GameEvent::Kind::ShipSunk)
            points += SCORE_SUNK;
        else if (e.kind == GameEvent::Kind::Ditched)
            points += SCORE_DITCHED;
        else if (e.kind == GameEvent::Kind::MissionComplete)
            points += SCORE_PER_SECOND_UNDER_PAR *
                      static_cast<int>(std::max(0.0, std::floor(MISSION_PAR_S - e.time)));
    }
    return points;
}

int World::shipHitBy(const glm::dvec3& p, double reach, double topMargin) const {
    for (size_t i = 0; i < mShips.size(); ++i) {
        const ShipState& s = mShips[i];
        if (s.sunkAt)
            continue;
        const glm::dvec2 d = glm::dvec2(p) - glm::dvec2(s.pose.position);
        const glm::dvec2 f = compass(s.pose.headingDeg);
        const double along = glm::dot(d, f), across = glm::dot(d, glm::dvec2(f.y, -f.x));
        if (std::abs(along) <= 0.5 * s.spec.length + reach && std::abs(across) <= halfBeam(s.spec) + reach &&
            p.z <= s.pose.position.z + hullTop(s.spec) + reach - topMargin)
            return static_cast<int>(i);
    }
    return -1;
}

void World::emit(GameEvent e) {
    mPending.push_back(e);
    mHistory.push_back(e);
}

std::vector<GameEvent> World::takeEvents() {
    std::vector<GameEvent> out;
    out.swap(mPending);
    return out;
}

uint64_t World::fire(WeaponKind kind) {
    int& left = kind == WeaponKind::Bomb ? mBombs : mRockets;
    const double interval = kind == WeaponKind::Bomb ? 0.4 : 0.15;
    if (mState != SortieState::Flying || left <= 0 || mPlayer.onDeck || mTime - mLastRelease < interval)
        return 0;
    --left;
    mLastRelease = mTime;
    const glm::dmat3 axes =
        attitudeMatrix(mPlayer.pose.headingDeg, mPlayer.pose.pitchDeg, mPlayer.pose.rollDeg);
    Weapon w;
    w.id = mNextWeaponId++;
    w.kind = kind;
    w.launchTime = mTime;
    w.position = mPlayer.pose.position - 1.5 * axes[2];
    w.velocity = mPlayer.velocity + (kind == WeaponKind::Rocket ? 20.0 : 0.0) * axes[0] - 1.0 * axes[2];
    mWeapons.push_back(w);
    emit({GameEvent::Kind::Launch, mTime, w.position, w.id, kind});
    return w.id;
}

void World::impact(Weapon& w, int shipHit, double seaUnder) {
    const double strength = w.kind == WeaponKind::Bomb ? BOMB_STRENGTH : ROCKET_STRENGTH;
    if (shipHit < 0 && w.kind == WeaponKind::Bomb) // a near miss within the lethal radius counts
        shipHit = shipHitBy(glm::dvec3(glm::dvec2(w.position), 0.0), BOMB_LETHAL_M);
    const glm::dvec3 at(glm::dvec2(w.position), seaUnder);
    mEvents.enqueue(ocean::SpawnExplosion{glm::dvec2(at), mTime, strength});
    GameEvent e{GameEvent::Kind::Impact, mTime, at, w.id, w.kind, shipHit, strength};
    emit(e);
    if (shipHit >= 0 && !mShips[shipHit].spec.carrier) {
        ShipState& s = mShips[shipHit];
        ++s.hits;
        emit({GameEvent::Kind::ShipHit, mTime, at, w.id, w.kind, shipHit});
        if (w.kind == WeaponKind::Bomb || s.hits >= ROCKET_HITS_TO_SINK) {
            s.sunkAt = mTime;
            emit({GameEvent::Kind::ShipSunk, mTime, s.pose.position, w.id, w.kind, shipHit});
            if (targetsLeft() == 0 && mState == SortieState::Flying) {
                mState = SortieState::Complete;
                emit({GameEvent::Kind::MissionComplete, mTime, at});
            }
        }
    }
}

void World::step(const FlightControls& controls, double dt) {
    mTime += dt;
    placeShips(mTime);
    const bool flying = mState != SortieState::Ditched;
    if (flying)
        stepAircraft(mPlayer, controls, mDesc.aircraft, dt, deck());
    for (Weapon& w : mWeapons)
        stepWeapon(w, mTime, dt);
    // The sea under the player's wheels and under every weapon in one batched query (one effects snapshot
    // a step besides the hulls'), then the ditching and the hits in order (a ship sunk by one weapon is not
    // hit by the next).
    mPoints.clear();
    mPoints.push_back(glm::dvec2(mPlayer.pose.position));
    for (const Weapon& w : mWeapons)
        mPoints.push_back(glm::dvec2(w.position));
    mHeights.resize(mPoints.size());
    seaHeights(mPoints, mHeights);
    if (flying)
        checkDitching(mHeights[0]);
    for (size_t i = 0; i < mWeapons.size(); ++i) {
        Weapon& w = mWeapons[i];
        const int ship = shipHitBy(w.position, 0.0);
        if (ship >= 0 || w.position.z <= mHeights[i + 1]) {
            impact(w, ship, mHeights[i + 1]);
            w.id = 0; // spent
        } else if (mTime - w.launchTime > WEAPON_MAX_LIFE_S) {
            emit({GameEvent::Kind::WeaponLost, mTime, w.position, w.id, w.kind});
            w.id = 0;
        }
    }
    std::erase_if(mWeapons, [](const Weapon& w) { return w.id == 0; });
}

void World::checkDitching(double seaUnderPlayer) {
    const glm::dvec2 xy(mPlayer.pose.position);
    const bool inSea =
        !mPlayer.onDeck && mPlayer.pose.position.z - 0.5 * mDesc.aircraft.gearHeight <= seaUnderPlayer;
    // Flown into a hull (the wheels more than a metre below its top: a touch-down on the deck is fine).
    const int crashed =
        mPlayer.onDeck
            ? -1
            : shipHitBy(mPlayer.pose.position - glm::dvec3(0, 0, mDesc.aircraft.gearHeight), 0.0, 1.0);
    if (!inSea && crashed < 0)
        return;
    mState = SortieState::Ditched;
    const glm::dvec3 at(xy, seaUnderPlayer);
    mEvents.enqueue(ocean::SpawnExplosion{xy, mTime, AIRCRAFT_STRENGTH});
    mPlayer.pose.position.z = at.z;
    mPlayer.velocity = glm::dvec3(0.0);
    emit({GameEvent::Kind::Ditched, mTime, at, 0, WeaponKind::Bomb, crashed, AIRCRAFT_STRENGTH});
}

} // namespace pacifica::game
