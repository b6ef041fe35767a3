// CameraPoses: look-at, cockpit, chase and orbit poses (engine/CameraPoses.h).
#include "engine/CameraPoses.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pacifica {

namespace {

constexpr double DEG = std::numbers::pi / 180.0;

double wrap360(double a) {
    a = std::fmod(a, 360.0);
    return a < 0.0 ? a + 360.0 : a;
}

} // namespace

Pose lookAtPose(const glm::dvec3& from, const glm::dvec3& to) {
    const double dz = drawnZ(to, from) - from.z;
    const double dx = to.x - from.x, dy = to.y - from.y;
    Pose p;
    p.position = from;
    const double h = std::hypot(dx, dy);
    p.headingDeg = h > 1e-9 ? wrap360(std::atan2(dx, dy) / DEG) : 0.0;
    p.pitchDeg = std::atan2(dz, h) / DEG;
    p.rollDeg = 0.0;
    return p;
}

Pose cockpitPose(const Pose& object, const glm::dvec3& eye) {
    Pose p = object;
    const glm::dmat3 axes = attitudeMatrix(p.headingDeg, p.pitchDeg, p.rollDeg); // forward, right, up
    p.position += axes * eye;
    return p;
}

Pose chasePose(const TrackFn& track, double t, double distance, double height, double smoothing) {
    const Pose target = track(t);
    // Heading smoothed by an exponential look-back window (weights e^(-age/tau), 0.05 s steps, 5 tau): the
    // circular mean of the track's headings, so the camera swings after the aircraft, not with it.
    double sx = 0.0, sy = 0.0;
    const double tau = smoothing;
    const int steps = tau > 0.0 ? std::min(400, static_cast<int>(std::ceil(5.0 * tau / 0.05))) : 0;
    for (int k = 0; k <= steps; ++k) {
        const double age = 0.05 * k;
        const double w = tau > 0.0 ? std::exp(-age / tau) : 1.0;
        const double h = track(t - age).headingDeg * DEG;
        sx += w * std::sin(h);
        sy += w * std::cos(h);
    }
    const double heading = std::atan2(sx, sy);
    const glm::dvec3 back(-std::sin(heading), -std::cos(heading), 0.0);
    const glm::dvec3 eye = target.position + distance * back + glm::dvec3(0.0, 0.0, height);
    return lookAtPose(eye, target.position);
}

Pose orbitPose(const glm::dvec3& centre, double distance, double elevationDeg, double azimuthDeg) {
    const double az = azimuthDeg * DEG, el = elevationDeg * DEG;
    const glm::dvec3 eye = centre + distance * glm::dvec3(std::cos(el) * std::sin(az),
                                                          std::cos(el) * std::cos(az), std::sin(el));
    return lookAtPose(eye, centre);
}

} // namespace pacifica
