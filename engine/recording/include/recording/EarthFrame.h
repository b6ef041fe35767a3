// EarthFrame: places geodetic (WGS84) positions in the renderer's world -- x east, y north, z up, metres,
// double -- around an origin near the action (never the ACMI reference point, which is 600-1000 km away in
// DCS files).
//
// The ocean draws a flat world and drops the sea by curvatureDrop(d) = d^2 / 2R with the horizontal distance
// d from the camera (ocean/OceanConstants.h). So the world frame here is flat too: x, y are the azimuthal
// equidistant projection of the point on the WGS84 ellipsoid (GeographicLib: distance and azimuth from the
// origin are exact geodesic ones), and z is the altitude above mean sea level. An object at altitude 0 is
// then on the rendered sea seen from any camera, because the host drops it by the same curvatureDrop() as the
// sea under it (drawnZ() below). Against the exact local ENU (GeographicLib::LocalCartesian), the dropped
// position of a sea-level point differs by the sphere-vs-ellipsoid sagitta and the projection's
// d^3/6R^2 shrinkage: a few metres at 100 km (tests/unit/test_recording.cpp states the bound).
//
// Headings: true north at a point is not the grid's +y away from the origin (meridian convergence, ~0.9 deg
// at 100 km); gridHeading() rotates a true heading into the world frame.
#pragma once

#include "recording/Recording.h"

#include <engine/Pose.h>

#include <glm/glm.hpp>

namespace pacifica::recording {

class EarthFrame {
public:
    /// Origin at (lat0, lon0) on the sea surface (altitude 0 -> z = 0).
    EarthFrame(double lat0, double lon0);
    double originLatitude() const { return mLat0; }
    double originLongitude() const { return mLon0; }

    /// World position (metres) of a geodetic point: azimuthal equidistant x, y; z = altMsl.
    glm::dvec3 toWorld(double lat, double lon, double altMsl) const;
    /// The inverse of toWorld().
    void toGeodetic(const glm::dvec3& world, double& lat, double& lon, double& altMsl) const;
    /// A true heading (degrees clockwise from true north at (lat, lon)) as a world-grid heading.
    double gridHeading(double lat, double lon, double trueHeadingDeg) const;
    /// An object's sample as a world pose (position, grid heading, pitch, roll).
    Pose toWorldPose(const ObjectSample& s) const;

private:
    double mLat0, mLon0;
};

/// Chooses an origin near the action: the position of `focus` at time t if given, else the mean of the
/// first samples of the recording's objects (ignoring navaids/bullseyes, which sit at dummy places).
EarthFrame chooseFrame(const Recording& rec, const RecordedObject* focus, double t);

} // namespace pacifica::recording
