// FlightModel: forces on a point mass, attitude from body rates (FlightModel.h).
#include "game/FlightModel.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pacifica::game {

namespace {
constexpr double DEG = std::numbers::pi / 180.0;
constexpr double RHO0 = 1.225; // kg/m^3, ISA sea level
/// Static pitch stability (1/s): the nose pitches toward ALPHA_TRIM, so the stick commands an angle of
/// attack offset of maxPitchRate / PITCH_STABILITY (full stick: ~17 degrees, just past the stall).
constexpr double PITCH_STABILITY = 2.0;
constexpr double ALPHA_TRIM = 1.0 * DEG;
/// Weathercock (directional) stability, 1/s per radian of sideslip: the heading follows the track.
constexpr double YAW_STABILITY = 3.0;

double finiteOr0(double v, double lo, double hi) {
    return std::isfinite(v) ? std::clamp(v, lo, hi) : 0.0;
}
} // namespace

double AircraftParams::clMax() const {
    return cl0 + clAlpha * stallAlphaDeg * DEG;
}

double AircraftParams::stallSpeed() const {
    return std::sqrt(2.0 * mass * GRAVITY / (RHO0 * wingArea * clMax()));
}

bool Deck::contains(const glm::dvec2& xy) const {
    const glm::dvec2 d = xy - centre;
    const glm::dvec2 across(forward.y, -forward.x);
    return std::abs(glm::dot(d, forward)) <= halfLength && std::abs(glm::dot(d, across)) <= halfBeam;
}

double liftCoefficient(const AircraftParams& p, double alphaRad) {
    const double stall = p.stallAlphaDeg * DEG;
    const double a = std::abs(alphaRad);
    if (a <= stall)
        return p.cl0 + p.clAlpha * alphaRad;
    // Past the stall the lift collapses linearly over 10 degrees to 45% of CLmax, then stays there.
    const double s = std::min(1.0, (a - stall) / (10.0 * DEG));
    const double mag = p.clMax() * (1.0 - 0.55 * s);
    return alphaRad > 0.0 ? mag : -mag;
}

double airDensity(double z) {
    return RHO0 * std::exp(-std::max(z, 0.0) / 8500.0);
}

void stepAircraft(AircraftState& s, const FlightControls& cIn, const AircraftParams& p, double dt,
                  const std::optional<Deck>& deck) {
    const FlightControls c{finiteOr0(cIn.pitch, -1, 1), finiteOr0(cIn.roll, -1, 1), finiteOr0(cIn.yaw, -1, 1),
                           finiteOr0(cIn.throttle, 0, 1)};
    s.throttle += std::clamp(c.throttle - s.throttle, -p.throttleRate * dt, p.throttleRate * dt);

    const glm::dmat3 axes = attitudeMatrix(s.pose.headingDeg, s.pose.pitchDeg, s.pose.rollDeg);
    const glm::dvec3 fwd = axes[0], right = axes[1], up = axes[2];
    const double speed = glm::length(s.velocity);
    const glm::dvec3 vhat = speed > 1e-6 ? s.velocity / speed : fwd;
    const double alpha = std::atan2(-glm::dot(s.velocity, up), glm::dot(s.velocity, fwd));
    const double beta = std::atan2(glm::dot(s.velocity, right), std::max(glm::dot(s.velocity, fwd), 1e-6));
    const double rho = airDensity(s.pose.position.z);
    const double q = 0.5 * rho * speed * speed;
    const double cl = liftCoefficient(p, alpha);
    const double stall = p.stallAlphaDeg * DEG;
    const double cd = p.cd0 + p.inducedK * cl * cl + 1.2 * std::max(0.0, std::abs(alpha) - stall);
    glm::dvec3 liftDir = up - glm::dot(up, vhat) * vhat;
    liftDir = glm::length(liftDir) > 1e-9 ? glm::normalize(liftDir) : up;
    const glm::dvec3 lift = q * p.wingArea * cl * liftDir;
    const glm::dvec3 drag = -q * p.wingArea * cd * vhat;
    const glm::dvec3 thrust = s.throttle * p.maxThrust * (rho / RHO0) * fwd;
    glm::dvec3 force = lift + drag + thrust + glm::dvec3(0.0, 0.0, -p.mass * GRAVITY);
    s.alphaDeg = alpha / DEG;
    s.stalled = std::abs(alpha) > stall && speed > 1.0;
    s.loadFactor = glm::length(lift) / (p.mass * GRAVITY);

    // Deck contact: the wheels are on (or below) the deck's top inside its rectangle.
    const glm::dvec2 xy(s.pose.position);
    const bool contact = deck && deck->contains(xy) && s.pose.position.z - p.gearHeight <= deck->top + 0.05 &&
                         s.velocity.z <= 0.5;
    if (contact) {
        const double normal = std::max(0.0, -force.z); // the deck carries what the lift does not
        force.z = std::max(force.z, 0.0);
        const glm::dvec2 h(std::sin(s.pose.headingDeg * DEG), std::cos(s.pose.headingDeg * DEG));
        const glm::dvec2 rel = glm::dvec2(s.velocity) - deck->velocity;
        const double along = glm::dot(rel, h);
        // Rolling friction against the motion over the deck; the tyres kill sideways slip.
        if (std::abs(along) > 1e-3) {
            const double fr = std::min(p.rollingFriction * normal, std::abs(along) * p.mass / dt);
            force -= glm::dvec3(h * (along > 0 ? fr : -fr), 0.0);
        }
        const glm::dvec2 side = rel - along * h;
        s.velocity -= glm::dvec3(side * (1.0 - std::exp(-8.0 * dt)), 0.0);
    }
    s.velocity += force / p.mass * dt;
    if (contact) {
        s.velocity.z = std::max(s.velocity.z, 0.0);
        s.pose.position.z = std::max(s.pose.position.z, deck->top + p.gearHeight);
    }
    s.pose.position += s.velocity * dt;
    s.onDeck = contact;

    // Attitude: body rates from the stick, static stabilities and control authority growing with dynamic
    // pressure; then the Euler-angle kinematics (aerospace Z-Y-X, e.g. Stevens & Lewis, "Aircraft Control
    // and Simulation", eq. 1.4-4).
    const double authority = std::clamp(speed / 60.0, 0.15, 1.0);
    double pr = c.roll * p.maxRollRateDeg * DEG * authority;
    double qr =
        c.pitch * p.maxPitchRateDeg * DEG * authority - PITCH_STABILITY * authority * (alpha - ALPHA_TRIM);
    double rr = c.yaw * p.maxYawRateDeg * DEG + YAW_STABILITY * authority * beta;
    double phi = s.pose.rollDeg * DEG, theta = s.pose.pitchDeg * DEG, psi = s.pose.headingDeg * DEG;
    if (contact) {
        // On the wheels: no roll, the nose can rotate up to 12 degrees for the take-off.
        pr = -phi * 4.0;
        if (theta <= 0.0 && qr < 0.0)
            qr = 0.0;
    }
    const double phiDot = pr + (qr * std::sin(phi) + rr * std::cos(phi)) * std::tan(theta);
    const double thetaDot = qr * std::cos(phi) - rr * std::sin(phi);
    const double psiDot = (qr * std::sin(phi) + rr * std::cos(phi)) / std::cos(theta);
    phi += phiDot * dt;
    theta = std::clamp(theta + thetaDot * dt, -85.0 * DEG, 85.0 * DEG);
    psi += psiDot * dt;
    if (contact)
        theta = std::clamp(theta, 0.0, 12.0 * DEG);
    s.pose.rollDeg = std::remainder(phi / DEG, 360.0);
    s.pose.pitchDeg = theta / DEG;
    s.pose.headingDeg = std::fmod(std::fmod(psi / DEG, 360.0) + 360.0, 360.0);
}

} // namespace pacifica::game
