// FlightModel: a small rigid-attitude aircraft model for the game -- thrust, lift with stall, drag and
// gravity on a point mass, with the attitude flown by rate commands (arcade handling, not a 6-DOF model).
//
//   lift  L = q S CL(alpha),  CL = CL0 + CLa alpha up to the stall angle, falling to ~0.45 CLmax past it
//   drag  D = q S (CD0 + k CL^2 + CDstall)     (drag polar: Anderson, "Introduction to Flight", 6.1)
//   q = 1/2 rho V^2, rho = 1.225 exp(-z / 8500 m)  (isothermal atmosphere)
// Lift acts perpendicular to the velocity in the plane of the velocity and the body's up axis; thrust along
// the body's forward axis; the heading follows the velocity's track (sideslip damping); past the stall the
// nose drops toward the flight path. A deck (the carrier's) carries the aircraft with rolling friction until
// the lift lifts it off. Everything is double precision and a pure function of (state, controls, dt).
#pragma once

#include <engine/Pose.h>

#include <glm/glm.hpp>

#include <optional>

namespace pacifica::game {

inline constexpr double GRAVITY = 9.81; ///< m/s^2

struct AircraftParams {
    double mass = 9000.0;        ///< kg
    double wingArea = 38.0;      ///< m^2
    double maxThrust = 90000.0;  ///< N at full throttle (sea level): thrust/weight ~1
    double cl0 = 0.2;            ///< lift coefficient at zero angle of attack
    double clAlpha = 4.6;        ///< per radian
    double stallAlphaDeg = 15.0; ///< critical angle of attack
    double cd0 = 0.022;          ///< zero-lift drag coefficient
    double inducedK = 0.075;     ///< induced drag factor k = 1 / (pi e AR)
    double maxPitchRateDeg = 35; ///< deg/s at full stick (above ~60 m/s)
    double maxRollRateDeg = 110; ///< deg/s
    double maxYawRateDeg = 8;    ///< deg/s of rudder
    double throttleRate = 0.6;   ///< throttle lag: fraction per second
    double gearHeight = 1.8;     ///< m: body origin above the wheels (deck) / lowest point (ditching)
    double rollingFriction = 0.03;

    double clMax() const;
    /// Stall speed at sea level in level flight, m/s: sqrt(2 m g / (rho0 S CLmax)).
    double stallSpeed() const;
};

/// Stick and throttle: pitch > 0 pulls the nose up, roll > 0 rolls right, yaw > 0 yaws right; each in
/// [-1, 1]; throttle in [0, 1]. Non-finite inputs count as 0.
struct FlightControls {
    double pitch = 0.0, roll = 0.0, yaw = 0.0, throttle = 0.0;
};

/// A horizontal deck moving with velocity `velocity` (the carrier): top at z = top, the rectangle
/// |along| <= halfLength, |across| <= halfBeam around centre, along the unit vector `forward`.
struct Deck {
    glm::dvec2 centre{0.0}, forward{0.0, 1.0};
    double halfLength = 150.0, halfBeam = 20.0, top = 20.0;
    glm::dvec2 velocity{0.0};
    bool contains(const glm::dvec2& xy) const;
};

struct AircraftState {
    Pose pose;                ///< world position (double) and attitude
    glm::dvec3 velocity{0.0}; ///< world m/s
    double throttle = 0.0;    ///< actual throttle (lags the command)
    bool onDeck = false;      ///< wheels on the deck this step
    // Last step's aerodynamics, for the HUD and tests.
    double alphaDeg = 0.0;
    bool stalled = false;
    double loadFactor = 1.0; ///< lift / weight
    double airspeed() const { return glm::length(velocity); }
};

/// CL(alpha) (radians): linear to the stall, then falling to 0.45 CLmax at stall + 10 degrees and beyond.
double liftCoefficient(const AircraftParams& p, double alphaRad);
/// Air density at altitude z (m), kg/m^3.
double airDensity(double z);

/// Advances the aircraft by dt seconds (dt <= 0.05 for stability; the game steps at 1/120 s).
void stepAircraft(AircraftState& s, const FlightControls& c, const AircraftParams& p, double dt,
                  const std::optional<Deck>& deck);

} // namespace pacifica::game
