// Tacview ACMI 2.x text parser, streaming (Tacview's "ACMI 2.2 file format" reference; the edge cases seen in
// real DCS exports are handled below and tested in tests/unit/test_recording.cpp). Lines are joined before
// they are classified (a line ending in an odd number of '\' continues on the next one), so a continued
// Comments or Briefing block is never mistaken for a frame, a removal or an object. Numbers go through
// std::from_chars (no locale). Properties the replay does not use are skipped without being copied; unknown
// ones are never fatal. Memory: the tracks kept plus the current line.
#include "recording/Recording.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <vector>

namespace pacifica::recording {

namespace {

constexpr std::string_view UTF8_BOM = "\xEF\xBB\xBF";

bool parseHexId(std::string_view s, uint64_t& id) {
    if (s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X'))
        s.remove_prefix(2);
    if (s.empty() || s.size() > 16)
        return false;
    uint64_t v = 0;
    for (const char c : s) {
        unsigned d = 0;
        if (c >= '0' && c <= '9')
            d = static_cast<unsigned>(c - '0');
        else if (c >= 'a' && c <= 'f')
            d = static_cast<unsigned>(c - 'a' + 10);
        else if (c >= 'A' && c <= 'F')
            d = static_cast<unsigned>(c - 'A' + 10);
        else
            return false;
        v = v << 4 | d;
    }
    id = v;
    return true;
}

/// Removes the ACMI escapes: "\," -> ",", "\\" -> "\" (a joined continuation is already a newline).
std::string unescape(std::string_view v) {
    std::string out;
    out.reserve(v.size());
    for (size_t i = 0; i < v.size(); ++i) {
        if (v[i] == '\\' && i + 1 < v.size() && (v[i + 1] == ',' || v[i + 1] == '\\'))
            ++i;
        out.push_back(v[i]);
    }
    return out;
}

/// "[-]digits[.digits]" with at most 15 significant digits and 22 decimals: the mantissa and 10^k are exact
/// doubles, so one division is correctly rounded and equals std::from_chars (Clinger 1990, "How to read
/// floating point numbers accurately", the fast path). ACMI numbers are nearly all of this form; anything
/// else (exponents, long mantissas, nan) returns false and goes through from_chars. scanDecimal() reads one
/// at pos and stops at a '|' (a T= field separator) or the end, advancing pos only on success.
/// Appends the run of decimal digits at p to mantissa (mantissa = mantissa * 10^k + digits), eight bytes at
/// a time where eight are readable: SWAR digit test and conversion after Lemire, "Number Parsing at a
/// Gigabyte per Second" (Software: Practice and Experience 51(8), 2021), section 5 — the first non-digit
/// byte is the lowest byte with ((c ^ '0') + 0x76 | (c ^ '0')) & 0x80 set, and three multiplies turn the
/// digits into their value. The byte loop finishes what is left.
[[gnu::always_inline]] inline void readDigits(const char*& p, const char* end, uint64_t& mantissa) {
    static constexpr uint64_t POW10_INT[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};
    while (end - p >= 8) {
        uint64_t w = 0;
        std::memcpy(&w, p, 8);
        const uint64_t a = w ^ 0x3030303030303030ull; // digit bytes become 0..9
        const uint64_t nonDigit = ((a + 0x7676767676767676ull) | a) & 0x8080808080808080ull;
        const int k = nonDigit ? __builtin_ctzll(nonDigit) / 8 : 8;
        if (k == 0)
            return;
        uint64_t v = a << (8 * (8 - k)); // the k digits in the high bytes, zeros before them
        v = v * 10 + (v >> 8);           // pairs 10*d[i] + d[i+1] in bytes 0, 2, 4, 6
        v = (((v & 0x000000FF000000FFull) * (100 + (1000000ull << 32))) +
             (((v >> 16) & 0x000000FF000000FFull) * (1 + (10000ull << 32)))) >>
            32;
        mantissa = mantissa * POW10_INT[k] + v;
        p += k;
        if (k < 8)
            return;
    }
    while (p != end && static_cast<unsigned>(*p - '0') < 10u)
        mantissa = mantissa * 10 + static_cast<uint64_t>(*p++ - '0');
}

[[gnu::always_inline]] inline bool scanDecimal(const char*& pos, const char* end, double& out) {
    static constexpr double POW10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                       1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const char* p = pos;
    const bool negative = p != end && *p == '-';
    if (negative)
        ++p;
    const char* const start = p;
    uint64_t mantissa = 0;
    readDigits(p, end, mantissa);
    const size_t whole = static_cast<size_t>(p - start);
    size_t decimals = 0;
    if (p != end && *p == '.') {
        const char* const frac = ++p;
        readDigits(p, end, mantissa);
        decimals = static_cast<size_t>(p - frac);
    }
    // At most 19 digits (no uint64 overflow), an exactly representable mantissa, 10^decimals exact.
    if ((p != end && *p != '|') || whole + decimals == 0 || whole + decimals > 19 || decimals > 22 ||
        mantissa > (uint64_t(1) << 53))
        return false;
    const double v = static_cast<double>(mantissa) / POW10[decimals];
    out = negative ? -v : v;
    pos = p;
    return true;
}

bool fastDecimal(std::string_view s, double& out) {
    const char* p = s.data();
    const char* const end = p + s.size();
    return scanDecimal(p, end, out) && p == end;
}

/// Object id -> index of the live object: open addressing with linear probing in a power-of-two table,
/// Fibonacci hashing (Knuth, TAOCP vol. 3, 6.4) and backward-shift deletion (no tombstones; Knuth's
/// Algorithm R). std::unordered_map spent most of its lookup in a 64-bit modulo by a prime; the parser looks
/// an id up on every object line.
class IdIndex {
public:
    static constexpr uint32_t NONE = ~0u;

    uint32_t find(uint64_t id) const {
        if (mSize == 0)
            return NONE;
        for (size_t i = slot(id);; i = (i + 1) & mMask) {
            if (mValues[i] == NONE)
                return NONE;
            if (mKeys[i] == id)
                return mValues[i];
        }
    }

    /// Adds id -> value; the id must not be present.
    void insert(uint64_t id, uint32_t value) {
        if ((mSize + 1) * 4 > mValues.size() * 3)
            grow();
        size_t i = slot(id);
        while (mValues[i] != NONE)
            i = (i + 1) & mMask;
        mKeys[i] = id;
        mValues[i] = value;
        ++mSize;
    }

    /// Removes id if present; returns its value or NONE.
    uint32_t erase(uint64_t id) {
        if (mSize == 0)
            return NONE;
        size_t i = slot(id);
        while (mValues[i] != NONE && mKeys[i] != id)
            i = (i + 1) & mMask;
        if (mValues[i] == NONE)
            return NONE;
        const uint32_t value = mValues[i];
        // Shift later members of the probe run back into the hole unless their home slot lies
        // cyclically in (hole, j].
        size_t hole = i;
        for (size_t j = (i + 1) & mMask; mValues[j] != NONE; j = (j + 1) & mMask) {
            const size_t home = slot(mKeys[j]);
            const bool stays = hole <= j ? (hole < home && home <= j) : (hole < home || home <= j);
            if (!stays) {
                mKeys[hole] = mKeys[j];
                mValues[hole] = mValues[j];
                hole = j;
            }
        }
        mValues[hole] = NONE;
        --mSize;
        return value;
    }

private:
    size_t slot(uint64_t id) const { return static_cast<size_t>((id * 0x9E3779B97F4A7C15ull) >> mShift); }

    void grow() {
        const size_t capacity = mValues.empty() ? 64 : mValues.size() * 2;
        std::vector<uint64_t> keys(capacity);
        std::vector<uint32_t> values(capacity, NONE);
        keys.swap(mKeys);
        values.swap(mValues);
        mMask = capacity - 1;
        mShift = 64;
        for (size_t c = capacity; c > 1; c >>= 1)
            --mShift;
        mSize = 0;
        for (size_t i = 0; i < values.size(); ++i)
            if (values[i] != NONE)
                insert(keys[i], values[i]);
    }

    std::vector<uint64_t> mKeys;
    std::vector<uint32_t> mValues;
    size_t mMask = 0;
    unsigned mShift = 64;
    size_t mSize = 0;
};

/// string_view::find for a byte expected within the first few characters (an id's comma, a key's '='): a
/// plain loop, where a memchr call costs more than the scan on the ~25-byte lines most recordings are made
/// of.
inline size_t findShort(std::string_view s, char c) {
    for (size_t i = 0; i < s.size(); ++i)
        if (s[i] == c)
            return i;
    return std::string_view::npos;
}

double wrapLongitude(double lon) {
    if (lon > 180.0)
        lon -= 360.0;
    if (lon < -180.0)
        lon += 360.0;
    return lon;
}

struct State {
    double lon = 0, lat = 0, alt = 0, roll = 0, pitch = 0, yaw = 0;
};

} // namespace

struct AcmiParser::Impl {
    std::string source;
    Recording rec;
    std::string carry;   // an incomplete physical line from the previous chunk
    std::string logical; // continued lines joined so far
    bool continuing = false;
    bool referenceFrozen = false;              // appliedLon/Lat were taken from the globals
    double appliedLon = 0.0, appliedLat = 0.0; // reference added to the samples stored so far
    bool mayEscape = true;      // false while the lines being read come from a chunk without any backslash
    long long lineNo = 0;       // physical line of the text just read
    long long logicalStart = 0; // physical line where the current logical line began
    bool sawFileType = false, sawVersion = false, firstBytes = true;
    double now = 0.0;
    IdIndex index;             // id -> objects[] of the live object
    std::vector<State> states; // parallel to rec.objects
    std::vector<bool> anyAttitude;

    [[noreturn]] void fail(const std::string& field, const std::string& message) const {
        throw RecordingError(source, logicalStart, field, message);
    }

    double number(std::string_view s, const char* field) const {
        double v = 0.0;
        if (!s.empty() && s.front() == '+')
            s.remove_prefix(1);
        if (fastDecimal(s, v))
            return v;
        const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (ec != std::errc() || ptr != s.data() + s.size())
            fail(field, "expected a number, got '" + std::string(s.substr(0, 40)) + "'");
        if (!std::isfinite(v) || std::abs(v) > 1e9)
            fail(field, "value '" + std::string(s.substr(0, 40)) + "' is not finite or out of range");
        return v;
    }

    void feed(std::string_view chunk) {
        rec.bytes += chunk.size();
        if (rec.bytes > RecordingLimits::MAX_TEXT_BYTES) {
            logicalStart = lineNo + 1;
            fail("", "the recording's text is longer than " +
                         std::to_string(RecordingLimits::MAX_TEXT_BYTES >> 30) +
                         " GiB (a zip member inflating without end?); refused");
        }
        if (firstBytes) {
            // The BOM may arrive split over chunks only for absurd chunk sizes; keep it simple and exact.
            carry.append(chunk);
            if (carry.size() < UTF8_BOM.size() && carry == UTF8_BOM.substr(0, carry.size()))
                return;
            firstBytes = false;
            std::string head;
            head.swap(carry);
            std::string_view h = head;
            if (h.substr(0, 3) == UTF8_BOM)
                h.remove_prefix(3);
            consume(h);
            return;
        }
        consume(chunk);
    }

    void consume(std::string_view chunk) {
        size_t pos = 0;
        if (!carry.empty()) {
            const size_t nl = chunk.find('\n');
            if (nl == std::string_view::npos) {
                carry.append(chunk);
                checkLineLength(carry.size());
                return;
            }
            carry.append(chunk.substr(0, nl));
            std::string line;
            line.swap(carry);
            mayEscape = true;
            physicalLine(line);
            pos = nl + 1;
        }
        // One vectorised scan per chunk: when it holds no backslash (nearly always), no line in it continues
        // or escapes, and the per-line checks are skipped.
        mayEscape =
            pos < chunk.size() && std::memchr(chunk.data() + pos, '\\', chunk.size() - pos) != nullptr;
        while (pos < chunk.size()) {
            const size_t nl = chunk.find('\n', pos);
            if (nl == std::string_view::npos) {
                carry.assign(chunk.substr(pos));
                checkLineLength(carry.size());
                return;
            }
            physicalLine(chunk.substr(pos, nl - pos));
            pos = nl + 1;
        }
    }

    /// A line (a physical one being read, or a logical one being joined) past MAX_LINE_BYTES is refused
    /// before it is held whole.
    void checkLineLength(size_t bytes) {
        if (bytes <= RecordingLimits::MAX_LINE_BYTES)
            return;
        if (!continuing)
            logicalStart = lineNo + 1;
        fail("", "line longer than " + std::to_string(RecordingLimits::MAX_LINE_BYTES >> 20) + " MiB" +
                     (continuing ? " (continued with '\\' since this line)" : "") + "; refused");
    }

    void physicalLine(std::string_view line) {
        ++lineNo;
        ++rec.lines;
        if (!line.empty() && line.back() == '\r')
            line.remove_suffix(1);
        size_t slashes = 0;
        while (mayEscape && slashes < line.size() && line[line.size() - 1 - slashes] == '\\')
            ++slashes;
        const bool continues = slashes % 2 == 1;
        if (continuing) {
            logical.append(line.substr(0, continues ? line.size() - 1 : line.size()));
            checkLineLength(logical.size());
            if (continues) {
                logical.push_back('\n');
                return;
            }
            continuing = false;
            std::string joined;
            joined.swap(logical);
            const bool clean = !mayEscape; // the joined text may hold escapes from earlier chunks
            mayEscape = true;
            logicalLine(joined);
            mayEscape = !clean;
            return;
        }
        logicalStart = lineNo;
        if (continues) {
            continuing = true;
            logical.assign(line.substr(0, line.size() - 1));
            logical.push_back('\n');
            return;
        }
        logicalLine(line);
    }

    void logicalLine(std::string_view line) {
        if (line.empty())
            return;
        if (!sawFileType) {
            if (line.substr(0, 9) != "FileType=")
                fail("", "not a Tacview ACMI file: the first line must be 'FileType=text/acmi/tacview'");
            if (line.substr(9) != "text/acmi/tacview")
                fail("FileType",
                     "expected 'text/acmi/tacview', got '" + std::string(line.substr(9, 40)) + "'");
            sawFileType = true;
            return;
        }
        if (!sawVersion) {
            if (line.substr(0, 12) != "FileVersion=")
                fail("FileVersion", "expected 'FileVersion=2.x' on the second line");
            const std::string_view v = line.substr(12);
            if (v.substr(0, 2) != "2.")
                fail("FileVersion", "unsupported version '" + std::string(v.substr(0, 20)) +
                                        "' (Tacview ACMI 2.x is supported)");
            rec.fileVersion = std::string(v);
            sawVersion = true;
            return;
        }
        if (line.size() >= 2 && line[0] == '/' && line[1] == '/')
            return;
        if (line[0] == '#') {
            now = number(line.substr(1), "frame time");
            return;
        }
        if (line[0] == '-') {
            uint64_t id = 0;
            if (!parseHexId(line.substr(1), id))
                fail("object id",
                     "expected a hexadecimal id after '-', got '" + std::string(line.substr(1, 20)) + "'");
            const uint32_t obj = index.erase(id);
            if (obj != IdIndex::NONE) // removing an unknown id is harmless (trimmed recordings)
                rec.objects[obj].removedAt = now;
            return;
        }
        objectLine(line);
    }

    /// Next property: up to the first unescaped comma. Returns false at the end. `escapes` is false when
    /// the line holds no backslash at all (checked once per line), which skips the per-property check.
    static bool nextProperty(std::string_view& rest, std::string_view& prop, bool& escaped, bool escapes) {
        if (rest.empty())
            return false;
        escaped = false;
        // Fast path: no backslash before the next comma (memchr is vectorised).
        const void* commaPtr = std::memchr(rest.data(), ',', rest.size());
        const size_t comma =
            commaPtr ? static_cast<size_t>(static_cast<const char*>(commaPtr) - rest.data()) : rest.size();
        if (!escapes || !std::memchr(rest.data(), '\\', comma)) {
            prop = rest.substr(0, comma);
            rest = comma < rest.size() ? rest.substr(comma + 1) : std::string_view{};
            return true;
        }
        size_t i = 0;
        for (; i < rest.size(); ++i) {
            if (rest[i] == '\\' && i + 1 < rest.size()) {
                escaped = true;
                ++i;
                continue;
            }
            if (rest[i] == ',')
                break;
        }
        prop = rest.substr(0, i);
        rest = i < rest.size() ? rest.substr(i + 1) : std::string_view{};
        return true;
    }

    void objectLine(std::string_view line) {
        const size_t comma = findShort(line, ',');
        const std::string_view idText = line.substr(0, comma);
        uint64_t id = 0;
        if (!parseHexId(idText, id))
            fail("object id", "expected a hexadecimal object id, a '#' frame time or a '-' removal, got '" +
                                  std::string(idText.substr(0, 20)) + "'");
        std::string_view rest = comma == std::string_view::npos ? std::string_view{} : line.substr(comma + 1);
        if (id == 0) {
            globalLine(rest);
            return;
        }
        uint32_t obj = index.find(id);
        if (obj == IdIndex::NONE) {
            if (rec.objects.size() >= RecordingLimits::MAX_OBJECTS)
                fail("object id",
                     "more than " + std::to_string(RecordingLimits::MAX_OBJECTS) + " objects; refused");
            obj = static_cast<uint32_t>(rec.objects.size());
            RecordedObject o;
            o.id = id;
            o.line = logicalStart;
            rec.objects.push_back(std::move(o));
            states.emplace_back();
            anyAttitude.push_back(false);
            index.insert(id, obj);
        }
        RecordedObject& o = rec.objects[obj];
        std::string_view prop;
        bool escaped = false;
        const bool escapes =
            mayEscape && !rest.empty() && std::memchr(rest.data(), '\\', rest.size()) != nullptr;
        while (nextProperty(rest, prop, escaped, escapes)) {
            const size_t eq = findShort(prop, '=');
            if (eq == std::string_view::npos)
                continue; // not a property; never fatal
            const std::string_view key = prop.substr(0, eq), value = prop.substr(eq + 1);
            if (key == "T") {
                transform(obj, value);
                continue;
            }
            std::string* field = nullptr;
            if (key == "Type")
                field = &o.type;
            else if (key == "Name")
                field = &o.name;
            else if (key == "Pilot")
                field = &o.pilot;
            else if (key == "CallSign")
                field = &o.callsign;
            else if (key == "Coalition")
                field = &o.coalition;
            else if (key == "Color")
                field = &o.color;
            else if (key == "Group")
                field = &o.group;
            else if (key == "Length") {
                double v = 0.0;
                const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
                if (ec == std::errc() && ptr == value.data() + value.size() && std::isfinite(v) && v > 0.0 &&
                    v < 2000.0)
                    o.length = v;
                continue;
            }
            if (field)
                *field = escaped ? unescape(value) : std::string(value);
        }
    }

    /// Splits T= into its '|'-separated fields and reads each number in the same pass: fastDecimal's loop
    /// stops at the '|', so the common line is scanned once (a separate split, then a parse, read it twice).
    void transform(uint32_t obj, std::string_view value) {
        // Plain arrays, left uninitialised (only [0, n) is read): string_view's zeroing constructor cost a
        // 144-byte rep stos per line, 13% of this function.
        const char* fieldStart[9];
        size_t fieldSize[9];
        double parsed[9];
        bool fast[9];
        int n = 0;
        const char* p = value.data();
        const char* const end = p + value.size();
        while (true) {
            if (n == 9)
                fail("T", "expected 3, 5, 6 or 9 '|'-separated fields, got more than 9");
            const char* const start = p;
            // Fields 6-8 (U, V, heading) are never read, so they are only skipped.
            fast[n] = n < 6 && scanDecimal(p, end, parsed[n]);
            if (!fast[n]) { // empty, or not the fast form: find the bar and let number() decide
                const void* bar = p == end ? nullptr : std::memchr(p, '|', static_cast<size_t>(end - p));
                p = bar ? static_cast<const char*>(bar) : end;
            }
            fieldStart[n] = start;
            fieldSize[n++] = static_cast<size_t>(p - start);
            if (p == end)
                break;
            ++p; // the '|'
        }
        if (n != 3 && n != 5 && n != 6 && n != 9)
            fail("T", "expected 3, 5, 6 or 9 '|'-separated fields, got " + std::to_string(n));
        auto field = [&](int k, const char* name) {
            return fast[k] ? parsed[k] : number(std::string_view(fieldStart[k], fieldSize[k]), name);
        };
        State& s = states[obj];
        static const char* names[] = {"T longitude", "T latitude", "T altitude", "T roll",   "T pitch",
                                      "T yaw",       "T U",        "T V",        "T heading"};
        if (fieldSize[0] != 0)
            s.lon = field(0, names[0]);
        if (fieldSize[1] != 0)
            s.lat = field(1, names[1]);
        if (fieldSize[2] != 0)
            s.alt = field(2, names[2]);
        if (std::abs(s.lon) > 360.0)
            fail(names[0], "longitude offset " + std::to_string(s.lon) + " is out of range");
        if (std::abs(s.lat) > 180.0)
            fail(names[1], "latitude offset " + std::to_string(s.lat) + " is out of range");
        if (n >= 6) {
            // 5 fields are lon|lat|alt|U|V: no attitude (a reader taking fields 3-5 as angles misreads them).
            for (int k = 3; k < 6; ++k)
                if (fieldSize[k] != 0) {
                    const double v = field(k, names[k]);
                    (k == 3 ? s.roll : k == 4 ? s.pitch : s.yaw) = v;
                    anyAttitude[obj] = true;
                }
        }
        // U, V (DCS's flat-world metres) and Heading (relative to that flat world's north) are not used --
        // the replay places objects on the ellipsoid -- so they are not read either.
        storeSample(obj, s);
    }

    /// The object's state at `now` as a track sample in absolute degrees (one sample per frame time). Offsets
    /// become absolute here, with the reference known when the first sample is stored (the header sets it
    /// first in every recording seen); finish() corrects the rare file that moves it later. Doing it at the
    /// end meant a second pass over all tracks, ~5% of a parse.
    void storeSample(uint32_t obj, const State& s) {
        RecordedObject& o = rec.objects[obj];
        if (!referenceFrozen) {
            appliedLon = rec.referenceLongitude;
            appliedLat = rec.referenceLatitude;
            referenceFrozen = true;
        }
        const double lat = s.lat + appliedLat;
        if (std::abs(lat) > 90.0)
            fail("T latitude", "object " + o.describe() + " has latitude " + std::to_string(lat) +
                                   " (reference + offset) outside [-90, 90]");
        ObjectSample sample{now,
                            wrapLongitude(s.lon + appliedLon),
                            lat,
                            s.alt,
                            static_cast<float>(s.roll),
                            static_cast<float>(s.pitch),
                            static_cast<float>(s.yaw)};
        if (!o.track.empty() && o.track.back().time == now)
            o.track.back() = sample;
        else {
            if (rec.samples >= RecordingLimits::MAX_SAMPLES)
                fail("T",
                     "more than " + std::to_string(RecordingLimits::MAX_SAMPLES) + " track samples; refused");
            o.track.push_back(sample);
            ++rec.samples;
        }
    }

    void globalLine(std::string_view rest) {
        std::string_view prop;
        bool escaped = false;
        const bool escapes = !rest.empty() && std::memchr(rest.data(), '\\', rest.size()) != nullptr;
        while (nextProperty(rest, prop, escaped, escapes)) {
            const size_t eq = prop.find('=');
            if (eq == std::string_view::npos)
                continue;
            const std::string_view key = prop.substr(0, eq), value = prop.substr(eq + 1);
            if (key == "ReferenceLongitude")
                rec.referenceLongitude = number(value, "ReferenceLongitude");
            else if (key == "ReferenceLatitude")
                rec.referenceLatitude = number(value, "ReferenceLatitude");
            else if (key == "ReferenceTime") {
                rec.referenceTime = escaped ? unescape(value) : std::string(value);
                rec.referenceUnix = parseIsoUtc(rec.referenceTime);
            } else if (key == "Title")
                rec.title = escaped ? unescape(value) : std::string(value);
            else if (key == "Event")
                event(escaped ? unescape(value) : std::string(value));
        }
    }

    void event(const std::string& value) {
        // Event=Type|ObjectId|...|Text: the first field is the type, the last the text, ids between.
        RecordedEvent e;
        e.time = now;
        e.line = logicalStart;
        std::vector<std::string_view> parts;
        std::string_view v = value;
        size_t start = 0;
        while (true) {
            const size_t bar = v.find('|', start);
            parts.push_back(
                v.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start));
            if (bar == std::string_view::npos)
                break;
            start = bar + 1;
        }
        e.type = std::string(parts.front());
        if (e.type.empty())
            fail("Event", "missing the event type");
        for (size_t i = 1; i < parts.size(); ++i) {
            uint64_t id = 0;
            if (i + 1 < parts.size() || parts.size() == 2) {
                if (parseHexId(parts[i], id)) {
                    e.objects.push_back(id);
                    continue;
                }
            }
            if (i + 1 == parts.size())
                e.text = std::string(parts[i]);
        }
        if (e.type == "Destroyed")
            for (uint64_t id : e.objects) {
                const uint32_t obj = index.find(id);
                if (obj != IdIndex::NONE && !rec.objects[obj].destroyedAt)
                    rec.objects[obj].destroyedAt = now;
            }
        rec.events.push_back(std::move(e));
    }

    Recording finish() {
        if (firstBytes && !carry.empty()) { // the whole input was shorter than a BOM
            firstBytes = false;
            std::string head;
            head.swap(carry);
            consume(head);
        }
        mayEscape = true; // the carry may have grown over chunks that were not scanned
        if (!carry.empty()) {
            std::string line;
            line.swap(carry);
            physicalLine(line);
        }
        if (continuing) {
            continuing = false;
            std::string joined;
            joined.swap(logical);
            logicalLine(joined);
        }
        if (!sawFileType || !sawVersion) {
            logicalStart = 0;
            fail("",
                 "not a Tacview ACMI file: missing the 'FileType=text/acmi/tacview' and 'FileVersion=2.x' "
                 "header");
        }
        rec.source = source;
        bool any = false;
        double lo = 0.0, hi = 0.0;
        auto extend = [&](double t) {
            lo = any ? std::min(lo, t) : t;
            hi = any ? std::max(hi, t) : t;
            any = true;
        };
        const double dLon = rec.referenceLongitude - appliedLon, dLat = rec.referenceLatitude - appliedLat;
        const bool moved = referenceFrozen && (dLon != 0.0 || dLat != 0.0);
        for (size_t i = 0; i < rec.objects.size(); ++i) {
            RecordedObject& o = rec.objects[i];
            const auto byTime = [](const ObjectSample& a, const ObjectSample& b) { return a.time < b.time; };
            if (!std::is_sorted(o.track.begin(), o.track.end(),
                                byTime)) // frames nearly always arrive in order
                std::stable_sort(o.track.begin(), o.track.end(), byTime);
            if (moved)
                for (ObjectSample& s : o.track) {
                    s.lon = wrapLongitude(s.lon + dLon);
                    s.lat += dLat;
                    if (std::abs(s.lat) > 90.0)
                        throw RecordingError(source, o.line, "T latitude",
                                             "object " + o.describe() + " has latitude " +
                                                 std::to_string(s.lat) +
                                                 " (reference + offset) outside [-90, 90]");
                }
            if (!o.track.empty()) {
                extend(o.track.front().time);
                extend(o.track.back().time);
            }
            // Attitude from the track is derived when a rig needs it (WorldTrack), not for the thousands of
            // shells and flares a busy recording holds.
            o.attitude = anyAttitude[i] ? "recorded" : "none";
        }
        std::stable_sort(rec.events.begin(), rec.events.end(),
                         [](const RecordedEvent& a, const RecordedEvent& b) { return a.time < b.time; });
        for (const RecordedEvent& e : rec.events)
            extend(e.time);
        rec.startTime = lo;
        rec.endTime = hi;
        return std::move(rec);
    }
};

AcmiParser::AcmiParser(std::string sourceName) : mImpl(new Impl) {
    mImpl->source = std::move(sourceName);
}
AcmiParser::~AcmiParser() {
    delete mImpl;
}
void AcmiParser::feed(std::string_view chunk) {
    mImpl->feed(chunk);
}
Recording AcmiParser::finish() {
    Recording r = mImpl->finish();
    r.format = "acmi-text";
    return r;
}

} // namespace pacifica::recording
