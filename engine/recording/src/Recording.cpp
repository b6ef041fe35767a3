// Recording: format detection, the zip wrapper (libzip, streamed), object sampling and the attitude derived
// from a track. The ACMI text parser is Acmi.cpp, the IGC parser Igc.cpp.
#include "recording/Recording.h"

#include "engine/Space.h"

#include <isa-l/igzip_lib.h>
#include <zip.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <memory>
#include <numbers>

namespace pacifica::recording {

namespace {

constexpr double DEG = std::numbers::pi / 180.0;
constexpr double G = 9.80665; // m/s^2, standard gravity (coordinated-turn bank)
constexpr double MEAN_RADIUS =
    EARTH_RADIUS; // m (engine/Space.h), only for the small local steps of deriveAttitude()
constexpr size_t CHUNK = 1 << 20;

double wrapDeg(double a) {
    a = std::fmod(a, 360.0);
    return a < 0.0 ? a + 360.0 : a;
}

/// Shortest signed difference b - a in degrees, in (-180, 180].
double angleDiff(double a, double b) {
    double d = std::fmod(b - a, 360.0);
    if (d > 180.0)
        d -= 360.0;
    if (d <= -180.0)
        d += 360.0;
    return d;
}

using ZipArchive = std::unique_ptr<zip_t, int (*)(zip_t*)>;
using ZipFile = std::unique_ptr<zip_file_t, int (*)(zip_file_t*)>;

ZipArchive openZip(const std::filesystem::path& file) {
    int err = 0;
    zip_t* za = zip_open(file.c_str(), ZIP_RDONLY, &err);
    if (!za) {
        zip_error_t ze;
        zip_error_init_with_code(&ze, err);
        const std::string msg = zip_error_strerror(&ze);
        zip_error_fini(&ze);
        throw RecordingError(file.string(), 0, "", "cannot open the zip archive: " + msg);
    }
    return ZipArchive(za, zip_close);
}

/// The archive's first file (folders skipped).
zip_uint64_t firstMember(zip_t* za, const std::filesystem::path& file) {
    const zip_int64_t n = zip_get_num_entries(za, 0);
    for (zip_int64_t i = 0; i < n; ++i) {
        const char* name = zip_get_name(za, static_cast<zip_uint64_t>(i), 0);
        const std::string s = name ? name : "";
        if (!s.empty() && s.back() == '/')
            continue;
        return static_cast<zip_uint64_t>(i);
    }
    throw RecordingError(file.string(), 0, "", "the zip archive holds no file (expected one .txt.acmi)");
}

RecordingError corruptMember(const std::filesystem::path& file, const std::string& why) {
    return RecordingError(file.string(), 0, "", "corrupt zip member: " + why);
}

/// Any member libzip decodes itself (stored, bzip2, encrypted...), fed to the parser as it is read.
void feedThroughLibzip(zip_file_t* zf, const std::filesystem::path& file, AcmiParser& parser) {
    std::vector<char> buf(CHUNK);
    while (true) {
        const zip_int64_t got = zip_fread(zf, buf.data(), buf.size());
        if (got < 0)
            throw corruptMember(file, zip_file_strerror(zf));
        if (got == 0)
            return;
        parser.feed(std::string_view(buf.data(), static_cast<size_t>(got)));
    }
}

std::string inflateError(int rc) {
    return std::string("inflate: ") + (rc == ISAL_INVALID_BLOCK      ? "invalid deflate block"
                                       : rc == ISAL_INVALID_SYMBOL   ? "invalid deflate symbol"
                                       : rc == ISAL_INVALID_LOOKBACK ? "invalid distance back"
                                                                     : "error " + std::to_string(rc));
}

/// A deflate member's raw stream inflated with ISA-L and fed to the parser, then checked against the
/// member's CRC-32 (`crc`). A parse error is held until the CRC says whether the archive or the recording
/// is at fault: damage usually shows first as nonsense text.
void inflateWithIsal(zip_file_t* zf, uint32_t crc, const std::filesystem::path& file, AcmiParser& parser) {
    // inflate_state holds ISA-L's 32 KiB history and decode tables: on the heap, not the stack.
    const auto zs = std::make_unique<inflate_state>();
    isal_inflate_init(zs.get());
    zs->crc_flag = ISAL_GZIP_NO_HDR;
    std::vector<unsigned char> in(CHUNK);
    std::vector<char> buf(CHUNK);
    std::unique_ptr<RecordingError> parseError;
    uint64_t inflated = 0;
    while (zs->block_state != ISAL_BLOCK_FINISH) {
        if (zs->avail_in == 0) {
            const zip_int64_t got = zip_fread(zf, in.data(), in.size());
            if (got < 0)
                throw corruptMember(file, zip_file_strerror(zf));
            if (got == 0)
                throw corruptMember(file, "the deflate stream ends early");
            zs->next_in = in.data();
            zs->avail_in = static_cast<uint32_t>(got);
        }
        const uint32_t inBefore = zs->avail_in;
        zs->next_out = reinterpret_cast<uint8_t*>(buf.data());
        zs->avail_out = static_cast<uint32_t>(buf.size());
        const int rc = isal_inflate(zs.get());
        if (rc < 0)
            throw corruptMember(file, inflateError(rc));
        const size_t produced = buf.size() - zs->avail_out;
        if (produced == 0 && zs->avail_in == inBefore && zs->block_state != ISAL_BLOCK_FINISH)
            throw corruptMember(file, "inflate made no progress");
        inflated += produced;
        if (inflated > RecordingLimits::MAX_TEXT_BYTES) // a bomb: stop now, even after a parse error
            throw RecordingError(file.string(), 0, "",
                                 "the zip member inflates to more than " +
                                     std::to_string(RecordingLimits::MAX_TEXT_BYTES >> 30) +
                                     " GiB; refused (a zip bomb?)");
        if (produced > 0 && !parseError) {
            try {
                parser.feed(std::string_view(buf.data(), produced));
            } catch (const RecordingError& e) {
                parseError = std::make_unique<RecordingError>(e); // finish inflating (without parsing)
            }
        }
    }
    if (zs->crc != crc)
        throw corruptMember(
            file, "CRC-32 mismatch (the archive is damaged)" +
                      (parseError ? "; its damaged text gave: " + std::string(parseError->what()) : ""));
    if (parseError)
        throw *parseError;
}

/// A zip ACMI: its first file, parsed as it is inflated. Deflate members are inflated here with Intel's
/// ISA-L (igzip, raw RFC 1951 stream) over 1 MiB buffers and checked against the member's CRC-32, which
/// ISA-L computes as it inflates (crc_flag ISAL_GZIP_NO_HDR: the gzip CRC, the same CRC-32 as zip's, PKWARE
/// APPNOTE 4.4.7). On this project's machine it inflates the bench's 200 MB recording at ~640 MB/s against
/// zlib 1.2.13's ~225 MB/s (docs/RECORDINGS.md), and libzip's own decoder feeds zlib 8 KiB at a time through
/// layered sources. Anything else (stored, bzip2, encrypted...) goes through libzip.
void parseZip(const std::filesystem::path& file, AcmiParser& parser) {
    const ZipArchive za = openZip(file);
    const zip_uint64_t member = firstMember(za.get(), file);
    zip_stat_t st;
    zip_stat_init(&st);
    const bool known = zip_stat_index(za.get(), member, 0, &st) == 0 &&
                       (st.valid & (ZIP_STAT_COMP_METHOD | ZIP_STAT_CRC | ZIP_STAT_ENCRYPTION_METHOD)) ==
                           (ZIP_STAT_COMP_METHOD | ZIP_STAT_CRC | ZIP_STAT_ENCRYPTION_METHOD);
    const bool raw = known && st.comp_method == ZIP_CM_DEFLATE && st.encryption_method == ZIP_EM_NONE;
    zip_file_t* zf = zip_fopen_index(za.get(), member, raw ? ZIP_FL_COMPRESSED : 0);
    if (!zf)
        throw RecordingError(file.string(), 0, "",
                             std::string("cannot read the zip member: ") + zip_strerror(za.get()));
    const ZipFile fguard(zf, zip_fclose);
    if (raw)
        inflateWithIsal(zf, st.crc, file, parser);
    else
        feedThroughLibzip(zf, file, parser);
}

std::string readHead(const std::filesystem::path& file, size_t n) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw RecordingError(file.string(), 0, "", "cannot open the file");
    std::string head(n, '\0');
    in.read(head.data(), static_cast<std::streamsize>(n));
    head.resize(static_cast<size_t>(in.gcount()));
    return head;
}

} // namespace

RecordingError::RecordingError(const std::string& file, long long line, const std::string& field,
                               const std::string& message)
    : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " +
                         (field.empty() ? "" : field + ": ") + message),
      mFile(file), mField(field), mMessage(message), mLine(line) {}

bool RecordedObject::hasTag(std::string_view tag) const {
    std::string_view t = type;
    while (!t.empty()) {
        const size_t plus = t.find('+');
        if (t.substr(0, plus) == tag)
            return true;
        if (plus == std::string_view::npos)
            break;
        t.remove_prefix(plus + 1);
    }
    return false;
}

ObjectSample RecordedObject::sampleAt(double t) const {
    if (!(t > track.front().time))
        return track.front();
    if (t >= track.back().time)
        return track.back();
    const auto it = std::upper_bound(track.begin(), track.end(), t,
                                     [](double v, const ObjectSample& s) { return v < s.time; });
    const ObjectSample& b = *it;
    const ObjectSample& a = *(it - 1);
    const double s = (t - a.time) / (b.time - a.time);
    ObjectSample r;
    r.time = t;
    r.lon = a.lon + s * angleDiff(a.lon, b.lon);
    r.lat = a.lat + s * (b.lat - a.lat);
    r.alt = a.alt + s * (b.alt - a.alt);
    r.roll = static_cast<float>(a.roll + s * angleDiff(a.roll, b.roll));
    r.pitch = static_cast<float>(a.pitch + s * (b.pitch - a.pitch));
    r.yaw = static_cast<float>(wrapDeg(a.yaw + s * angleDiff(a.yaw, b.yaw)));
    return r;
}

std::string hexId(uint64_t id) {
    char text[24];
    std::snprintf(text, sizeof text, "%llx", static_cast<unsigned long long>(id));
    return text;
}

std::string RecordedObject::describe() const {
    std::string s = hexId(id);
    s += " " + (type.empty() ? std::string("(no type)") : type);
    if (!name.empty())
        s += " '" + name + "'";
    if (!pilot.empty())
        s += " pilot '" + pilot + "'";
    if (!callsign.empty())
        s += " callsign '" + callsign + "'";
    return s;
}

const RecordedObject* Recording::find(uint64_t id) const {
    for (auto it = objects.rbegin(); it != objects.rend(); ++it)
        if (it->id == id)
            return &*it;
    return nullptr;
}

std::optional<double> parseIsoUtc(std::string_view s) {
    int y = 0, mo = 0, d = 0, h = 0, mi = 0;
    double sec = 0.0;
    char tail[8] = {};
    const std::string text(s.substr(0, 64));
    if (std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%lf%7s", &y, &mo, &d, &h, &mi, &sec, tail) < 6)
        return std::nullopt;
    if (mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || !(sec >= 0.0 && sec < 61.0))
        return std::nullopt;
    if (tail[0] != '\0' && std::strcmp(tail, "Z") != 0)
        return std::nullopt;
    // Days from civil (Howard Hinnant's algorithm), so no time zone or locale is involved.
    const int yy = y - (mo <= 2);
    const int era = (yy >= 0 ? yy : yy - 399) / 400;
    const int yoe = yy - era * 400;
    const int doy = (153 * (mo + (mo > 2 ? -3 : 9)) + 2) / 5 + d - 1;
    const int doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    const double days = static_cast<double>(era) * 146097.0 + doe - 719468.0;
    return days * 86400.0 + h * 3600.0 + mi * 60.0 + sec;
}

void deriveAttitude(RecordedObject& o, double smoothing) {
    o.attitude = "derived";
    const size_t n = o.track.size();
    if (n < 2)
        return;
    // Local metres around each sample (the steps are short, so the sphere's tangent plane is exact enough).
    std::vector<double> x(n), y(n), z(n), t(n);
    const double lat0 = o.track.front().lat * DEG;
    for (size_t i = 0; i < n; ++i) {
        const ObjectSample& s = o.track[i];
        x[i] = angleDiff(o.track.front().lon, s.lon) * DEG * MEAN_RADIUS * std::cos(lat0);
        y[i] = (s.lat - o.track.front().lat) * DEG * MEAN_RADIUS;
        z[i] = s.alt;
        t[i] = s.time;
    }
    // Velocity by central differences, then Gaussian smoothing in time (sigma = smoothing / 2).
    std::vector<double> vx(n), vy(n), vz(n);
    for (size_t i = 0; i < n; ++i) {
        const size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
        const double dt = t[b] - t[a];
        vx[i] = dt > 0 ? (x[b] - x[a]) / dt : 0.0;
        vy[i] = dt > 0 ? (y[b] - y[a]) / dt : 0.0;
        vz[i] = dt > 0 ? (z[b] - z[a]) / dt : 0.0;
    }
    const double sigma = std::max(smoothing * 0.5, 1e-3);
    auto smooth = [&](const std::vector<double>& v) {
        std::vector<double> out(n);
        size_t lo = 0, hi = 0;
        for (size_t i = 0; i < n; ++i) {
            // +-3 sigma, at most 256 samples each side (a burst of samples at nearly one time stays linear).
            while (t[i] - t[lo] > 3 * sigma || i - lo > 256)
                ++lo;
            if (hi < i)
                hi = i;
            while (hi + 1 < n && t[hi + 1] - t[i] <= 3 * sigma && hi + 1 - i <= 256)
                ++hi;
            double sw = 0.0, s = 0.0;
            for (size_t j = lo; j <= hi; ++j) {
                const double u = (t[j] - t[i]) / sigma;
                const double w = std::exp(-0.5 * u * u);
                sw += w;
                s += w * v[j];
            }
            out[i] = s / sw;
        }
        return out;
    };
    vx = smooth(vx);
    vy = smooth(vy);
    vz = smooth(vz);
    std::vector<double> heading(n), rate(n, 0.0);
    double last = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const double vh = std::hypot(vx[i], vy[i]);
        heading[i] = vh > 0.5 ? wrapDeg(std::atan2(vx[i], vy[i]) / DEG) : last; // keep it when hovering
        last = heading[i];
    }
    for (size_t i = 0; i < n; ++i) {
        const size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
        const double dt = t[b] - t[a];
        rate[i] = dt > 0 ? angleDiff(heading[a], heading[b]) * DEG / dt : 0.0;
    }
    rate = smooth(rate);
    for (size_t i = 0; i < n; ++i) {
        const double vh = std::hypot(vx[i], vy[i]);
        ObjectSample& s = o.track[i];
        s.yaw = static_cast<float>(heading[i]);
        s.pitch = static_cast<float>(std::atan2(vz[i], std::max(vh, 1e-9)) / DEG);
        // Coordinated turn: tan(bank) = v w / g (w the turn rate in rad/s), right turn = right wing down.
        s.roll = static_cast<float>(std::atan(vh * rate[i] / G) / DEG);
        if (vh < 0.5)
            s.pitch = s.roll = 0.0f;
    }
}

std::string supportedFormats() {
    return "Tacview ACMI 2.x text (.txt.acmi), Tacview ACMI zip (.zip.acmi), IGC (.igc), and the Pacifica "
           "flight CSV (docs/FLIGHT_FORMAT.md)";
}

std::string detectFormat(const std::filesystem::path& file) {
    const std::string head = readHead(file, 4096);
    std::string_view h = head;
    if (h.substr(0, 2) == "PK")
        return "acmi-zip";
    if (h.substr(0, 6) == "7z\xBC\xAF\x27\x1C")
        return "7z";
    if (h.substr(0, 3) == "\xEF\xBB\xBF")
        h.remove_prefix(3);
    while (!h.empty() && (h.front() == '\n' || h.front() == '\r' || h.front() == ' ' || h.front() == '\t'))
        h.remove_prefix(1);
    if (h.substr(0, 9) == "FileType=")
        return "acmi-text";
    if (!h.empty() && h.front() == 'A' &&
        (h.find("\nB") != std::string_view::npos || h.find("\nH") != std::string_view::npos ||
         head.size() < 4096))
        return "igc";
    // The CSV flight format: comments (#) and blank lines, then the time_s header.
    while (!h.empty()) {
        const size_t nl = h.find('\n');
        std::string_view line = h.substr(0, nl);
        size_t i = 0;
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
            ++i;
        line.remove_prefix(i);
        if (!line.empty() && line.front() != '#' && line != "\r")
            return line.substr(0, 6) == "time_s" ? "csv" : "";
        if (nl == std::string_view::npos)
            break;
        h.remove_prefix(nl + 1);
    }
    return "";
}

Recording readRecording(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw RecordingError(file.string(), 0, "", "no such file");
    const std::string format = detectFormat(file);
    if (format == "7z")
        throw RecordingError(
            file.string(), 0, "",
            "a 7z-compressed ACMI is not read here; extract it (7z x) and pass the .txt.acmi");
    if (format == "acmi-zip") {
        AcmiParser parser(file.string());
        parseZip(file, parser);
        Recording r = parser.finish();
        r.format = "acmi-zip";
        return r;
    }
    if (format == "acmi-text") {
        AcmiParser parser(file.string());
        std::ifstream in(file, std::ios::binary);
        std::vector<char> buf(CHUNK);
        while (in) {
            in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
            const std::streamsize got = in.gcount();
            if (got <= 0)
                break;
            parser.feed(std::string_view(buf.data(), static_cast<size_t>(got)));
        }
        if (in.bad())
            throw RecordingError(file.string(), 0, "", "read error");
        return parser.finish();
    }
    if (format == "igc") {
        const uintmax_t size = std::filesystem::file_size(file, ec);
        if (ec || size > RecordingLimits::MAX_IGC_BYTES)
            throw RecordingError(file.string(), 0, "",
                                 ec ? "cannot read its size: " + ec.message()
                                    : "IGC file of " + std::to_string(size >> 20) + " MiB, larger than " +
                                          std::to_string(RecordingLimits::MAX_IGC_BYTES >> 20) +
                                          " MiB; refused before reading it");
        std::ifstream in(file, std::ios::binary);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        return parseIgc(text, file.string());
    }
    if (format == "csv")
        throw RecordingError(file.string(), 0, "",
                             "this is a Pacifica flight CSV, not a recording (read it with FlightPath)");
    throw RecordingError(file.string(), 0, "",
                         "unrecognised flight file format; supported: " + supportedFormats());
}

} // namespace pacifica::recording
