// IGC flight recorder files (FAI, "Technical Specification for IGC-approved GNSS flight recorders", Appendix
// A): A (manufacturer), H (headers: HFDTE date in both spellings, pilot, glider type and id), I (extension
// layout), B (fixes: B HHMMSS DDMMmmmN DDDMMmmmE V PPPPP GGGGG, then extensions). Times are UTC; a time that
// runs back by more than an hour is the next day (midnight rollover), a smaller step back is a logger glitch
// and the fix is skipped (counted in the log). Altitude: GNSS when non-zero, else pressure (ISA).
#include "recording/Recording.h"

#include <cmath>
#include <cstdio>

namespace pacifica::recording {

namespace {

bool digits(std::string_view s, int& out) {
    out = 0;
    if (s.empty())
        return false;
    for (char c : s) {
        if (c < '0' || c > '9')
            return false;
        out = out * 10 + (c - '0');
    }
    return true;
}

/// "-0037" / "00512" (5 characters; a leading '-' allowed).
bool altitude(std::string_view s, int& out) {
    if (s.size() != 5)
        return false;
    if (s[0] == '-') {
        if (!digits(s.substr(1), out))
            return false;
        out = -out;
        return true;
    }
    return digits(s, out);
}

std::string latin1ToUtf8(std::string_view s) {
    std::string out;
    bool ascii = true, validUtf8 = true;
    for (size_t i = 0; i < s.size(); ++i) {
        const auto c = static_cast<unsigned char>(s[i]);
        if (c < 0x80)
            continue;
        ascii = false;
        const int len = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
        if (len == 0 || i + static_cast<size_t>(len) > s.size()) {
            validUtf8 = false;
            break;
        }
        for (int k = 1; k < len; ++k)
            if ((static_cast<unsigned char>(s[i + static_cast<size_t>(k)]) & 0xC0) != 0x80)
                validUtf8 = false;
        i += static_cast<size_t>(len - 1);
    }
    if (ascii || validUtf8)
        return std::string(s);
    for (char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        if (c < 0x80)
            out.push_back(ch);
        else {
            out.push_back(static_cast<char>(0xC0 | (c >> 6)));
            out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
        }
    }
    return out;
}

std::string_view trimmed(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

/// The value of an H record "HFPLTPILOTINCHARGE:Jane Doe" (after the colon; "" if none).
std::string headerValue(std::string_view line) {
    const size_t colon = line.find(':');
    return colon == std::string_view::npos ? std::string() : latin1ToUtf8(trimmed(line.substr(colon + 1)));
}

} // namespace

namespace {

/// "YYYY-MM-DDTHH:MM:SSZ" of a Unix time (civil from days, Hinnant).
std::string isoUtc(double unix) {
    const auto t = static_cast<long long>(unix);
    const long long days = t / 86400, rem = t % 86400;
    const long long z = days + 719468, era = z / 146097, doe = z - era * 146097;
    const long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    const long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100), mp = (5 * doy + 2) / 153;
    const long long d = doy - (153 * mp + 2) / 5 + 1, m = mp < 10 ? mp + 3 : mp - 9,
                    y = yoe + era * 400 + (m <= 2);
    char iso[96];
    std::snprintf(iso, sizeof iso, "%04lld-%02lld-%02lldT%02lld:%02lld:%02lldZ", y, m, d, rem / 3600,
                  rem / 60 % 60, rem % 60);
    return iso;
}

/// One IGC file's records, line by line: H headers (date, datum, pilot, glider, callsign) and B fixes.
struct IgcReader {
    const std::string& source;
    Recording rec;
    RecordedObject o;
    std::optional<double> dayUnix; // 00:00 UTC of the flight's date
    double firstSeconds = 0.0, lastSeconds = -1.0, dayOffset = 0.0;
    long long lineNo = 0;

    RecordingError fail(const char* field, const std::string& msg) const {
        return RecordingError(source, lineNo, field, msg);
    }

    /// "HFDTE150717" or "HFDTEDATE:150717,01".
    void date(std::string_view line) {
        std::string_view d = line.substr(5);
        const size_t colon = d.find(':');
        if (colon != std::string_view::npos)
            d = d.substr(colon + 1);
        d = trimmed(d.substr(0, 6));
        int dd = 0, mm = 0, yy = 0;
        if (d.size() != 6 || !digits(d.substr(0, 2), dd) || !digits(d.substr(2, 2), mm) ||
            !digits(d.substr(4, 2), yy) || dd < 1 || dd > 31 || mm < 1 || mm > 12)
            throw fail("HFDTE", "expected the date as DDMMYY, got '" + std::string(line.substr(5, 20)) + "'");
        char iso[48];
        std::snprintf(iso, sizeof iso, "%04d-%02d-%02dT00:00:00Z", yy < 80 ? 2000 + yy : 1900 + yy, mm, dd);
        dayUnix = parseIsoUtc(iso);
    }

    void header(std::string_view line) {
        const std::string_view key = line.substr(0, std::min<size_t>(line.size(), 5));
        if (key == "HFDTE" || key == "HPDTE")
            return date(line);
        // HxPLT, HxGTY, ... (a header shorter than its key is ignored, like any unknown header)
        const std::string_view tag = line.size() >= 5 ? line.substr(2, 3) : std::string_view{};
        if (tag == "ALG") { // HFALGALTGPS:GEO / ELL (the GNSS altitude datum)
            const std::string datum = headerValue(line);
            if (datum.rfind("ELL", 0) == 0 || datum.rfind("GEO", 0) == 0)
                rec.altitudeDatum = datum.substr(0, 3);
        } else if (tag == "PLT")
            o.pilot = headerValue(line);
        else if (tag == "GTY")
            o.name = headerValue(line);
        else if (tag == "CID" || (tag == "GID" && o.callsign.empty()))
            o.callsign = headerValue(line);
    }

    /// A B record's fix: time, position, validity, pressure and GNSS altitudes, each checked.
    void fix(std::string_view line) {
        if (line.size() < 35)
            throw fail("B record", "a fix needs at least 35 characters, got " + std::to_string(line.size()));
        int hh = 0, mi = 0, ss = 0, latD = 0, latM = 0, lonD = 0, lonM = 0, pAlt = 0, gAlt = 0;
        if (!digits(line.substr(1, 2), hh) || !digits(line.substr(3, 2), mi) ||
            !digits(line.substr(5, 2), ss) || hh > 23 || mi > 59 || ss > 60)
            throw fail("B time", "expected HHMMSS, got '" + std::string(line.substr(1, 6)) + "'");
        if (!digits(line.substr(7, 2), latD) || !digits(line.substr(9, 5), latM) || latD > 90 ||
            latM >= 60000 || (line[14] != 'N' && line[14] != 'S'))
            throw fail("B latitude", "expected DDMMmmmN/S, got '" + std::string(line.substr(7, 8)) + "'");
        if (!digits(line.substr(15, 3), lonD) || !digits(line.substr(18, 5), lonM) || lonD > 180 ||
            lonM >= 60000 || (line[23] != 'E' && line[23] != 'W'))
            throw fail("B longitude", "expected DDDMMmmmE/W, got '" + std::string(line.substr(15, 9)) + "'");
        if (line[24] != 'A' && line[24] != 'V')
            throw fail("B validity", std::string("expected A or V, got '") + line[24] + "'");
        if (!altitude(line.substr(25, 5), pAlt))
            throw fail("B pressure altitude",
                       "expected 5 digits, got '" + std::string(line.substr(25, 5)) + "'");
        if (!altitude(line.substr(30, 5), gAlt))
            throw fail("B GNSS altitude", "expected 5 digits, got '" + std::string(line.substr(30, 5)) + "'");
        const double lat = (latD + latM / 60000.0) * (line[14] == 'S' ? -1.0 : 1.0);
        const double lon = (lonD + lonM / 60000.0) * (line[23] == 'W' ? -1.0 : 1.0);
        if (std::abs(lat) > 90.0 || std::abs(lon) > 180.0)
            throw fail("B latitude", "position out of range");
        addFix(hh * 3600.0 + mi * 60.0 + ss + dayOffset, lat, lon, gAlt != 0 ? gAlt : pAlt);
    }

    /// Time order: a fix earlier by more than an hour is past midnight UTC; a smaller step back is a logger
    /// glitch and a repeated time a repeated fix (both dropped). alt: GNSS altitude (00000 = no data), else
    /// pressure altitude.
    void addFix(double seconds, double lat, double lon, int alt) {
        if (lastSeconds >= 0.0 && seconds < lastSeconds) {
            if (lastSeconds - seconds > 3600.0) {
                dayOffset += 86400.0;
                seconds += 86400.0;
            } else {
                return;
            }
        }
        if (lastSeconds >= 0.0 && seconds == lastSeconds)
            return;
        if (lastSeconds < 0.0)
            firstSeconds = seconds;
        lastSeconds = seconds;
        ObjectSample s;
        s.time = seconds - firstSeconds;
        s.lat = lat;
        s.lon = lon;
        s.alt = alt;
        o.track.push_back(s);
    }

    Recording finish(bool sawA) {
        if (!sawA)
            throw RecordingError(source, 0, "", "empty file: not an IGC file");
        if (o.track.size() < 2)
            throw RecordingError(source, 0, "B record",
                                 "an IGC flight needs at least 2 fixes, got " +
                                     std::to_string(o.track.size()));
        if (dayUnix) {
            rec.referenceUnix = *dayUnix + firstSeconds;
            rec.referenceTime = isoUtc(*rec.referenceUnix);
        }
        if (o.name.empty())
            o.name = "glider";
        deriveAttitude(o);
        rec.samples = static_cast<long long>(o.track.size());
        rec.startTime = o.track.front().time;
        rec.endTime = o.track.back().time;
        rec.lines = lineNo;
        rec.title = "IGC " + o.name + (o.pilot.empty() ? "" : " (" + o.pilot + ")");
        rec.objects.push_back(std::move(o));
        return std::move(rec);
    }
};

} // namespace

Recording parseIgc(std::string_view text, const std::string& source) {
    IgcReader r{source};
    r.rec.source = source;
    r.rec.format = "igc";
    r.rec.fileVersion = "IGC";
    r.rec.bytes = text.size();
    r.o.id = 1;
    r.o.type = "Air+FixedWing";
    r.o.line = 1;
    bool sawA = false;
    size_t pos = 0;
    while (pos < text.size()) {
        const size_t nl = text.find('\n', pos);
        std::string_view line =
            text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
        pos = nl == std::string_view::npos ? text.size() : nl + 1;
        ++r.lineNo;
        if (!line.empty() && line.back() == '\r')
            line.remove_suffix(1);
        if (r.lineNo == 1 && line.substr(0, 3) == "\xEF\xBB\xBF")
            line.remove_prefix(3);
        if (line.empty())
            continue;
        if (!sawA) {
            if (line.front() != 'A')
                throw r.fail("A record",
                             "not an IGC file: the first record must be the A (manufacturer) record");
            sawA = true;
        } else if (line.front() == 'H') {
            r.header(line);
        } else if (line.front() == 'B') {
            r.fix(line);
        } // I, J, C, L, E, F, G, K records: not needed for the track
    }
    return r.finish(sawA);
}

} // namespace pacifica::recording
