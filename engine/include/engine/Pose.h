// Pose: where a camera or vehicle is and which way it faces, in double precision world space.
//
// Conventions (docs/ARCHITECTURE.md): world frame is local ENU — x east, y north, z up, metres, double.
// heading: degrees clockwise from north (compass); pitch: degrees, nose up positive; roll: degrees,
// right wing down positive. Attitude is applied heading, then pitch, then roll (aerospace Z-Y-X order).
#pragma once

#include <glm/glm.hpp>

namespace pacifica {

struct Pose {
    glm::dvec3 position{0.0, 0.0, 0.0}; // world metres (ENU)
    double headingDeg = 0.0;
    double pitchDeg = 0.0;
    double rollDeg = 0.0;
};

/// Body axes of an attitude expressed in the world frame: columns are forward, right, up (unit vectors).
/// heading 0 -> forward +y (north); heading 90 -> forward +x (east); pitch +90 -> forward +z;
/// roll +90 at heading 0, pitch 0 -> right = -z. Note the column order makes det = -1 (forward x right =
/// -up); reorder to (right, forward, up) for a proper rotation. Implemented in engine/src/Pose.cpp.
glm::dmat3 attitudeMatrix(double headingDeg, double pitchDeg, double rollDeg);

/// Interpolates two poses: position linearly, attitude by quaternion slerp (shortest arc), s in [0,1].
/// The result's heading is in [0, 360), pitch in [-90, 90], roll in (-180, 180]; looking straight up or
/// down (where heading and roll coincide) the roll is folded into the heading. So heading 350 -> 10 passes
/// through 0, not 180.
Pose interpolatePose(const Pose& a, const Pose& b, double s);

} // namespace pacifica
