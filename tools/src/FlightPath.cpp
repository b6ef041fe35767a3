// FlightPath parsing and sampling. The parser walks the text line by line (1-based physical line numbers,
// counting comments and blank lines, so an editor's "go to line" lands on the culprit), validates the
// header and every field, and parses numbers with std::from_chars so the result never depends on the
// process locale (a German locale would otherwise read "1.5" as 1). A line whose first field is a number is a
// camera sample; one whose first field is a word is an event record (`explosion`, `ship`), so files written
// before events existed read exactly as before. See docs/FLIGHT_FORMAT.md.
#include "FlightPath.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <numbers>
#include <system_error>
#include <unordered_map>
#include <utility>

namespace pacifica::tools {

namespace {

constexpr int FIELD_COUNT = 7;
constexpr std::array<std::string_view, FIELD_COUNT> COLUMN_NAMES = {
    "time_s", "x_m", "y_m", "z_m", "heading_deg", "pitch_deg", "roll_deg"};
constexpr std::string_view HEADER = "time_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg";
constexpr std::string_view UTF8_BOM = "\xEF\xBB\xBF";

std::string_view trim(std::string_view s) {
    const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
    while (!s.empty() && isSpace(s.front())) {
        s.remove_prefix(1);
    }
    while (!s.empty() && isSpace(s.back())) {
        s.remove_suffix(1);
    }
    return s;
}

std::vector<std::string_view> splitFields(std::string_view line) {
    std::vector<std::string_view> fields;
    size_t begin = 0;
    while (true) {
        const size_t comma = line.find(',', begin);
        if (comma == std::string_view::npos) {
            fields.push_back(trim(line.substr(begin)));
            return fields;
        }
        fields.push_back(trim(line.substr(begin, comma - begin)));
        begin = comma + 1;
    }
}

// Shortest text that reads back as the same double, for error messages.
std::string formatNumber(double v) {
    std::array<char, 32> buf{};
    const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    return std::string(buf.data(), res.ptr);
}

// Reads a double with from_chars, accepting a leading '+' (from_chars rejects it, but spreadsheets write it).
// Returns the error code, and whether the whole field was consumed.
std::pair<std::errc, bool> readDouble(std::string_view field, double& value) {
    if (field.size() > 1 && field.front() == '+' && field[1] != '+' && field[1] != '-') {
        field.remove_prefix(1);
    }
    const char* end = field.data() + field.size();
    const auto [ptr, ec] = std::from_chars(field.data(), end, value);
    return {ec, ptr == end};
}

// Parses one numeric field; the whole field must be consumed. "nan"/"inf" parse and are then rejected as not
// finite. `what` names the field in messages: "field 'z_m'" for camera samples, "explosion field 'strength'"
// for event records.
double parseNumber(std::string_view field, const std::string& what, const std::string& source, int lineNo) {
    double value = 0.0;
    const auto [ec, whole] = readDouble(field, value);
    if (ec == std::errc::result_out_of_range) {
        throw FlightError(source, lineNo, what + " is out of range: '" + std::string(field) + "'");
    }
    if (ec != std::errc() || !whole) {
        throw FlightError(source, lineNo, what + " is not a number: '" + std::string(field) + "'");
    }
    if (!std::isfinite(value)) {
        throw FlightError(source, lineNo, what + " is not finite");
    }
    return value;
}

double parseField(std::string_view field, int column, const std::string& source, int lineNo) {
    return parseNumber(field, "field '" + std::string(COLUMN_NAMES[static_cast<size_t>(column)]) + "'",
                       source, lineNo);
}

double parseRecordField(std::string_view field, std::string_view record, std::string_view name,
                        const std::string& source, int lineNo) {
    return parseNumber(field, std::string(record) + " field '" + std::string(name) + "'", source, lineNo);
}

bool isAsciiLetter(char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}
bool isAsciiDigit(char c) {
    return c >= '0' && c <= '9';
}

// True if the whole field reads as a number (finite or not, in range or not), as parseNumber() reads it.
bool readsAsNumber(std::string_view field) {
    double value = 0.0;
    const auto [ec, whole] = readDouble(field, value);
    return (ec == std::errc() || ec == std::errc::result_out_of_range) && whole;
}

// A record keyword is a word (a letter, then letters, digits or '_') that is not a spelling of a number
// ("nan", "inf"); anything else in the first field is a camera sample's time_s and gets its errors.
bool isRecordKeyword(std::string_view field) {
    if (field.empty() || !isAsciiLetter(field.front())) {
        return false;
    }
    for (char c : field) {
        if (!isAsciiLetter(c) && !isAsciiDigit(c) && c != '_') {
            return false;
        }
    }
    return !readsAsNumber(field);
}

bool isValidShipId(std::string_view id) {
    if (id.empty()) {
        return false;
    }
    for (char c : id) {
        if (!isAsciiLetter(c) && !isAsciiDigit(c) && c != '_' && c != '-') {
            return false;
        }
    }
    return true;
}

constexpr size_t EXPLOSION_FIELD_COUNT = 5;
constexpr size_t SHIP_FIELD_COUNT = 5;

ExplosionEvent parseExplosion(const std::vector<std::string_view>& fields, const std::string& source,
                              int lineNo) {
    if (fields.size() != EXPLOSION_FIELD_COUNT) {
        throw FlightError(source, lineNo,
                          "explosion record: expected " + std::to_string(EXPLOSION_FIELD_COUNT) +
                              " fields (explosion,time_s,x_m,y_m,strength), got " +
                              std::to_string(fields.size()));
    }
    ExplosionEvent e;
    e.time = parseRecordField(fields[1], "explosion", "time_s", source, lineNo);
    e.x = parseRecordField(fields[2], "explosion", "x_m", source, lineNo);
    e.y = parseRecordField(fields[3], "explosion", "y_m", source, lineNo);
    e.strength = parseRecordField(fields[4], "explosion", "strength", source, lineNo);
    if (!(e.strength > 0.0)) {
        throw FlightError(source, lineNo,
                          "explosion field 'strength' must be > 0, got " + formatNumber(e.strength));
    }
    e.line = lineNo;
    return e;
}

// Heading (compass degrees in [0, 360)) of the displacement from a to b; only for a != b.
double compassHeading(const ShipSample& a, const ShipSample& b) {
    const double deg = std::atan2(b.x - a.x, b.y - a.y) * (180.0 / std::numbers::pi);
    const double wrapped = deg < 0.0 ? deg + 360.0 : deg;
    return wrapped >= 360.0 ? 0.0 : wrapped;
}

bool segmentMoves(const ShipSample& a, const ShipSample& b) {
    return a.x != b.x || a.y != b.y;
}

// Index i of the segment [samples[i], samples[i + 1]] holding t, for t within [first time, last time]:
// a.time <= t < b.time, and the last segment at the last time.
size_t segmentIndex(const std::vector<ShipSample>& samples, double t) {
    const auto after = std::upper_bound(samples.begin(), samples.end(), t,
                                        [](double time, const ShipSample& s) { return time < s.time; });
    const size_t index = static_cast<size_t>(after - samples.begin());
    return std::clamp<size_t>(index, 1, samples.size() - 1) - 1;
}

} // namespace

FlightError::FlightError(const std::string& file, int line, const std::string& message)
    : std::runtime_error(line > 0 ? file + ":" + std::to_string(line) + ": " + message
                                  : file + ": " + message),
      mFile(file), mLine(line), mMessage(message) {}

FlightPath FlightPath::load(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) {
        throw FlightError(name, 0, "cannot open flight file: no such file");
    }
    if (std::filesystem::is_directory(status)) {
        throw FlightError(name, 0, "cannot open flight file: it is a directory");
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw FlightError(name, 0, std::string("cannot open flight file: ") + std::strerror(errno));
    }
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad()) {
        throw FlightError(name, 0, "cannot open flight file: read error");
    }
    return parse(text, name);
}

namespace {

/// The CSV's records as they are read, each checked with the line it came from (FlightError names it).
struct CsvRecords {
    const std::string& sourceName;
    std::vector<FlightSample> samples;
    std::vector<ExplosionEvent> explosions;
    std::vector<ShipTrack> ships;
    std::vector<int> shipLastLine; // per ship: line of its latest record, for the time-order message
    std::unordered_map<std::string, size_t> shipIndex;
    int previousLineNo = 0;

    void header(const std::vector<std::string_view>& fields, std::string_view line, int lineNo) const {
        bool matches = fields.size() == COLUMN_NAMES.size();
        for (size_t i = 0; matches && i < fields.size(); ++i)
            matches = fields[i] == COLUMN_NAMES[i];
        if (!matches)
            throw FlightError(sourceName, lineNo,
                              "expected header '" + std::string(HEADER) + "', got '" + std::string(line) +
                                  "'");
    }

    void ship(const std::vector<std::string_view>& fields, int lineNo) {
        if (fields.size() != SHIP_FIELD_COUNT)
            throw FlightError(sourceName, lineNo,
                              "ship record: expected " + std::to_string(SHIP_FIELD_COUNT) +
                                  " fields (ship,id,time_s,x_m,y_m), got " + std::to_string(fields.size()));
        const std::string_view id = fields[1];
        if (!isValidShipId(id))
            throw FlightError(sourceName, lineNo,
                              "ship id must match [A-Za-z0-9_-]+, got '" + std::string(id) + "'");
        ShipSample sample;
        sample.time = parseRecordField(fields[2], "ship", "time_s", sourceName, lineNo);
        sample.x = parseRecordField(fields[3], "ship", "x_m", sourceName, lineNo);
        sample.y = parseRecordField(fields[4], "ship", "y_m", sourceName, lineNo);
        const auto [it, inserted] = shipIndex.try_emplace(std::string(id), ships.size());
        if (inserted) {
            ShipTrack track;
            track.id = std::string(id);
            track.line = lineNo;
            ships.push_back(std::move(track));
            shipLastLine.push_back(lineNo);
        }
        ShipTrack& track = ships[it->second];
        if (!track.samples.empty() && !(sample.time > track.samples.back().time))
            throw FlightError(sourceName, lineNo,
                              "ship '" + track.id +
                                  "': time_s must be strictly increasing: " + formatNumber(sample.time) +
                                  " does not follow " + formatNumber(track.samples.back().time) + " (line " +
                                  std::to_string(shipLastLine[it->second]) + ")");
        track.samples.push_back(sample);
        shipLastLine[it->second] = lineNo;
    }

    void record(const std::vector<std::string_view>& fields, int lineNo) {
        if (fields[0] == "explosion")
            explosions.push_back(parseExplosion(fields, sourceName, lineNo));
        else if (fields[0] == "ship")
            ship(fields, lineNo);
        else
            throw FlightError(sourceName, lineNo,
                              "unknown record '" + std::string(fields[0]) +
                                  "': expected a camera sample (a number first), 'explosion' or 'ship'");
    }

    void camera(const std::vector<std::string_view>& fields, int lineNo) {
        if (fields.size() != static_cast<size_t>(FIELD_COUNT))
            throw FlightError(sourceName, lineNo,
                              "expected " + std::to_string(FIELD_COUNT) + " fields, got " +
                                  std::to_string(fields.size()));
        std::array<double, FIELD_COUNT> v{};
        for (int i = 0; i < FIELD_COUNT; ++i)
            v[static_cast<size_t>(i)] = parseField(fields[static_cast<size_t>(i)], i, sourceName, lineNo);
        FlightSample sample;
        sample.time = v[0];
        sample.pose.position = glm::dvec3(v[1], v[2], v[3]);
        sample.pose.headingDeg = v[4];
        sample.pose.pitchDeg = v[5];
        sample.pose.rollDeg = v[6];
        // Beyond +-90 degrees the same attitude has a second (heading+180, roll+180) spelling; one
        // spelling per attitude keeps interpolation and the file's meaning unambiguous.
        if (std::abs(sample.pose.pitchDeg) > 90.0)
            throw FlightError(sourceName, lineNo,
                              "field 'pitch_deg' must be within [-90, 90], got " +
                                  formatNumber(sample.pose.pitchDeg));
        if (!samples.empty() && !(sample.time > samples.back().time))
            throw FlightError(sourceName, lineNo,
                              "time_s must be strictly increasing: " + formatNumber(sample.time) +
                                  " does not follow " + formatNumber(samples.back().time) + " (line " +
                                  std::to_string(previousLineNo) + ")");
        samples.push_back(sample);
        previousLineNo = lineNo;
    }

    /// The whole file's checks; then explosions in time order (stable: explosions at the same time keep
    /// their file order, so a replay is deterministic).
    void finish(bool haveHeader) {
        if (!haveHeader)
            throw FlightError(sourceName, 0,
                              "empty flight file: expected header '" + std::string(HEADER) + "'");
        if (samples.size() < 2)
            throw FlightError(sourceName, 0,
                              "expected at least 2 samples, got " + std::to_string(samples.size()));
        for (const ShipTrack& ship : ships)
            if (ship.samples.size() < 2)
                throw FlightError(sourceName, ship.line,
                                  "ship '" + ship.id + "' has " + std::to_string(ship.samples.size()) +
                                      " sample, expected at least 2");
        std::stable_sort(explosions.begin(), explosions.end(),
                         [](const ExplosionEvent& a, const ExplosionEvent& b) { return a.time < b.time; });
    }
};

} // namespace

FlightPath FlightPath::parse(std::string_view text, const std::string& sourceName) {
    if (text.starts_with(UTF8_BOM))
        text.remove_prefix(UTF8_BOM.size());
    CsvRecords r{sourceName};
    bool haveHeader = false;
    int lineNo = 0;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t newline = text.find('\n', pos);
        if (newline == std::string_view::npos)
            newline = text.size();
        const std::string_view line = trim(text.substr(pos, newline - pos));
        pos = newline + 1;
        ++lineNo;
        if (line.empty() || line.front() == '#')
            continue;
        const std::vector<std::string_view> fields = splitFields(line);
        if (!haveHeader) {
            r.header(fields, line, lineNo);
            haveHeader = true;
        } else if (isRecordKeyword(fields[0])) {
            r.record(fields, lineNo);
        } else {
            r.camera(fields, lineNo);
        }
    }
    r.finish(haveHeader);
    return FlightPath(std::move(r.samples), std::move(r.explosions), std::move(r.ships));
}

Pose FlightPath::poseAt(double t) const {
    if (!(t > mSamples.front().time)) { // also catches NaN
        return mSamples.front().pose;
    }
    if (t >= mSamples.back().time) {
        return mSamples.back().pose;
    }
    // First sample strictly after t; the clamps above guarantee 1 <= index < size.
    const auto after = std::upper_bound(mSamples.begin(), mSamples.end(), t,
                                        [](double time, const FlightSample& s) { return time < s.time; });
    const FlightSample& b = *after;
    const FlightSample& a = *std::prev(after);
    const double s = (t - a.time) / (b.time - a.time);
    return interpolatePose(a.pose, b.pose, s);
}

glm::dvec2 ShipTrack::positionAt(double t) const {
    if (!(t > samples.front().time)) { // also catches NaN
        return {samples.front().x, samples.front().y};
    }
    if (t >= samples.back().time) {
        return {samples.back().x, samples.back().y};
    }
    const size_t i = segmentIndex(samples, t);
    const ShipSample& a = samples[i];
    const ShipSample& b = samples[i + 1];
    const double s = (t - a.time) / (b.time - a.time);
    return {a.x + (b.x - a.x) * s, a.y + (b.y - a.y) * s};
}

glm::dvec2 ShipTrack::velocityAt(double t) const {
    if (!(t >= samples.front().time && t <= samples.back().time)) { // outside, or NaN
        return {0.0, 0.0};
    }
    const size_t i = segmentIndex(samples, t);
    const ShipSample& a = samples[i];
    const ShipSample& b = samples[i + 1];
    const double dt = b.time - a.time;
    return {(b.x - a.x) / dt, (b.y - a.y) / dt};
}

double ShipTrack::headingAt(double t) const {
    const double clamped = t > samples.front().time ? std::min(t, samples.back().time) : samples.front().time;
    const size_t segment = segmentIndex(samples, clamped);
    // A stationary segment has no direction of its own: the ship keeps pointing where it last went.
    for (size_t i = segment + 1; i-- > 0;) {
        if (segmentMoves(samples[i], samples[i + 1])) {
            return compassHeading(samples[i], samples[i + 1]);
        }
    }
    for (size_t i = segment + 1; i + 1 < samples.size(); ++i) {
        if (segmentMoves(samples[i], samples[i + 1])) {
            return compassHeading(samples[i], samples[i + 1]);
        }
    }
    return 0.0;
}

} // namespace pacifica::tools
