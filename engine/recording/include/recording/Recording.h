// Recording: a recorded flight session as objects with timed geodetic tracks and events, read from the
// formats flight-sim and glider pilots record with -- Tacview ACMI 2.x (text and zip) and IGC -- by one
// entry point that detects the format from the content (never the file name). The CLI, the game and the
// tests link this library (pacifica_recording); placing objects in the renderer's world is EarthFrame.h,
// turning objects into cameras is CameraRig.h, and what drives the sea is SeaDrivers.h.
//
// Usage:
//   1. Recording rec = readRecording("flight.acmi");         // throws RecordingError "FILE:LINE: field: ..."
//   2. for (const RecordedObject& o : rec.objects)           // in order of first appearance
//          ObjectSample s = o.sampleAt(t);                   // geodetic, interpolated, clamped to the track
//   3. rec.events: ACMI `Event=` lines (Destroyed, Timeout, ...), sorted by time.
//
// Times are seconds on the recording's clock (ACMI: relative to ReferenceTime; IGC: from the first fix),
// longitudes and latitudes absolute degrees (WGS84), altitudes metres above mean sea level.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pacifica::recording {

/// A recording could not be read. what() is "FILE:LINE: FIELD: message" (LINE and FIELD left out when the
/// problem is not about one line or one field).
class RecordingError : public std::runtime_error {
public:
    RecordingError(const std::string& file, long long line, const std::string& field,
                   const std::string& message);
    const std::string& file() const { return mFile; }
    long long line() const { return mLine; }
    const std::string& field() const { return mField; }
    const std::string& message() const { return mMessage; }

private:
    std::string mFile, mField, mMessage;
    long long mLine = 0;
};

/// One timed state of an object. Angles in degrees: roll right wing down positive, pitch nose up positive,
/// yaw = true heading (clockwise from true north at the object).
struct ObjectSample {
    double time = 0.0;
    double lon = 0.0; ///< degrees east, absolute
    double lat = 0.0; ///< degrees north, absolute
    double alt = 0.0; ///< metres above mean sea level
    float roll = 0.0f, pitch = 0.0f, yaw = 0.0f;
};

struct RecordedObject {
    uint64_t id = 0;
    std::string type; ///< ACMI tags joined by '+', e.g. "Sea+Watercraft+Warship"
    std::string name, pilot, callsign, coalition, color, group;
    double length = 0.0;               ///< metres, the ACMI Length property (0 = not given)
    std::vector<ObjectSample> track;   ///< sorted by time (stable); may be empty
    std::optional<double> removedAt;   ///< time of the `-id` line
    std::optional<double> destroyedAt; ///< time of the first Destroyed event naming it
    /// Where roll/pitch/yaw came from: "recorded" (ACMI 6/9-field T=), "derived" (from the track:
    /// heading from velocity, pitch from climb, coordinated-turn bank; deriveAttitude(), as for IGC), or
    /// "none" (ACMI 3/5-field T= only: angles 0 until deriveAttitude() is called; WorldTrack does).
    std::string attitude = "none";
    long long line = 0; ///< 1-based line of the object's first appearance

    /// Whether `tag` is one of the '+'-separated tags of type (case-sensitive, as ACMI writes them).
    bool hasTag(std::string_view tag) const;
    double startTime() const { return track.empty() ? 0.0 : track.front().time; }
    double endTime() const { return track.empty() ? 0.0 : track.back().time; }
    /// State at time t: positions interpolated linearly, angles along the shortest arc; t clamped to the
    /// track (NaN gives the first sample). Requires a non-empty track.
    ObjectSample sampleAt(double t) const;
    /// A label for messages and listings: "d01 Air+FixedWing 'F-14B' pilot 'Nuevo apodo'".
    std::string describe() const;
};

struct RecordedEvent {
    double time = 0.0;
    std::string type; ///< "Destroyed", "Timeout", ... (unknown types are kept)
    std::vector<uint64_t> objects;
    std::string text;
    long long line = 0;
};

struct Recording {
    std::string source; ///< the file as given
    std::string format; ///< "acmi-text", "acmi-zip", "igc"
    std::string fileVersion;
    double referenceLongitude = 0.0, referenceLatitude = 0.0;
    std::string referenceTime;           ///< ISO 8601 UTC as in the file ("" if absent)
    std::optional<double> referenceUnix; ///< referenceTime in seconds since 1970 (UTC), if it parsed
    std::string title;
    /// IGC: the GNSS altitude datum the logger declares (HFALGALTGPS): "GEO" (geoid, i.e. MSL), "ELL" (WGS84
    /// ellipsoid: taken as MSL here, no geoid model is packaged; the geoid undulation is -106..+85 m), or "".
    std::string altitudeDatum;
    std::vector<RecordedObject> objects;   ///< in order of first appearance
    std::vector<RecordedEvent> events;     ///< sorted by time (stable)
    double startTime = 0.0, endTime = 0.0; ///< over every sample and event
    uint64_t bytes = 0;                    ///< decoded text bytes read
    long long lines = 0;                   ///< physical lines read
    long long samples = 0;                 ///< track samples kept, all objects

    /// The object with this id (the latest one if an id was reused after a removal), or nullptr.
    const RecordedObject* find(uint64_t id) const;
};

/// What a recording may hold. A file built to exhaust memory or time (a zip member that inflates to many GB,
/// 10^7 object ids, a 1 GB line, a 3 GB IGC) is refused with a RecordingError naming the limit as soon as it
/// is passed, so a read holds at most MAX_SAMPLES samples (48 bytes each, twice that while a track grows),
/// MAX_OBJECTS objects and one MAX_LINE_BYTES line. Real recordings sit far below: the 220 s DCS recording of
/// docs/RECORDINGS.md has 14 objects and ~7 000 samples; a 2-hour mission of 300 objects sampled at 10 Hz
/// has ~2 x 10^7. docs/RELIABILITY.md ("Hostile inputs") gives what each refusal costs.
struct RecordingLimits {
    static constexpr uint64_t MAX_TEXT_BYTES = uint64_t(4) << 30; ///< decoded ACMI text, zip members inflated
    static constexpr size_t MAX_LINE_BYTES = size_t(1) << 20;     ///< one line, '\\' continuations joined
    static constexpr size_t MAX_OBJECTS = 1000000;                ///< objects (an id reused after removal: 2)
    static constexpr long long MAX_SAMPLES = 25000000;            ///< track samples, all objects together
    /// An IGC file: 7 x 10^6 one-second fixes.
    static constexpr uint64_t MAX_IGC_BYTES = uint64_t(256) << 20;
};

/// Reads a recording, detecting the format from the content: ACMI text (`FileType=text/acmi/tacview`,
/// UTF-8 BOM allowed), zip (`PK` magic; one `.acmi`/`.txt` member, streamed), IGC (first record `A...` and
/// B fixes). Anything else -- including a 7z-wrapped ACMI -- is a RecordingError that lists the supported
/// formats. The project's CSV flight format is read by tools/src/FlightPath.h; isFlightCsv() tells it apart.
Recording readRecording(const std::filesystem::path& file);

/// The formats readRecording() understands, for messages: "Tacview ACMI 2.x text, Tacview ACMI zip, IGC".
std::string supportedFormats();

/// What a file's first bytes say it is: "acmi-text", "acmi-zip", "igc", "csv" (the project's flight
/// CSV: a `time_s,` header after comments), "7z", or "" (unknown). Reads at most a few kB.
std::string detectFormat(const std::filesystem::path& file);

/// Streaming ACMI text parser: feed() any chunks of the decoded text, then finish(). Memory is the kept
/// tracks plus one line. Used by readRecording(); exposed for tests, fuzzers and benchmarks.
class AcmiParser {
public:
    explicit AcmiParser(std::string sourceName);
    ~AcmiParser();
    AcmiParser(const AcmiParser&) = delete;
    AcmiParser& operator=(const AcmiParser&) = delete;
    void feed(std::string_view chunk);
    Recording finish();

private:
    struct Impl;
    Impl* mImpl;
};

/// Parses a whole IGC file's text (ISO-8859-1 or UTF-8 H records). sourceName is used in messages.
Recording parseIgc(std::string_view text, const std::string& sourceName);

/// Fills roll/pitch/yaw of every sample from the track (object.attitude = "derived"): heading from the
/// horizontal velocity, pitch from the climb angle, bank from the coordinated turn atan(v w / g), each
/// smoothed over smoothingSeconds (a Gaussian window, so 1 Hz GPS noise does not shake the camera).
void deriveAttitude(RecordedObject& object, double smoothingSeconds = 2.0);

/// An object id as ACMI writes it: lowercase hex without a prefix ("d01").
std::string hexId(uint64_t id);

/// Parses "YYYY-MM-DDTHH:MM:SS[.fff]Z" (UTC) into seconds since 1970; nullopt if it does not parse.
std::optional<double> parseIsoUtc(std::string_view text);

} // namespace pacifica::recording
