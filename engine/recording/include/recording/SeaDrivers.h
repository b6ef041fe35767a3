// SeaDrivers: what in a recording drives the sea -- ships (Kelvin wakes along their recorded tracks) and
// impacts (explosions where a weapon or aircraft meets the sea) -- and what is left out, and why.
//
// Rules (docs/FLIGHT_FORMAT.md, "Recordings", repeats them):
// - `Sea+Watercraft` objects become ships: their track in the world frame (speed from the track; a ship that
//   does not move makes no wake, WakeParams::minSpeed). Length from the ACMI Length property, else by type
//   (AircraftCarrier 330 m, Warship 150 m, other 60 m).
// - Weapons (`Weapon`, `Projectile` tags: bombs, missiles, rockets, torpedoes, shells) and aircraft (`Air`)
//   explode where their track ends -- a `-id` removal or a Destroyed event -- at the sea: the last recorded
//   altitude within SEA_CONTACT_M of sea level, or a descent that reaches it within the last sample step
//   (extrapolated: a 300 m/s bomb recorded at 10 Hz is last seen ~30 m up), and not over land by the GSHHG
//   shorelines when a LandMask is given. An end further above sea level is "ended above the sea (in the air)"
//   (without a mask: "(over land or in the air)") and left out; an
//   aircraft removed at sea level without a Destroyed event and below 20 m/s (parked, landed, despawned) is
//   left out too. Strength by type: explosionStrengthFor() (1 = a nominal 500 kg charge).
// - Everything else (navaids, ground units, flares, chaff, shrapnel, parachutists) is left out by type.
#pragma once

#include "recording/EarthFrame.h"
#include "recording/LandMask.h"
#include "recording/Recording.h"

#include <glm/glm.hpp>

#include <map>
#include <string>
#include <vector>

namespace pacifica::recording {

inline constexpr double SEA_CONTACT_M = 5.0; ///< metres: an end this close to sea level is at the sea

struct SeaShip {
    uint64_t id = 0;
    std::string label; ///< RecordedObject::describe()
    double length = 60.0;
    std::vector<glm::dvec3> samples; ///< (time, x, y) world metres; strictly increasing time, >= 2 samples
};

struct SeaImpact {
    double time = 0.0;
    glm::dvec2 position{0.0}; ///< world metres
    double strength = 1.0;
    uint64_t id = 0;
    std::string type;
    std::string cause; ///< "removed at the sea surface", "destroyed at the sea surface"
};

struct TypeTally {
    long long read = 0, ships = 0, explosions = 0;
    std::map<std::string, long long> leftOut; ///< reason -> count
};

struct SeaDrivers {
    std::vector<SeaShip> ships;              ///< in the recording's object order
    std::vector<SeaImpact> impacts;          ///< sorted by time (stable)
    std::map<std::string, TypeTally> byType; ///< key: the object's type ("(no type)" when absent)
};

/// Strength (1 = a nominal 500 kg charge) of the explosion an object makes at the sea, by its type tags:
/// Bomb 1.0, Torpedo 1.0, Missile 0.4, Rocket 0.05, Shell 0.01, other weapon 0.2; FixedWing 0.8,
/// Rotorcraft 0.4, other aircraft 0.3. 0 for objects that never explode (ships, navaids, ...).
double explosionStrengthFor(const RecordedObject& o);

/// mask (optional, LandMask::loadDefault()): an end over land is left out as "ended over land (GSHHG
/// shoreline)" whatever its altitude; without a mask only the altitude rule above applies.
/// A ship's length: the ACMI Length property, else carrier 330 m, warship 150 m, other 60 m.
double shipLength(const RecordedObject& o);

SeaDrivers seaDrivers(const Recording& rec, const EarthFrame& frame, const LandMask* mask = nullptr);

} // namespace pacifica::recording
