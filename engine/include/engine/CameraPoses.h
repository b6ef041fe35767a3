// CameraPoses: the camera maths every host shares -- look at a point, ride in a cockpit, chase, orbit -- as
// functions of a pose or of any track (a recording's object in replay, the game's live aircraft), so the
// game's cameras are the replay's rigs. Poses are world ENU metres and degrees (engine/Pose.h).
#pragma once

#include "engine/Pose.h"
#include "engine/Space.h"

#include <glm/glm.hpp>

#include <functional>

namespace pacifica {

/// The pose at `from` looking at `to` (roll 0), aiming where the renderer draws `to` (drawnZ,
/// engine/Space.h).
Pose lookAtPose(const glm::dvec3& from, const glm::dvec3& to);

using TrackFn = std::function<Pose(double)>;
/// The object's pose plus an eye offset in its body axes (forward, right, up; metres).
Pose cockpitPose(const Pose& object, const glm::dvec3& eye);
/// Behind and above the object, looking at it; the heading is the circular mean of the track's headings
/// over an exponential look-back window of `smoothing` seconds (0 = none), so the camera swings after it.
Pose chasePose(const TrackFn& track, double t, double distance, double height, double smoothing);
/// On a sphere of `distance` around `centre` at elevation and compass azimuth (degrees), looking at it.
Pose orbitPose(const glm::dvec3& centre, double distance, double elevationDeg, double azimuthDeg);

} // namespace pacifica
