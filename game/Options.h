// Options: pacifica-game's command line (CLI11). Bad values throw UsageError naming the option; main exits 2.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pacifica::game {

class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// cockpit, chase and orbit are the replay's rigs (recording/CameraRig.h) over the player's live track;
/// weapon follows the newest bomb or rocket down and then watches where it hit for a few seconds; ship
/// circles the target ship nearest to the player (else the carrier) low over the sea, to see it pitch and
/// heave on the waves.
enum class CameraMode { Cockpit = 0, Chase = 1, Orbit = 2, Weapon = 3, Ship = 4 };
inline constexpr int CAMERA_MODES = 5;
const char* toString(CameraMode m);

/// The sea the HUD can switch live: quality preset, surface model, wind speed (sea state).
struct SeaSettings {
    std::string quality = "medium"; ///< low | medium | high | reference (ocean/Presets.h)
    std::string model = "octaves";  ///< octaves | gerstner | fft
    double windSpeed = 12.0;        ///< U10, m/s, [2, 25]
    bool night = false;             ///< --night: moonlit, hazy, the carrier's lamps (game/Night.h); not live
};
/// ocean::SurfaceKind of a model name; UsageError listing the names.
int parseSurfaceModelIndex(const std::string& name);

struct Options {
    bool help = false;
    bool autopilot = false; ///< the autopilot flies (scripted input)
    long long frames = 0;   ///< stop after N frames (0 = play until quit)
    double fps = 30.0;      ///< scripted runs: game seconds per frame = 1 / fps
    std::vector<std::pair<double, std::string>> screenshots; ///< (game time, PNG file)
    std::string record;                                      ///< ACMI file
    std::string summary;                                     ///< JSON file
    std::string bench; ///< JSON file: time each preset (implies --autopilot)
    CameraMode camera = CameraMode::Chase;
    SeaSettings sea;
    std::string view, wipeView; ///< OCIO views ("" = the config's default; wipe "" = off)
    double wipePosition = 0.5;
    int width = 1280, height = 720;
    bool hud = true;
    bool headless = false; ///< EGL, no window (benchmarks on a machine without a display)
    /// Scripted (reproducible) stepping: autopilot or a fixed frame count.
    bool scripted() const { return autopilot || frames > 0; }
};

/// Parses argv; --help prints the usage and sets help. Throws UsageError.
Options parseOptions(int argc, char** argv);

} // namespace pacifica::game
