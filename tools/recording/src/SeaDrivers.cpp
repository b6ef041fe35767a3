// SeaDrivers: recorded objects -> ships and sea impacts (rules in SeaDrivers.h).
#include "recording/SeaDrivers.h"

#include <algorithm>
#include <cmath>

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

SeaDrivers seaDrivers(const Recording& rec, const EarthFrame& frame, const LandMask* mask) {
    SeaDrivers out;
    for (const RecordedObject& o : rec.objects) {
        TypeTally& tally = out.byType[o.type.empty() ? "(no type)" : o.type];
        ++tally.read;
        if (o.track.empty()) {
            ++tally.leftOut["no position recorded"];
            continue;
        }
        if (o.hasTag("Watercraft")) {
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
            if (ship.samples.size() == 1) { // a ship seen once stays put for the whole recording
                glm::dvec3 last = ship.samples.front();
                last.x = std::max(rec.endTime, last.x + 1.0);
                ship.samples.push_back(last);
            }
            out.ships.push_back(std::move(ship));
            ++tally.ships;
            continue;
        }
        const double strength = explosionStrengthFor(o);
        if (strength <= 0.0) {
            ++tally.leftOut[o.hasTag("Ground") ? "ground object" : "not a ship, weapon or aircraft"];
            continue;
        }
        const bool destroyed = o.destroyedAt.has_value();
        if (!destroyed && !o.removedAt) {
            ++tally.leftOut["track does not end (no removal or Destroyed event)"];
            continue;
        }
        const double tEnd = destroyed ? *o.destroyedAt : *o.removedAt;
        ObjectSample end = o.sampleAt(tEnd);
        // Vertical speed over the last step, to catch a fast descent last seen above the contact height.
        const auto it = std::upper_bound(o.track.begin(), o.track.end(), tEnd,
                                         [](double v, const ObjectSample& s) { return v < s.time; });
        double vz = 0.0, vh = 0.0, step = 0.0;
        if (it - o.track.begin() >= 2) {
            const ObjectSample& b = *(it - 1);
            const ObjectSample& a = *(it - 2);
            step = b.time - a.time;
            if (step > 0.0) {
                const glm::dvec3 wa = frame.toWorld(a.lat, a.lon, a.alt),
                                 wb = frame.toWorld(b.lat, b.lon, b.alt);
                vz = (wb.z - wa.z) / step;
                vh = std::hypot(wb.x - wa.x, wb.y - wa.y) / step;
            }
        }
        glm::dvec3 at = frame.toWorld(end.lat, end.lon, end.alt);
        bool atSea = end.alt <= SEA_CONTACT_M;
        if (!atSea && vz < 0.0 && step > 0.0 && end.alt / -vz <= std::min(1.5 * step, 2.0)) {
            // Extrapolate the last step's straight line down to sea level.
            const ObjectSample& b = *(it - 1);
            const ObjectSample& a = *(it - 2);
            const glm::dvec3 wa = frame.toWorld(a.lat, a.lon, a.alt), wb = frame.toWorld(b.lat, b.lon, b.alt);
            const double s = wb.z / (wa.z - wb.z);
            at = wb + s * (wb - wa);
            atSea = true;
        }
        if (mask) {
            double lat = 0.0, lon = 0.0, alt = 0.0;
            frame.toGeodetic(at, lat, lon, alt);
            if (mask->isLand(lat, lon)) {
                ++tally.leftOut["ended over land (GSHHG shoreline)"];
                continue;
            }
        }
        if (!atSea) {
            ++tally.leftOut[mask ? "ended above the sea (in the air)"
                                 : "ended above the sea (over land or in the air)"];
            continue;
        }
        if (o.hasTag("Air") && !destroyed && vh < 20.0) {
            ++tally.leftOut["removed slowly at sea level without a Destroyed event (landed or despawned)"];
            continue;
        }
        SeaImpact impact;
        impact.time = tEnd;
        impact.position = {at.x, at.y};
        impact.strength = strength;
        impact.id = o.id;
        impact.type = o.type;
        impact.cause = destroyed ? "destroyed at the sea surface" : "removed at the sea surface";
        out.impacts.push_back(impact);
        ++tally.explosions;
    }
    std::stable_sort(out.impacts.begin(), out.impacts.end(),
                     [](const SeaImpact& a, const SeaImpact& b) { return a.time < b.time; });
    return out;
}

} // namespace pacifica::recording
