// Autopilot: flies a whole sortie from the controls alone -- the same FlightControls and fire() a player
// has -- for scripted runs (`pacifica-game --autopilot`, the tests) and as a demo: full-throttle take-off
// roll, rotation at the stall speed, climb to the cruise altitude, then for each target in turn a
// level bomb run: it predicts where a bomb released now would fall (the weapon's own ballistics,
// stepWeapon()) and where the ship will be by then, steers toward that point and releases as the predicted
// impact passes it.
#pragma once

#include "game/World.h"

#include <string>

namespace pacifica::game {

struct AutopilotDecision {
    FlightControls controls;
    bool releaseBomb = false;
    std::string phase;           ///< "takeoff", "climb", "run-in", "extend", "release", "egress", "done"
    int target = -1;             ///< index into World::ships()
    double predictedMissM = 0.0; ///< predicted impact to the ship's predicted position, metres
};

class Autopilot {
public:
    double cruiseAltitude = 320.0; ///< m
    double cruiseSpeed = 150.0;    ///< m/s

    AutopilotDecision decide(const World& world);
    /// Tells the autopilot the bomb it asked for left the aircraft (World::fire's id, 0 = none).
    void released(uint64_t id, double time) {
        if (id != 0) {
            mBombInFlight = id;
            mLastRelease = time;
        }
    }

    /// Where a bomb released now from the player would meet z = 0, and after how long (flat calm sea).
    static glm::dvec2 predictImpact(const World& world, double& fallTime);

private:
    int chooseTarget(const World& world);

    uint64_t mBombInFlight = 0;
    double mLastRelease = -1e9;
    int mTarget = -1;
    bool mExtending = false;
};

} // namespace pacifica::game
