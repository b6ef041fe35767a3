// EarthFrame: WGS84 geodesics through GeographicLib's azimuthal equidistant projection (Karney 2013,
// "Algorithms for geodesics", J. Geodesy 87), z = altitude MSL. See EarthFrame.h for why the world is flat.
#include "recording/EarthFrame.h"

#include <GeographicLib/AzimuthalEquidistant.hpp>

#include <cmath>

namespace pacifica::recording {

namespace {
const GeographicLib::AzimuthalEquidistant& projection() {
    static const GeographicLib::AzimuthalEquidistant p(GeographicLib::Geodesic::WGS84());
    return p;
}
double wrap360(double a) {
    a = std::fmod(a, 360.0);
    return a < 0.0 ? a + 360.0 : a;
}
} // namespace

EarthFrame::EarthFrame(double lat0, double lon0) : mLat0(lat0), mLon0(lon0) {}

glm::dvec3 EarthFrame::toWorld(double lat, double lon, double altMsl) const {
    double x = 0.0, y = 0.0;
    projection().Forward(mLat0, mLon0, lat, lon, x, y);
    return {x, y, altMsl};
}

void EarthFrame::toGeodetic(const glm::dvec3& w, double& lat, double& lon, double& altMsl) const {
    projection().Reverse(mLat0, mLon0, w.x, w.y, lat, lon);
    altMsl = w.z;
}

double EarthFrame::gridHeading(double lat, double lon, double trueHeadingDeg) const {
    double x = 0.0, y = 0.0, azi = 0.0, rk = 1.0;
    projection().Forward(mLat0, mLon0, lat, lon, x, y, azi, rk);
    if (std::hypot(x, y) < 1e-3)
        return wrap360(trueHeadingDeg);
    // The geodesic from the origin is a straight radial line in this projection with grid bearing
    // atan2(x, y); at the point it runs at true azimuth azi. So grid = true + (radial bearing - azi).
    const double radial = std::atan2(x, y) * 180.0 / M_PI;
    return wrap360(trueHeadingDeg + radial - azi);
}

Pose EarthFrame::toWorldPose(const ObjectSample& s) const {
    Pose p;
    p.position = toWorld(s.lat, s.lon, s.alt);
    p.headingDeg = gridHeading(s.lat, s.lon, s.yaw);
    p.pitchDeg = s.pitch;
    p.rollDeg = s.roll;
    return p;
}

EarthFrame chooseFrame(const Recording& rec, const RecordedObject* focus, double t) {
    if (focus && !focus->track.empty()) {
        const ObjectSample s = focus->sampleAt(t);
        return EarthFrame(s.lat, s.lon);
    }
    double lat = 0.0, x = 0.0, y = 0.0;
    int n = 0;
    for (const RecordedObject& o : rec.objects) {
        if (o.track.empty() || o.hasTag("Navaid"))
            continue;
        lat += o.track.front().lat;
        x += std::cos(o.track.front().lon * M_PI / 180.0);
        y += std::sin(o.track.front().lon * M_PI / 180.0);
        ++n;
    }
    if (n == 0)
        return EarthFrame(rec.referenceLatitude, rec.referenceLongitude);
    return EarthFrame(lat / n, std::atan2(y, x) * 180.0 / M_PI);
}

} // namespace pacifica::recording
