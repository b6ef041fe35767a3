// Pose implementation: heading/pitch/roll to body axes in the ENU world frame, and pose interpolation by
// quaternion slerp. Angles follow the aerospace Z-Y-X (yaw, pitch, roll) sequence, written out for the
// compass-heading convention of Pose.h (heading clockwise from north, so the yaw is about -z).
#include "engine/Pose.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace pacifica {
namespace {

constexpr double PI = 3.14159265358979323846;
constexpr double DEG = PI / 180.0;

/// The attitude as a proper rotation: columns right, forward, up (right x forward = up, det +1), so it can
/// round-trip through a quaternion. attitudeMatrix's column order (forward, right, up) has det -1.
glm::dmat3 bodyToWorld(double headingDeg, double pitchDeg, double rollDeg) {
    const glm::dmat3 m = attitudeMatrix(headingDeg, pitchDeg, rollDeg);
    return glm::dmat3(m[1], m[0], m[2]);
}

double wrapDegrees360(double deg) {
    double r = std::fmod(deg, 360.0);
    if (r < 0.0)
        r += 360.0;
    return r < 360.0 ? r + 0.0 : 0.0;
}

} // namespace

glm::dmat3 attitudeMatrix(double headingDeg, double pitchDeg, double rollDeg) {
    const double sh = std::sin(headingDeg * DEG), ch = std::cos(headingDeg * DEG);
    const double sp = std::sin(pitchDeg * DEG), cp = std::cos(pitchDeg * DEG);
    const double sr = std::sin(rollDeg * DEG), cr = std::cos(rollDeg * DEG);
    // Heading then pitch: forward points at compass bearing h, elevation p. Before roll, right stays
    // horizontal and up = right x forward.
    const glm::dvec3 forward(sh * cp, ch * cp, sp);
    const glm::dvec3 right0(ch, -sh, 0.0);
    const glm::dvec3 up0(-sh * sp, -ch * sp, cp);
    // Roll about forward, right wing down positive: right tilts towards -up, up tilts towards right.
    const glm::dvec3 right = right0 * cr - up0 * sr;
    const glm::dvec3 up = up0 * cr + right0 * sr;
    return glm::dmat3(forward, right, up);
}

Pose interpolatePose(const Pose& a, const Pose& b, double s) {
    Pose out;
    out.position = a.position + (b.position - a.position) * s;

    const glm::dquat qa = glm::normalize(glm::quat_cast(bodyToWorld(a.headingDeg, a.pitchDeg, a.rollDeg)));
    glm::dquat qb = glm::normalize(glm::quat_cast(bodyToWorld(b.headingDeg, b.pitchDeg, b.rollDeg)));
    if (glm::dot(qa, qb) < 0.0)
        qb = -qb; // q and -q are the same rotation: pick the one on qa's side for the shortest arc
    const glm::dmat3 m = glm::mat3_cast(glm::normalize(glm::slerp(qa, qb, s)));
    const glm::dvec3 right = m[0], forward = m[1], up = m[2];

    // Back to angles (inverse of attitudeMatrix): forward gives heading and pitch; roll from the vertical
    // components right.z = -cos(p) sin(r) and up.z = cos(p) cos(r).
    // atan2 rather than asin: well conditioned near +-90 degrees, where asin loses half the digits.
    const double horizontal = std::hypot(forward.x, forward.y);
    out.pitchDeg = std::atan2(forward.z, horizontal) / DEG;
    // Near vertical, heading and roll come from components of size ~horizontal carrying ~1e-16 of rounding
    // (relative error 1e-16 / horizontal), while folding roll into heading moves the axes by ~horizontal.
    // The threshold 1e-8 = sqrt(1e-16) balances the two: axis errors stay below ~1e-8 either way.
    if (horizontal > 1e-8) {
        out.headingDeg = wrapDegrees360(std::atan2(forward.x, forward.y) / DEG);
        out.rollDeg = std::atan2(-right.z, up.z) / DEG;
    } else {
        // Pointing straight up or down: heading and roll turn about the same axis. Put it all in heading
        // (roll 0, so right = (cos h, -sin h, 0)).
        out.headingDeg = wrapDegrees360(std::atan2(-right.y, right.x) / DEG);
        out.rollDeg = 0.0;
    }
    return out;
}

} // namespace pacifica
