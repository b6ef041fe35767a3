// FlightPath: a recorded or scripted camera flight, read from the CSV format in docs/FLIGHT_FORMAT.md,
// sampled at any time by interpolating between its timed poses. It is the tools' data boundary for
// flights: malformed files are reported as a FlightError that names the file and the 1-based line, so a
// demo or capture run fails with a message a person can act on instead of rendering a wrong flight.
//
// Usage:
//   1. FlightPath path = FlightPath::load("tools/data/demo_flight.csv");   // throws FlightError
//   2. for (double t = path.startTime(); t <= path.endTime(); t += dt) {
//          pacifica::Pose pose = path.poseAt(t);                            // clamps t to the flight
//          ...
//      }
#pragma once

#include <engine/Pose.h>

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

/// A validated flight: at least two samples with strictly increasing times and finite values.
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

private:
    explicit FlightPath(std::vector<FlightSample> samples) : mSamples(std::move(samples)) {}

    std::vector<FlightSample> mSamples;
};

} // namespace pacifica::tools
