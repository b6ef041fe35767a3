// FlightPath: a recorded or scripted camera flight, read from the CSV format in docs/FLIGHT_FORMAT.md,
// sampled at any time by interpolating between its timed poses, together with the scene events the same
// file carries (explosions on the sea, ships with timed tracks). It is the tools' data boundary for
// flights: malformed files are reported as a FlightError that names the file and the 1-based line, so a
// demo or capture run fails with a message a person can act on instead of rendering a wrong flight.
//
// Usage:
//   1. FlightPath path = FlightPath::load("tools/data/demo_flight.csv");   // throws FlightError
//   2. for (double t = path.startTime(); t <= path.endTime(); t += dt) {
//          pacifica::Pose pose = path.poseAt(t);                            // clamps t to the flight
//          ...
//      }
//   3. Events (optional in a file; their times may lie outside [startTime(), endTime()]):
//        for (const ExplosionEvent& e : path.explosions()) { ... }     // sorted by time
//        for (const ShipTrack& ship : path.ships()) {                  // in order of first appearance
//            glm::dvec2 p = ship.positionAt(t);                        // clamps t to the track
//            double heading = ship.headingAt(t);                       // compass degrees, [0, 360)
//        }
#pragma once

#include <engine/Pose.h>

#include <glm/glm.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pacifica::tools {

/// One line of a flight file: a time in seconds and the pose at that time (world ENU metres, degrees).
struct FlightSample {
    double time = 0.0;
    Pose pose;
};

/// An `explosion` record: a charge going off at the sea surface (z = 0) at a time and place.
struct ExplosionEvent {
    double time = 0.0;     ///< seconds, on the flight's clock (may lie outside the camera's time span)
    double x = 0.0;        ///< metres east (world ENU)
    double y = 0.0;        ///< metres north (world ENU)
    double strength = 1.0; ///< > 0, proportional to the charge: 1 = a nominal ~500 kg charge, 2 = twice that
    int line = 0;          ///< 1-based line of the record in the file, for messages
};

/// One `ship` record: where a ship is (at sea level) at a time.
struct ShipSample {
    double time = 0.0; ///< seconds, on the flight's clock
    double x = 0.0;    ///< metres east (world ENU)
    double y = 0.0;    ///< metres north (world ENU)
};

/// A ship's timed track: all `ship` records with one id, in file order (at least two, strictly increasing
/// times). Between samples the ship moves in a straight line at constant speed.
struct ShipTrack {
    std::string id;                  ///< [A-Za-z0-9_-]+, unique within the file
    std::vector<ShipSample> samples; ///< strictly increasing time, at least two
    int line = 0;                    ///< 1-based line of the ship's first record

    /// Time of the first sample, seconds.
    double startTime() const { return samples.front().time; }
    /// Time of the last sample, seconds.
    double endTime() const { return samples.back().time; }

    /// Position (x east, y north, metres) at time t, interpolated linearly between the enclosing samples;
    /// t is clamped to [startTime(), endTime()] (NaN gives the first position).
    glm::dvec2 positionAt(double t) const;

    /// Velocity (metres per second, east and north) at time t: that of the segment [a, b) with
    /// a.time <= t < b.time -- so at a sample's exact time, the segment that starts there -- and at
    /// endTime() that of the last segment. Before startTime() and after endTime() (and for NaN) it is zero,
    /// matching the clamped positionAt().
    glm::dvec2 velocityAt(double t) const;

    /// Compass heading the ship points to at time t, degrees in [0, 360) (0 = north, 90 = east): the
    /// direction of the segment that velocityAt() picks, with t clamped like positionAt() (so the first
    /// segment's heading before the track, the last one's after it). A segment without movement keeps the
    /// heading of the latest moving segment before it (or, if there is none, of the first moving one after
    /// it); a ship that never moves heads 0.
    double headingAt(double t) const;
};

/// A flight file could not be read or is malformed. what() is "FILE:LINE: message", or "FILE: message"
/// when the problem is not about one line (missing file, no header, too few samples).
class FlightError : public std::runtime_error {
public:
    /// line is 1-based; 0 means "not about a line" and is left out of what().
    FlightError(const std::string& file, int line, const std::string& message);

    /// The file (or source name) the error is about.
    const std::string& file() const { return mFile; }
    /// The 1-based line the error is about, or 0.
    int line() const { return mLine; }
    /// The message without the "FILE:LINE: " prefix.
    const std::string& message() const { return mMessage; }

private:
    std::string mFile;
    int mLine = 0;
    std::string mMessage;
};

/// A validated flight: at least two camera samples with strictly increasing times and finite values, plus
/// any number of validated explosion and ship records.
class FlightPath {
public:
    /// Reads and parses a flight file. Throws FlightError ("cannot open flight file", or any parse error
    /// of parse()) naming the path.
    static FlightPath load(const std::filesystem::path& path);

    /// Parses flight CSV text. sourceName is used only in error messages (usually the file name).
    /// Throws FlightError on the first problem found.
    static FlightPath parse(std::string_view text, const std::string& sourceName);

    /// Time of the first sample, seconds.
    double startTime() const { return mSamples.front().time; }
    /// Time of the last sample, seconds.
    double endTime() const { return mSamples.back().time; }
    /// All samples in file order (strictly increasing time, at least two).
    const std::vector<FlightSample>& samples() const { return mSamples; }

    /// The pose at time t: t is clamped to [startTime(), endTime()] (NaN gives the start pose), the
    /// enclosing pair of samples is found by binary search and blended with interpolatePose().
    Pose poseAt(double t) const;

    /// Every `explosion` record, sorted by time; records with equal times keep their file order.
    const std::vector<ExplosionEvent>& explosions() const { return mExplosions; }
    /// Every ship, in order of its first `ship` record in the file.
    const std::vector<ShipTrack>& ships() const { return mShips; }

private:
    FlightPath(std::vector<FlightSample> samples, std::vector<ExplosionEvent> explosions,
               std::vector<ShipTrack> ships)
        : mSamples(std::move(samples)), mExplosions(std::move(explosions)), mShips(std::move(ships)) {}

    std::vector<FlightSample> mSamples;
    std::vector<ExplosionEvent> mExplosions;
    std::vector<ShipTrack> mShips;
};

} // namespace pacifica::tools
