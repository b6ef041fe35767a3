// SeaDrivers: recorded objects -> ships and sea impacts (rules in SeaDrivers.h).
#include "recording/SeaDrivers.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace pacifica::recording {

double explosionStrengthFor(const RecordedObject& o) {
    if (o.hasTag("Bomb") || o.hasTag("Torpedo"))
        return 1.0;
    if (o.hasTag("Missile"))
        return 0.4;
    if (o.hasTag("Rocket"))
        return 0.05;
    if (o.hasTag("Shell"))
        return 0.01;
    if (o.hasTag("Weapon") || o.hasTag("Projectile"))
        return 0.2;
    if (o.hasTag("Parachutist"))
        return 0.0;
    if (o.hasTag("FixedWing"))
        return 0.8;
    if (o.hasTag("Rotorcraft"))
        return 0.4;
    if (o.hasTag("Air"))
        return 0.3;
    return 0.0;
}

double shipLength(const RecordedObject& o) {
    if (o.length > 0.0)
        return o.length;
    if (o.hasTag("AircraftCarrier"))
        return 330.0;
    if (o.hasTag("Warship"))
        return 150.0;
    return 60.0;
}

namespace {

/// A watercraft's track in the world frame (one sample per time; a ship seen once stays put for the whole
/// recording).
SeaShip seaShip(const RecordedObject& o, const EarthFrame& frame, double recordingEnd) {
    SeaShip ship;
    ship.id = o.id;
    ship.label = o.describe();
    ship.length = shipLength(o);
    for (const ObjectSample& s : o.track) {
        const glm::dvec3 w = frame.toWorld(s.lat, s.lon, s.alt);
        if (!ship.samples.empty() && s.time <= ship.samples.back().x)
            continue;
        ship.samples.push_back({s.time, w.x, w.y});
    }
    if (ship.samples.size() == 1) {
        glm::dvec3 last = ship.samples.front();
        last.x = std::max(recordingEnd, last.x + 1.0);
        ship.samples.push_back(last);
    }
    return ship;
}

/// Where an object's track ends (at tEnd) and whether that is at the sea surface: at or below the contact
/// height, or a fast descent last seen above it whose last step's straight line reaches sea level within
/// 1.5 steps (2 s at most). `horizontalSpeed`: over the last step, m/s.
glm::dvec3 endPoint(const RecordedObject& o, const EarthFrame& frame, double tEnd, bool& atSea,
                    double& horizontalSpeed) {
    const ObjectSample end = o.sampleAt(tEnd);
    const auto it = std::upper_bound(o.track.begin(), o.track.end(), tEnd,
                                     [](double v, const ObjectSample& s) { return v < s.time; });
    double vz = 0.0, step = 0.0;
    horizontalSpeed = 0.0;
    glm::dvec3 wa(0.0), wb(0.0);
    if (it - o.track.begin() >= 2) {
        const ObjectSample& b = *(it - 1);
        const ObjectSample& a = *(it - 2);
        step = b.time - a.time;
        if (step > 0.0) {
            wa = frame.toWorld(a.lat, a.lon, a.alt);
            wb = frame.toWorld(b.lat, b.lon, b.alt);
            vz = (wb.z - wa.z) / step;
            horizontalSpeed = std::hypot(wb.x - wa.x, wb.y - wa.y) / step;
        }
    }
    glm::dvec3 at = frame.toWorld(end.lat, end.lon, end.alt);
    atSea = end.alt <= SEA_CONTACT_M;
    if (!atSea && vz < 0.0 && step > 0.0 && end.alt / -vz <= std::min(1.5 * step, 2.0)) {
        const double s = wb.z / (wa.z - wb.z); // extrapolate the last step's line down to sea level
        at = wb + s * (wb - wa);
        atSea = true;
    }
    return at;
}

/// The explosion a weapon or aircraft makes where its track ends at sea, or the reason it makes none
/// (counted in the tally's leftOut).
std::optional<SeaImpact> seaImpact(const RecordedObject& o, const EarthFrame& frame, const LandMask* mask,
                                   TypeTally& tally) {
    const double strength = explosionStrengthFor(o);
    if (strength <= 0.0) {
        ++tally.leftOut[o.hasTag("Ground") ? "ground object" : "not a ship, weapon or aircraft"];
        return std::nullopt;
    }
    const bool destroyed = o.destroyedAt.has_value();
    if (!destroyed && !o.removedAt) {
        ++tally.leftOut["track does not end (no removal or Destroyed event)"];
        return std::nullopt;
    }
    const double tEnd = destroyed ? *o.destroyedAt : *o.removedAt;
    bool atSea = false;
    double vh = 0.0;
    const glm::dvec3 at = endPoint(o, frame, tEnd, atSea, vh);
    if (mask) {
        double lat = 0.0, lon = 0.0, alt = 0.0;
        frame.toGeodetic(at, lat, lon, alt);
        if (mask->isLand(lat, lon)) {
            ++tally.leftOut["ended over land (GSHHG shoreline)"];
            return std::nullopt;
        }
    }
    if (!atSea) {
        ++tally.leftOut[mask ? "ended above the sea (in the air)"
                             : "ended above the sea (over land or in the air)"];
        return std::nullopt;
    }
    if (o.hasTag("Air") && !destroyed && vh < 20.0) {
        ++tally.leftOut["removed slowly at sea level without a Destroyed event (landed or despawned)"];
        return std::nullopt;
    }
    SeaImpact impact;
    impact.time = tEnd;
    impact.position = {at.x, at.y};
    impact.strength = strength;
    impact.id = o.id;
    impact.type = o.type;
    impact.cause = destroyed ? "destroyed at the sea surface" : "removed at the sea surface";
    return impact;
}

} // namespace

SeaDrivers seaDrivers(const Recording& rec, const EarthFrame& frame, const LandMask* mask) {
    SeaDrivers out;
    for (const RecordedObject& o : rec.objects) {
        TypeTally& tally = out.byType[o.type.empty() ? "(no type)" : o.type];
        ++tally.read;
        if (o.track.empty()) {
            ++tally.leftOut["no position recorded"];
        } else if (o.hasTag("Watercraft")) {
            out.ships.push_back(seaShip(o, frame, rec.endTime));
            ++tally.ships;
        } else if (const std::optional<SeaImpact> impact = seaImpact(o, frame, mask, tally)) {
            out.impacts.push_back(*impact);
            ++tally.explosions;
        }
    }
    std::stable_sort(out.impacts.begin(), out.impacts.end(),
                     [](const SeaImpact& a, const SeaImpact& b) { return a.time < b.time; });
    return out;
}

} // namespace pacifica::recording
