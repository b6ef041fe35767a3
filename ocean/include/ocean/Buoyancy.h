// Buoyancy: a hull floated on the sea from a few of its points -- what a game's ships and a replay's
// recorded ships ride. Quasi-static: the hull takes the least-squares plane through the sea's heights under a
// 3 x 3 grid of its points (no inertia, no added mass; the hull's length and beam average the waves shorter
// than it out, as a real hull's response does to first order). The heights come from SeaQuery (one batched
// query for every hull).
//
//   std::array<glm::dvec2, HULL_POINTS> points;
//   hullPoints(centre, headingDeg, length, halfBeam, points);   // for each hull, into one span
//   query.heights(allPoints, allHeights);
//   const HullPose p = floatHull(heights of this hull, length, halfBeam);   // heave, pitch, roll
#pragma once

#include <glm/glm.hpp>

#include <span>

namespace pacifica::ocean {

/// A hull's buoyancy points: at 0 and +-HULL_ALONG of its length along, 0 and +-HULL_ACROSS of its half beam
/// across (row by row from the stern, port to starboard).
inline constexpr int HULL_POINTS = 9;
inline constexpr double HULL_ALONG = 0.4, HULL_ACROSS = 0.8;

struct HullPose {
    double heave = 0.0;    ///< metres above mean sea level: the mean of the heights
    double pitchDeg = 0.0; ///< bow up positive (the sea higher ahead)
    double rollDeg = 0.0;  ///< right side down positive (the sea lower to starboard), as Pose
};

/// The HULL_POINTS world points (x, y) of a hull centred at `centre`, heading `headingDeg` (compass: 0 north,
/// 90 east), `length` and `halfBeam` metres.
void hullPoints(const glm::dvec2& centre, double headingDeg, double length, double halfBeam,
                std::span<glm::dvec2, HULL_POINTS> out);

/// The plane through the sea's heights at hullPoints() (same order): heave = their mean, the slopes
/// b = sum h a / sum a^2 along and c likewise across (the grid's moments separate), pitch = atan b, roll =
/// -atan c.
HullPose floatHull(std::span<const double, HULL_POINTS> heights, double length, double halfBeam);

} // namespace pacifica::ocean
