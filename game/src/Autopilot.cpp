// Autopilot: a scripted pilot using only the player's controls (Autopilot.h).
#include "game/Autopilot.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pacifica::game {

namespace {
constexpr double DEG = std::numbers::pi / 180.0;

double bearingDeg(const glm::dvec2& from, const glm::dvec2& to) {
    const glm::dvec2 d = to - from;
    return std::fmod(std::atan2(d.x, d.y) / DEG + 360.0, 360.0);
}
} // namespace

glm::dvec2 Autopilot::predictImpact(const World& world, double& fallTime) {
    const AircraftState& a = world.player();
    const glm::dmat3 axes = attitudeMatrix(a.pose.headingDeg, a.pose.pitchDeg, a.pose.rollDeg);
    // As World::fire() releases a bomb.
    Weapon w;
    w.kind = WeaponKind::Bomb;
    w.position = a.pose.position - 1.5 * axes[2];
    w.velocity = a.velocity - 1.0 * axes[2];
    const double dt = 1.0 / 60.0;
    double t = 0.0;
    while (w.position.z > 0.0 && t < 60.0) {
        stepWeapon(w, t, dt);
        t += dt;
    }
    fallTime = t;
    return glm::dvec2(w.position);
}

namespace {

/// Heading, altitude and speed hold: bank toward the heading, stick from the climb-rate error plus the extra
/// lift a bank needs, throttle from the speed error.
void holdCourse(const AircraftState& a, double cruiseSpeed, double headingDeg, double altitude,
                double maxBankDeg, FlightControls& c) {
    const double err = std::remainder(headingDeg - a.pose.headingDeg, 360.0);
    const double bank = std::clamp(2.0 * err, -maxBankDeg, maxBankDeg);
    c.roll = std::clamp(0.05 * (bank - a.pose.rollDeg), -1.0, 1.0);
    const double vzWanted = std::clamp(0.25 * (altitude - a.pose.position.z), -20.0, 25.0);
    const double turnLift = 1.0 / std::max(std::cos(a.pose.rollDeg * DEG), 0.3) - 1.0;
    c.pitch = std::clamp(0.03 * (vzWanted - a.velocity.z) + 0.3 * turnLift, -1.0, 1.0);
    c.throttle = std::clamp(0.5 + 0.05 * (cruiseSpeed - a.airspeed()), 0.0, 1.0);
}

/// Release when the predicted impact falls on the ship's predicted hull (plus half the lethal radius), in
/// the ship's own axes, level enough, high enough and a second after the last release.
bool onTheHull(const ShipState& ship, const glm::dvec2& impact, const glm::dvec2& aim,
               const AircraftState& a) {
    const glm::dvec2 f(std::sin(ship.pose.headingDeg * DEG), std::cos(ship.pose.headingDeg * DEG));
    const glm::dvec2 rel = impact - aim;
    const double along = glm::dot(rel, f), across = glm::dot(rel, glm::dvec2(f.y, -f.x));
    const double reach = 0.5 * BOMB_LETHAL_M;
    return std::abs(along) <= 0.5 * ship.spec.length + reach &&
           std::abs(across) <= 0.07 * ship.spec.length + reach && std::abs(a.pose.rollDeg) < 12.0 &&
           a.pose.position.z > 150.0;
}

} // namespace

/// The target: kept until it is sunk, then the nearest afloat one (-1: none left).
int Autopilot::chooseTarget(const World& world) {
    const auto& ships = world.ships();
    if (mTarget >= 0 && (mTarget >= static_cast<int>(ships.size()) || ships[mTarget].sunkAt))
        mTarget = -1;
    if (mTarget >= 0)
        return mTarget;
    const glm::dvec2 xy(world.player().pose.position);
    double best = 1e300;
    for (size_t i = 0; i < ships.size(); ++i) {
        if (!ships[i].spec.target || ships[i].sunkAt)
            continue;
        const double dist = glm::distance(xy, glm::dvec2(ships[i].pose.position));
        if (dist < best) {
            best = dist;
            mTarget = static_cast<int>(i);
        }
    }
    return mTarget;
}

AutopilotDecision Autopilot::decide(const World& world) {
    AutopilotDecision d;
    const AircraftState& a = world.player();
    const double z = a.pose.position.z;
    const glm::dvec2 xy(a.pose.position);
    auto fly = [&](double headingDeg, double altitude, double maxBankDeg) {
        holdCourse(a, cruiseSpeed, headingDeg, altitude, maxBankDeg, d.controls);
    };
    if (a.onDeck) {
        d.phase = "takeoff";
        d.controls.throttle = 1.0;
        if (a.airspeed() >= world.params().stallSpeed())
            d.controls.pitch = std::clamp(0.15 * (12.0 - a.pose.pitchDeg), -1.0, 1.0);
        return d;
    }
    // A bomb still falling: hold the heading until it lands.
    const auto& weapons = world.weapons();
    if (std::any_of(weapons.begin(), weapons.end(), [&](const Weapon& w) { return w.id == mBombInFlight; })) {
        d.phase = "egress";
        fly(a.pose.headingDeg, cruiseAltitude, 10.0);
        return d;
    }
    mBombInFlight = 0;
    d.target = chooseTarget(world);
    if (d.target < 0 || world.bombsLeft() == 0) {
        d.phase = "done";
        fly(a.pose.headingDeg + 20.0, cruiseAltitude, 30.0); // a gentle orbit
        return d;
    }
    const ShipState& ship = world.ships()[d.target];
    double fall = 0.0;
    const glm::dvec2 impact = predictImpact(world, fall);
    const glm::dvec2 aim = glm::dvec2(ship.pose.position) + ship.velocity * fall;
    d.predictedMissM = glm::distance(aim, impact);
    const double dist = glm::distance(xy, aim);
    const double bearing = bearingDeg(xy, aim);
    // Too close to turn onto the aim point and settle before the release (a 55-degree turn at 150 m/s has
    // a ~1.7 km radius, the bomb falls ~1.3 km ahead): fly on straight until there is room, then turn back.
    if (mExtending && dist > 6500.0)
        mExtending = false;
    else if (!mExtending && std::abs(std::remainder(bearing - a.pose.headingDeg, 360.0)) > 30.0 &&
             dist < 5000.0)
        mExtending = true;
    if (mExtending) {
        d.phase = "extend";
        fly(a.pose.headingDeg, cruiseAltitude, 10.0);
        return d;
    }
    d.phase = z < cruiseAltitude - 100.0 && dist > 3000.0 ? "climb" : "run-in";
    fly(bearing, cruiseAltitude, z < 120.0 ? 15.0 : 55.0);
    if (onTheHull(ship, impact, aim, a) && world.time() - mLastRelease > 1.0) {
        d.releaseBomb = true;
        d.phase = "release";
    }
    return d;
}

} // namespace pacifica::game
