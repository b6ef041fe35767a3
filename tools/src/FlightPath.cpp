// FlightPath parsing and sampling. The parser walks the text line by line (1-based physical line numbers,
// counting comments and blank lines, so an editor's "go to line" lands on the culprit), validates the
// header and every field, and parses numbers with std::from_chars so the result never depends on the
// process locale (a German locale would otherwise read "1.5" as 1). See docs/FLIGHT_FORMAT.md.
#include "FlightPath.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>
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

// Parses one numeric field; the whole field must be consumed. A leading '+' is accepted (from_chars
// rejects it, but spreadsheets write it). "nan"/"inf" parse and are then rejected as not finite.
double parseField(std::string_view field, int column, const std::string& source, int lineNo) {
    const std::string_view name = COLUMN_NAMES[static_cast<size_t>(column)];
    std::string_view digits = field;
    if (digits.size() > 1 && digits.front() == '+' && digits[1] != '+' && digits[1] != '-') {
        digits.remove_prefix(1);
    }
    double value = 0.0;
    const char* end = digits.data() + digits.size();
    const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
    if (ec == std::errc::result_out_of_range) {
        throw FlightError(source, lineNo,
                          "field '" + std::string(name) + "' is out of range: '" + std::string(field) + "'");
    }
    if (ec != std::errc() || ptr != end) {
        throw FlightError(source, lineNo,
                          "field '" + std::string(name) + "' is not a number: '" + std::string(field) + "'");
    }
    if (!std::isfinite(value)) {
        throw FlightError(source, lineNo, "field '" + std::string(name) + "' is not finite");
    }
    return value;
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

FlightPath FlightPath::parse(std::string_view text, const std::string& sourceName) {
    if (text.starts_with(UTF8_BOM)) {
        text.remove_prefix(UTF8_BOM.size());
    }

    std::vector<FlightSample> samples;
    bool haveHeader = false;
    int lineNo = 0;
    int previousLineNo = 0;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t newline = text.find('\n', pos);
        if (newline == std::string_view::npos) {
            newline = text.size();
        }
        const std::string_view line = trim(text.substr(pos, newline - pos));
        pos = newline + 1;
        ++lineNo;

        if (line.empty() || line.front() == '#') {
            continue;
        }

        const std::vector<std::string_view> fields = splitFields(line);
        if (!haveHeader) {
            bool matches = fields.size() == COLUMN_NAMES.size();
            for (size_t i = 0; matches && i < fields.size(); ++i) {
                matches = fields[i] == COLUMN_NAMES[i];
            }
            if (!matches) {
                throw FlightError(sourceName, lineNo,
                                  "expected header '" + std::string(HEADER) + "', got '" + std::string(line) +
                                      "'");
            }
            haveHeader = true;
            continue;
        }

        if (fields.size() != static_cast<size_t>(FIELD_COUNT)) {
            throw FlightError(sourceName, lineNo,
                              "expected " + std::to_string(FIELD_COUNT) + " fields, got " +
                                  std::to_string(fields.size()));
        }
        std::array<double, FIELD_COUNT> v{};
        for (int i = 0; i < FIELD_COUNT; ++i) {
            v[static_cast<size_t>(i)] = parseField(fields[static_cast<size_t>(i)], i, sourceName, lineNo);
        }

        FlightSample sample;
        sample.time = v[0];
        sample.pose.position = glm::dvec3(v[1], v[2], v[3]);
        sample.pose.headingDeg = v[4];
        sample.pose.pitchDeg = v[5];
        sample.pose.rollDeg = v[6];

        // Beyond +-90 degrees the same attitude has a second (heading+180, roll+180) spelling; one
        // spelling per attitude keeps interpolation and the file's meaning unambiguous.
        if (std::abs(sample.pose.pitchDeg) > 90.0) {
            throw FlightError(sourceName, lineNo,
                              "field 'pitch_deg' must be within [-90, 90], got " +
                                  formatNumber(sample.pose.pitchDeg));
        }
        if (!samples.empty() && !(sample.time > samples.back().time)) {
            throw FlightError(sourceName, lineNo,
                              "time_s must be strictly increasing: " + formatNumber(sample.time) +
                                  " does not follow " + formatNumber(samples.back().time) + " (line " +
                                  std::to_string(previousLineNo) + ")");
        }
        samples.push_back(sample);
        previousLineNo = lineNo;
    }

    if (!haveHeader) {
        throw FlightError(sourceName, 0, "empty flight file: expected header '" + std::string(HEADER) + "'");
    }
    if (samples.size() < 2) {
        throw FlightError(sourceName, 0,
                          "expected at least 2 samples, got " + std::to_string(samples.size()));
    }
    return FlightPath(std::move(samples));
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

} // namespace pacifica::tools
