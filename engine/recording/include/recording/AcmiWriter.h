// AcmiWriter: writes Tacview ACMI 2.2 text (the format Acmi.cpp reads), so a game can record its sessions for
// `pacifica replay` and Tacview, and other recordings (IGC) can be converted. Transforms are delta-coded as
// Tacview writes them: a field equal to the object's previous value is left empty (ACMI: empty = unchanged).
// Positions are written with 7 decimals of a degree (~1 cm), altitudes with 2 decimals, angles with 1.
//
// Usage:
//   AcmiWriter w(out, {"2024-06-01T10:00:00Z", 36.0, 44.0, "Sortie 1"});  // header + global object
//   w.frame(0.0);
//   w.object(0x101, {{"Type", "Air+FixedWing"}, {"Name", "F-14B"}});      // properties, escaped
//   w.transform(0x101, lon, lat, alt, roll, pitch, yaw);                  // absolute degrees / metres
//   w.frame(0.1); ...; w.event("Destroyed", {0x101}, "hit"); w.remove(0x101);
#pragma once

#include "recording/Recording.h"

#include <cstdint>
#include <ostream>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace pacifica::recording {

struct AcmiHeader {
    std::string referenceTime;                                ///< ISO 8601 UTC, "" to leave out
    double referenceLongitude = 0.0, referenceLatitude = 0.0; ///< whole degrees are what Tacview writes
    std::string title;
};

class AcmiWriter {
public:
    AcmiWriter(std::ostream& out, const AcmiHeader& header);
    /// Starts a frame at time t (seconds from ReferenceTime); frames must not go back in time
    /// (std::invalid_argument).
    void frame(double t);
    /// Sets text properties of an object (Type, Name, Pilot, CallSign, Coalition, Color, ...).
    void object(uint64_t id, const std::vector<std::pair<std::string, std::string>>& properties);
    /// The object's pose: absolute longitude/latitude (degrees), altitude MSL (metres), roll/pitch/yaw
    /// (degrees). Non-finite values: std::invalid_argument (a recording is never written with NaN).
    void transform(uint64_t id, double lon, double lat, double alt, double roll, double pitch, double yaw);
    /// Position only (3-field T=): for objects without a recorded attitude.
    void transform(uint64_t id, double lon, double lat, double alt);
    void remove(uint64_t id);
    void event(const std::string& type, const std::vector<uint64_t>& ids, const std::string& text);

    /// "\," for commas and "\" + newline for line breaks, as ACMI escapes property values.
    static std::string escape(const std::string& value);

private:
    void writeTransform(uint64_t id, const double* v, int n);
    struct Last {
        std::string fields[6];
    };
    std::ostream& mOut;
    AcmiHeader mHeader;
    double mTime = -1e300;
    bool mFrameWritten = false;
    std::unordered_map<uint64_t, Last> mLast;
};

/// Writes a whole recording: every object's track (merged by time, one frame line per distinct time), its
/// properties on first appearance, its removal, and the events.
void writeAcmi(const Recording& rec, std::ostream& out);

} // namespace pacifica::recording
