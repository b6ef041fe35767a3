// ReplayInput: what `pacifica replay` renders, read from any supported flight file -- the cameras (views),
// the ships and the explosions -- so the render loop does not care whether it came from the project's CSV
// (its own camera path) or from a recording (Tacview ACMI, IGC) through camera rigs over its objects.
#pragma once

#include "FlightPath.h"
#include "ocean/Ocean.h"
#include <engine/gl/ObjectRenderer.h>

#include <recording/CameraRig.h>
#include <recording/EarthFrame.h>
#include <recording/Recording.h>
#include <recording/SeaDrivers.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pacifica::tools {

using gl::DrawnObject;
using gl::ObjectRenderer;
using gl::ObjectShape;

/// One camera of a run: its rig and its own image size and field of view.
struct ReplayView {
    std::string name; ///< file prefix ("" for a single view: frame_NNNNN.*)
    std::string rig;  ///< the spec as given ("path" for a CSV's own camera)
    int width = 640, height = 360;
    float fovYDeg = 60.0f;
    std::function<Pose(double)> camera;
    std::optional<uint64_t> hiddenObject; ///< a cockpit view does not draw the object it sits in
};

/// A recorded object drawn in the frames (ObjectRenderer), alive over [start, end].
struct ReplayObject {
    uint64_t id = 0;
    ObjectShape shape = ObjectShape::Aircraft;
    double length = 19.0;
    double start = 0.0, end = 0.0;
    std::shared_ptr<const recording::WorldTrack> track;
};

struct ReplayInput {
    std::string format;                    ///< "csv", "acmi-text", "acmi-zip", "igc"
    double startTime = 0.0, endTime = 0.0; ///< the default range (the first view's object, or the CSV)
    std::optional<double> referenceUnix;   ///< UTC of time 0, for --start/--end given as timestamps
    std::vector<ReplayView> views;
    std::vector<ShipTrack> ships;
    std::vector<double> shipLengths; ///< metres, parallel to ships
    std::vector<ExplosionEvent> explosions;
    nlohmann::json summary; ///< "recording" block of summary.json (objects per type, origin, rigs)

    // What the views' cameras refer to.
    std::shared_ptr<const FlightPath> csv;
    std::shared_ptr<const recording::Recording> recording;
    std::shared_ptr<const recording::EarthFrame> frame;
    std::vector<std::shared_ptr<const recording::CameraRig>> rigs;
};

/// Reads FLIGHT (format from its content) and builds the views from the --rig specs (empty: the CSV's path,
/// or for a recording a chase rig on its first piloted aircraft). Each view takes the default size and fov
/// unless its spec says size=WxH / fov=DEG. Throws FlightError, RecordingError, RigError or UsageError.
ReplayInput loadReplayInput(const std::filesystem::path& flight, const std::vector<std::string>& rigs,
                            int defaultWidth, int defaultHeight, float defaultFov);

/// The recording's aircraft, ships and weapons (not shells, decoys, ground units or navaids) alive at some
/// time in [start, end], with their world tracks. Empty for a CSV flight.
std::vector<ReplayObject> replayObjects(const ReplayInput& input, double start, double end);

/// The world frame a replay of this recording with these --rig specs uses: its origin is the first rig's
/// object where that object's track starts (near the action). Throws UsageError or RecordingError.
recording::EarthFrame replayEarthFrame(const recording::Recording& rec, const std::vector<std::string>& rigs,
                                       const std::filesystem::path& flight);

/// `--list-objects`: one line per object with a track: id, type, name, pilot, time span, altitude range, the
/// share of its samples at the sea surface drawn under it (`at_sea`: within recording::SEA_CONTACT_M of the
/// waves of `sea` at the sample's time and place in `frame`; every object's samples at one time are one
/// batched ocean::SeaQuery), and with the GSHHG shorelines installed the share over the sea (`over_sea`).
/// Throws UsageError when the ocean cannot be made.
std::string listObjects(const recording::Recording& rec, const recording::EarthFrame& frame,
                        const ocean::OceanDesc& sea);

/// --start/--end: seconds on the flight's clock, or a UTC timestamp (YYYY-MM-DDTHH:MM:SS[.f]Z) when the
/// recording has a reference time. Throws UsageError naming the option.
double parseTimeArgument(const std::string& text, const std::optional<double>& referenceUnix,
                         const std::string& option);

} // namespace pacifica::tools
