// ReplayLights: `pacifica replay --light spot:TARGET[,key=value...]` -- spot lights (ocean::SpotLight) on a
// recorded ship (its searchlight, turning with it) or fixed in the world (a lighthouse), as the frames need
// them: parsed once against the run's ships, placed at each frame's time.
//
//   spot:SHIP[,height=M][,azimuth=DEG][,elevation=DEG][,angle=DEG][,intensity=I][,range=M][,color=R:G:B]
//   spot:fixed,x=M,y=M[,...the same keys]
//
// SHIP is a ship's id (`--list-objects`, or a flight CSV's ship id). height: metres above the sea, >= 0
// (default 20); azimuth: degrees clockwise from the ship's heading (fixed: from north; default 0); elevation:
// degrees above the horizontal (default -10: onto the sea); angle: the cone's half-angle (default 6);
// intensity, range, color: ocean::SpotLight's (default 2e4, 5000 m, white). x, y: metres east and north in
// the replay's world (summary.json's recording origin).
#pragma once

#include "ReplayInput.h"

#include "ocean/Lighting.h"

#include <optional>
#include <string>
#include <vector>

namespace pacifica::tools {

struct ReplayLight {
    std::string spec;            ///< as given, for messages and summary.json
    std::optional<size_t> ship;  ///< index into ReplayInput::ships; none = fixed
    glm::dvec2 fixedPosition{0}; ///< fixed: metres east, north
    double height = 20.0, azimuthDeg = 0.0, elevationDeg = -10.0, angleDeg = 6.0;
    float intensity = 2.0e4f;
    double range = 5000.0;
    glm::vec3 color{1.0f};
};

/// Parses every --light spec against the run's ships. `exposureScale` (2^EV, the replay's pre-exposure) is
/// checked with each light's colour x intensity against ocean::MAX_SPOT_INTENSITY. Throws UsageError naming
/// the spec and the key.
std::vector<ReplayLight> parseReplayLights(const std::vector<std::string>& specs, const ReplayInput& input,
                                           double exposureScale);

/// The lights at time t, their intensities times `exposureScale` (2^EV: the replay's pre-exposure). A ship's
/// light is out of the frame before its track starts and after it ends.
std::vector<ocean::SpotLight> replayLightsAt(const std::vector<ReplayLight>& lights, const ReplayInput& input,
                                             double t, double exposureScale);

} // namespace pacifica::tools
