// Unit tests for pacifica_recording: the ACMI reader (every T= form, escapes, continuations, removals,
// events, BOM, CRLF, zip, malformed lines naming file:line and field), the IGC reader (both HFDTE spellings,
// midnight rollover, derived attitude), format detection, the WGS84 world frame against GeographicLib's exact
// local ENU, camera rigs and object selection, and which recorded objects drive the sea. The real DCS
// recording in the shared data directory ($PACIFICA_SHARED_DIR) is read too, when it is there.
#include "SharedData.h"
#include <recording/AcmiWriter.h>
#include <recording/CameraRig.h>
#include <recording/EarthFrame.h>
#include <recording/LandMask.h>
#include <recording/Recording.h>
#include <recording/SeaDrivers.h>

#include <GeographicLib/LocalCartesian.hpp>
#include <gtest/gtest.h>
#include <zip.h>

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace pacifica::recording;
using pacifica::Pose;

const char* HEADER = "FileType=text/acmi/tacview\nFileVersion=2.2\n";

Recording acmi(const std::string& text, size_t chunk = 0) {
    AcmiParser p("t.acmi");
    if (chunk == 0)
        p.feed(text);
    else
        for (size_t i = 0; i < text.size(); i += chunk)
            p.feed(std::string_view(text).substr(i, chunk));
    return p.finish();
}

std::string acmiError(const std::string& text) {
    try {
        acmi(text);
    } catch (const RecordingError& e) {
        return e.what();
    }
    return "";
}

fs::path tempDir() {
    fs::path d = fs::temp_directory_path() / ("pacifica-rec-" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
}

void writeFile(const fs::path& p, const std::string& s) {
    std::ofstream(p, std::ios::binary) << s;
}

TEST(Acmi, TransformFormsAndEmptyFields) {
    const std::string text = std::string(HEADER) +
                             "0,ReferenceLongitude=30\n0,ReferenceLatitude=40\n"
                             "#1\n"
                             "a1,T=1|2|100|10|5|90|7|8|91,Type=Air+FixedWing,Name=Hornet\n"
                             "#2\n"
                             "a1,T=1.5||200|333|444\n" // 5 fields: lon|lat|alt|U|V -- no attitude
                             "#3\n"
                             "a1,T=|2.5|\n" // 3 fields, only latitude
                             "#4\n"
                             "a1,T=||||20||\n" // 6 fields: pitch only... (7 fields is invalid, see below)
        ;
    // "||||20||" has 7 fields: invalid. Use a 6-field update instead.
    const std::string fixed = text.substr(0, text.rfind("a1,T=||||20||")) + "a1,T=|||-3|20|\n";
    const Recording r = acmi(fixed);
    ASSERT_EQ(r.objects.size(), 1u);
    const RecordedObject& o = r.objects[0];
    EXPECT_EQ(o.name, "Hornet");
    EXPECT_EQ(o.attitude, "recorded");
    ASSERT_EQ(o.track.size(), 4u);
    EXPECT_DOUBLE_EQ(o.track[0].lon, 31.0);
    EXPECT_DOUBLE_EQ(o.track[0].lat, 42.0);
    EXPECT_FLOAT_EQ(o.track[0].yaw, 90.0f);
    EXPECT_DOUBLE_EQ(o.track[1].lon, 31.5);
    EXPECT_DOUBLE_EQ(o.track[1].lat, 42.0); // empty = unchanged
    EXPECT_DOUBLE_EQ(o.track[1].alt, 200.0);
    EXPECT_FLOAT_EQ(o.track[1].roll, 10.0f); // U|V were not taken as angles
    EXPECT_FLOAT_EQ(o.track[1].pitch, 5.0f);
    EXPECT_DOUBLE_EQ(o.track[2].lat, 42.5);
    EXPECT_DOUBLE_EQ(o.track[2].alt, 200.0);
    EXPECT_FLOAT_EQ(o.track[3].roll, -3.0f);
    EXPECT_FLOAT_EQ(o.track[3].pitch, 20.0f);
    EXPECT_FLOAT_EQ(o.track[3].yaw, 90.0f);
    EXPECT_DOUBLE_EQ(r.startTime, 1.0);
    EXPECT_DOUBLE_EQ(r.endTime, 4.0);
    EXPECT_EQ(acmiError(text), "t.acmi:12: T: expected 3, 5, 6 or 9 '|'-separated fields, got 7");
}

TEST(Acmi, NumbersReadExactlyAsFromChars) {
    // The reader's fast decimal path (Clinger) must give the same doubles as std::from_chars.
    std::string text = std::string(HEADER);
    std::vector<std::string> alts;
    uint64_t state = 7;
    for (int i = 0; i < 2000; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        const int decimals = static_cast<int>((state >> 20) % 12);
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s%.*f", (state >> 40) % 3 == 0 ? "-" : "", decimals,
                      static_cast<double>(state >> 24) / 1e6);
        alts.push_back(buf);
        // At the end of the line and before a '|' (the reader reads digits 8 bytes at a time when 8 are
        // readable, so both a field's end and the line's end must stop it right).
        text +=
            "#" + std::to_string(i) + "\n1,T=0|0|" + alts.back() + "\n2,T=0|0|0|" + alts.back() + "|0|0\n";
    }
    alts.push_back("1e3");
    text += "#2000\n1,T=0|0|1e3\n2,T=0|0|0|1e3|0|0\n";
    const Recording r = acmi(text);
    ASSERT_EQ(r.objects.at(0).track.size(), alts.size());
    ASSERT_EQ(r.objects.at(1).track.size(), alts.size());
    for (size_t i = 0; i < alts.size(); ++i) {
        double want = 0.0;
        std::from_chars(alts[i].data(), alts[i].data() + alts[i].size(), want);
        ASSERT_EQ(r.objects[0].track[i].alt, want) << alts[i];
        ASSERT_EQ(r.objects[1].track[i].roll, static_cast<float>(want)) << alts[i];
    }
}

TEST(Acmi, FastAndSlowNumberFormsMixInOneTransform) {
    // Fields read in the scan that splits T= (plain decimals) next to ones that need from_chars (exponent,
    // '+' sign, long mantissa), empty fields, and U|V|heading that are skipped unread (even when odd).
    const Recording r = acmi(std::string(HEADER) + "#1\n1,T=1e-1|+2.5|-0.125|1.5e1|-3|+4|x|y|z\n" +
                             "#2\n1,T=|0.12345678901234567|7||2|\n");
    const auto& t = r.objects.at(0).track;
    ASSERT_EQ(t.size(), 2u);
    EXPECT_EQ(t[0].lon, 0.1);
    EXPECT_EQ(t[0].lat, 2.5);
    EXPECT_EQ(t[0].alt, -0.125);
    EXPECT_EQ(t[0].roll, 15.0f);
    EXPECT_EQ(t[0].pitch, -3.0f);
    EXPECT_EQ(t[0].yaw, 4.0f);
    EXPECT_EQ(t[1].lon, 0.1); // empty: unchanged
    EXPECT_EQ(t[1].lat, 0.12345678901234567);
    EXPECT_EQ(t[1].alt, 7.0);
    EXPECT_EQ(t[1].roll, 15.0f);
    EXPECT_EQ(t[1].pitch, 2.0f);
    EXPECT_EQ(t[1].yaw, 4.0f);
    EXPECT_NE(acmiError(std::string(HEADER) + "1,T=1|2x|3\n").find("T latitude: expected a number, got '2x'"),
              std::string::npos);
    // The reference is added as samples are stored; one set after the first sample still applies to all.
    const Recording late =
        acmi(std::string(HEADER) + "0,ReferenceLongitude=179\n1,T=0.5|1|0\n#1\n1,T=2|1|0\n" +
             "0,ReferenceLongitude=-170\n0,ReferenceLatitude=40\n#2\n2,T=1|1|1\n");
    ASSERT_EQ(late.objects.size(), 2u);
    EXPECT_EQ(late.objects[0].track[0].lon, -169.5);
    EXPECT_EQ(late.objects[0].track[1].lon, -168.0);
    EXPECT_EQ(late.objects[0].track[1].lat, 41.0);
    EXPECT_EQ(late.objects[1].track[0].lon, -169.0);
    EXPECT_EQ(late.objects[1].track[0].lat, 41.0);
    EXPECT_NE(acmiError(std::string(HEADER) + "0,ReferenceLatitude=89\n#0\n1,T=0|2|0\n")
                  .find("t.acmi:5: T latitude: object 1 (no type) has latitude 91.000000 (reference + "
                        "offset) outside"),
              std::string::npos);
    EXPECT_NE(
        acmiError(std::string(HEADER) + "1,T=0|2|0\n0,ReferenceLatitude=89\n").find("outside [-90, 90]"),
        std::string::npos);
}

TEST(Acmi, ManyObjectsRemovedAndIdsReused) {
    // The id index under load: 20000 ids, every third removed, removed ids reused by new objects; each
    // object keeps its own track and removal time (probe runs shifted back on removal stay findable).
    std::string text = std::string(HEADER) + "#0\n";
    const int N = 20000;
    for (int i = 1; i <= N; ++i)
        text += hexId(static_cast<uint64_t>(i) * 7919u) + ",T=1|2|" + std::to_string(i) + "\n";
    text += "#1\n";
    for (int i = 3; i <= N; i += 3)
        text += "-" + hexId(static_cast<uint64_t>(i) * 7919u) + "\n";
    text += "#2\n";
    for (int i = 1; i <= N; ++i)
        text += hexId(static_cast<uint64_t>(i) * 7919u) + ",T=||" + std::to_string(i + 1000000) + "\n";
    const Recording r = acmi(text, 4096);
    ASSERT_EQ(r.objects.size(), static_cast<size_t>(N + N / 3));
    for (int i = 1; i <= N; ++i) {
        const auto& o = r.objects[static_cast<size_t>(i - 1)];
        ASSERT_EQ(o.id, static_cast<uint64_t>(i) * 7919u);
        if (i % 3 == 0) {
            ASSERT_EQ(o.track.size(), 1u) << i;
            ASSERT_TRUE(o.removedAt.has_value());
            EXPECT_EQ(*o.removedAt, 1.0);
        } else {
            ASSERT_EQ(o.track.size(), 2u) << i;
            EXPECT_EQ(o.track[1].alt, i + 1000000.0);
            EXPECT_FALSE(o.removedAt.has_value());
        }
    }
    // The reused ids are new objects that start at t = 2 (their position fields were empty: zero).
    for (size_t k = static_cast<size_t>(N); k < r.objects.size(); ++k) {
        const auto& o = r.objects[k];
        ASSERT_EQ(o.id % 7919u, 0u);
        ASSERT_EQ(o.track.size(), 1u);
        EXPECT_EQ(o.track[0].time, 2.0);
        EXPECT_EQ(o.track[0].alt, static_cast<double>(o.id / 7919u) + 1000000.0);
    }
}

TEST(Acmi, BomCrlfCommentsEscapesContinuationsRemovalsEvents) {
    const std::string text = "\xEF\xBB\xBF"
                             "FileType=text/acmi/tacview\r\nFileVersion=2.1\r\n"
                             "// a comment\r\n"
                             "0,ReferenceTime=2020-12-26T21:04:15Z\r\n"
                             "0,Comments=line one\\\r\n"
                             "-5 looks like a removal\\\r\n"
                             "#99 looks like a frame\r\n"
                             "\r\n"
                             "1f,T=0.1|0.2|3,Type=Weapon+Missile,Name=A\\, B\r\n"
                             "#2.5\r\n"
                             "0,Event=Destroyed|1f|hit\r\n"
                             "#3\r\n"
                             "-1f\r\n"
                             "-77\r\n"; // removing an unknown id is harmless
    for (size_t chunk : {size_t(0), size_t(1), size_t(7)}) {
        const Recording r = acmi(text, chunk);
        EXPECT_EQ(r.fileVersion, "2.1");
        ASSERT_EQ(r.objects.size(), 1u) << chunk;
        const RecordedObject& o = r.objects[0];
        EXPECT_EQ(o.id, 0x1fu);
        EXPECT_EQ(o.name, "A, B");
        EXPECT_EQ(o.line, 9);
        ASSERT_TRUE(o.removedAt.has_value());
        EXPECT_DOUBLE_EQ(*o.removedAt, 3.0);
        ASSERT_TRUE(o.destroyedAt.has_value());
        EXPECT_DOUBLE_EQ(*o.destroyedAt, 2.5);
        ASSERT_EQ(r.events.size(), 1u);
        EXPECT_EQ(r.events[0].type, "Destroyed");
        ASSERT_EQ(r.events[0].objects.size(), 1u);
        EXPECT_EQ(r.events[0].objects[0], 0x1fu);
        EXPECT_EQ(r.events[0].text, "hit");
        EXPECT_EQ(r.events[0].line, 11);
        ASSERT_TRUE(r.referenceUnix.has_value());
        EXPECT_DOUBLE_EQ(*r.referenceUnix, 1609016655.0);
        EXPECT_EQ(r.lines, 14);
    }
    // An escape in one chunk and the end of its continued line in a later chunk without any backslash:
    // every split point must give the same object.
    const std::string cont = std::string(HEADER) + "1,T=1|2|3,Name=A\\, B\\\n,Pilot=P\n#1\n1,T=4||\n";
    for (size_t chunk = 1; chunk <= cont.size(); ++chunk) {
        const Recording r = acmi(cont, chunk);
        ASSERT_EQ(r.objects.size(), 1u) << chunk;
        EXPECT_EQ(r.objects[0].name, "A, B\n") << chunk;
        EXPECT_EQ(r.objects[0].pilot, "P") << chunk;
        EXPECT_EQ(r.objects[0].track.size(), 2u) << chunk;
    }
}

TEST(Acmi, MalformedInputNamesFileLineAndField) {
    EXPECT_EQ(acmiError("hello\n"),
              "t.acmi:1: not a Tacview ACMI file: the first line must be 'FileType=text/acmi/tacview'");
    EXPECT_EQ(acmiError("FileType=text/acmi/tacview\nFileVersion=3.0\n"),
              "t.acmi:2: FileVersion: unsupported version '3.0' (Tacview ACMI 2.x is supported)");
    EXPECT_EQ(acmiError(std::string(HEADER) + "#abc\n"),
              "t.acmi:3: frame time: expected a number, got 'abc'");
    EXPECT_EQ(
        acmiError(std::string(HEADER) + "#1\nzz,T=1|2|3\n"),
        "t.acmi:4: object id: expected a hexadecimal object id, a '#' frame time or a '-' removal, got 'zz'");
    EXPECT_EQ(acmiError(std::string(HEADER) + "1,T=1|x|3\n"),
              "t.acmi:3: T latitude: expected a number, got 'x'");
    EXPECT_EQ(acmiError(std::string(HEADER) + "1,T=1|nan|3\n"),
              "t.acmi:3: T latitude: value 'nan' is not finite or out of range");
    EXPECT_EQ(acmiError(std::string(HEADER) + "1,T=1|2|1e300\n"),
              "t.acmi:3: T altitude: value '1e300' is not finite or out of range");
    EXPECT_EQ(acmiError(std::string(HEADER) + "1,T=400|2|3\n"),
              "t.acmi:3: T longitude: longitude offset 400.000000 is out of range");
    EXPECT_EQ(
        acmiError(""),
        "t.acmi: not a Tacview ACMI file: missing the 'FileType=text/acmi/tacview' and 'FileVersion=2.x' "
        "header");
    // Unknown properties and events are never fatal.
    const Recording r =
        acmi(std::string(HEADER) + "1,T=1|2|3,Foo=bar,Weird,Type=Sea+Watercraft\n0,Event=X|y\n");
    EXPECT_EQ(r.objects[0].type, "Sea+Watercraft");
    EXPECT_EQ(r.events[0].type, "X");
}

TEST(Acmi, ZipAndDetection) {
    const fs::path dir = tempDir();
    const std::string text = std::string(HEADER) + "#0\n1,T=1|2|3,Type=Sea+Watercraft\n#10\n1,T=1.01|2|3\n";
    const fs::path zipPath = dir / "flight.acmi"; // a zip named like a text file: detected by content
    {
        int err = 0;
        zip_t* za = zip_open(zipPath.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
        ASSERT_NE(za, nullptr);
        zip_source_t* src = zip_source_buffer(za, text.data(), text.size(), 0);
        ASSERT_GE(zip_file_add(za, "flight.txt.acmi", src, ZIP_FL_OVERWRITE), 0);
        ASSERT_EQ(zip_close(za), 0);
    }
    EXPECT_EQ(detectFormat(zipPath), "acmi-zip");
    const Recording z = readRecording(zipPath);
    EXPECT_EQ(z.format, "acmi-zip");
    ASSERT_EQ(z.objects.size(), 1u);
    EXPECT_EQ(z.objects[0].track.size(), 2u);

    writeFile(dir / "t.txt.acmi", text);
    EXPECT_EQ(detectFormat(dir / "t.txt.acmi"), "acmi-text");
    writeFile(dir / "f.csv", "# c\ntime_s,x_m,y_m,z_m,heading_deg,pitch_deg,roll_deg\n");
    EXPECT_EQ(detectFormat(dir / "f.csv"), "csv");
    writeFile(dir / "x.7z", std::string("7z\xBC\xAF\x27\x1C", 6) + "rest");
    try {
        readRecording(dir / "x.7z");
        ADD_FAILURE() << "7z accepted";
    } catch (const RecordingError& e) {
        EXPECT_NE(std::string(e.what()).find("7z-compressed ACMI is not read here"), std::string::npos);
    }
    writeFile(dir / "junk.bin", "just some text\n");
    try {
        readRecording(dir / "junk.bin");
        ADD_FAILURE() << "junk accepted";
    } catch (const RecordingError& e) {
        EXPECT_EQ(std::string(e.what()),
                  (dir / "junk.bin").string() +
                      ": unrecognised flight file format; supported: " + supportedFormats());
    }
    // A member bigger than the 1 MiB buffers, deflated (inflated here with ISA-L) and stored (read by
    // libzip): both give the text file's recording; a damaged deflate stream is an error, not a short read.
    std::string big = std::string(HEADER);
    for (int f = 0; f < 3000; ++f) {
        big += "#" + std::to_string(f) + "\n";
        for (int k = 1; k <= 40; ++k)
            big += hexId(static_cast<uint64_t>(k)) + ",T=" + std::to_string(0.001 * f) + "|" +
                   std::to_string(0.5 + 0.0001 * k) + "|" + std::to_string(100 * k) + "\n";
    }
    ASSERT_GT(big.size(), size_t(3) << 20);
    writeFile(dir / "big.txt.acmi", big);
    const Recording want = readRecording(dir / "big.txt.acmi");
    for (const zip_int32_t method : {ZIP_CM_DEFLATE, ZIP_CM_STORE}) {
        const fs::path zp = dir / (method == ZIP_CM_STORE ? "stored.zip.acmi" : "deflated.zip.acmi");
        int err = 0;
        zip_t* za = zip_open(zp.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
        ASSERT_NE(za, nullptr);
        zip_source_t* src = zip_source_buffer(za, big.data(), big.size(), 0);
        const zip_int64_t idx = zip_file_add(za, "big.txt.acmi", src, ZIP_FL_OVERWRITE);
        ASSERT_GE(idx, 0);
        ASSERT_EQ(zip_set_file_compression(za, static_cast<zip_uint64_t>(idx), method, 0), 0);
        ASSERT_EQ(zip_close(za), 0);
        const Recording got = readRecording(zp);
        EXPECT_EQ(got.bytes, big.size());
        ASSERT_EQ(got.objects.size(), want.objects.size());
        for (size_t i = 0; i < want.objects.size(); ++i) {
            ASSERT_EQ(got.objects[i].track.size(), want.objects[i].track.size());
            EXPECT_EQ(got.objects[i].track.back().lat, want.objects[i].track.back().lat);
        }
    }
    {
        std::ifstream in(dir / "deflated.zip.acmi", std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        ASSERT_GT(bytes.size(), 4096u);
        bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x5A);
        writeFile(dir / "damaged.zip.acmi", bytes);
        try {
            readRecording(dir / "damaged.zip.acmi");
            ADD_FAILURE() << "damaged zip accepted";
        } catch (const RecordingError& e) {
            EXPECT_NE(std::string(e.what()).find("corrupt zip member"), std::string::npos) << e.what();
        }
    }
    {
        // The first deflate block's header made invalid (BFINAL 1, BTYPE 11, RFC 1951 3.2.3): named as such.
        std::ifstream in(dir / "deflated.zip.acmi", std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        ASSERT_EQ(bytes.substr(0, 4), std::string("PK\x03\x04"));
        auto u16 = [&](size_t at) {
            return static_cast<size_t>(static_cast<unsigned char>(bytes[at])) |
                   static_cast<size_t>(static_cast<unsigned char>(bytes[at + 1])) << 8;
        };
        const size_t data = 30 + u16(26) + u16(28); // local file header, name, extra (APPNOTE 4.3.7)
        bytes[data] = 0x07;
        writeFile(dir / "badblock.zip.acmi", bytes);
        try {
            readRecording(dir / "badblock.zip.acmi");
            ADD_FAILURE() << "invalid deflate block accepted";
        } catch (const RecordingError& e) {
            EXPECT_NE(std::string(e.what()).find("corrupt zip member: inflate: invalid deflate block"),
                      std::string::npos)
                << e.what();
        }
    }
    writeFile(dir / "bad.zip", "PK\x03\x04 not really a zip");
    EXPECT_THROW(readRecording(dir / "bad.zip"), RecordingError);
    fs::remove_all(dir);
}

std::string igcFix(int h, int m, int s, double lat, double lon, int alt) {
    char b[64];
    const int latD = static_cast<int>(lat), lonD = static_cast<int>(lon);
    const int latM = static_cast<int>(std::lround((lat - latD) * 60000.0));
    const int lonM = static_cast<int>(std::lround((lon - lonD) * 60000.0));
    std::snprintf(b, sizeof b, "B%02d%02d%02d%02d%05dN%03d%05dEA%05d%05d\n", h, m, s, latD, latM, lonD, lonM,
                  alt, alt + 10);
    return b;
}

TEST(Igc, DateSpellingsRolloverAndDerivedAttitude) {
    // A glider circling to the right (clockwise seen from above) at ~25 m/s across midnight UTC.
    std::string body;
    const double lat0 = 46.0, lon0 = 7.0, radius = 150.0, speed = 25.0;
    const double w = speed / radius; // rad/s
    int n = 0;
    for (int k = 0; k < 480; ++k) { // 1 s fixes, as loggers record
        const double t = k;
        const double a = w * t; // heading = a + 90 deg for a clockwise circle starting north of centre
        const double x = radius * std::sin(a), y = radius * std::cos(a);
        const double lat = lat0 + y / 111195.0, lon = lon0 + x / (111195.0 * std::cos(lat0 * M_PI / 180.0));
        const int secs = 23 * 3600 + 58 * 60 + static_cast<int>(t); // 23:58:00 onwards
        body += igcFix((secs / 3600) % 24, secs / 60 % 60, secs % 60, lat, lon, 1000 + k);
        ++n;
    }
    for (const std::string date : {"HFDTE150717\n", "HFDTEDATE:150717,01\n"}) {
        const std::string text = "AXXX001\n" + date +
                                 "HFPLTPILOTINCHARGE:Ana Ribeiro\nHFGTYGLIDERTYPE:ASK 21\n" +
                                 "I023638FXA3940SIU\n" + body;
        const Recording r = parseIgc(text, "g.igc");
        EXPECT_EQ(r.altitudeDatum, "");
        ASSERT_EQ(r.objects.size(), 1u);
        const RecordedObject& o = r.objects[0];
        EXPECT_EQ(o.pilot, "Ana Ribeiro");
        EXPECT_EQ(o.name, "ASK 21");
        ASSERT_EQ(o.track.size(), static_cast<size_t>(n));
        EXPECT_DOUBLE_EQ(o.track.back().time, n - 1.0); // rollover: no jump back by a day
        EXPECT_EQ(r.referenceTime, "2017-07-15T23:58:00Z");
        EXPECT_DOUBLE_EQ(o.track[5].alt, 1015.0); // GNSS altitude
        // Coordinated-turn bank atan(v w / g) = atan(25^2 / (150 g)) = 23.0 deg, right wing down.
        const ObjectSample mid = o.track[240];
        EXPECT_NEAR(mid.roll, std::atan(speed * w / 9.80665) * 180.0 / M_PI, 1.0);
        EXPECT_NEAR(mid.pitch, std::atan2(1.0, speed) * 180.0 / M_PI, 0.3); // climbing 1 m/s
        const double expectHeading = std::fmod(w * 240.0 * 180.0 / M_PI + 90.0, 360.0);
        EXPECT_NEAR(std::abs(std::remainder(mid.yaw - expectHeading, 360.0)), 0.0, 1.5);
    }
    // Errors name the line and the field.
    auto err = [](const std::string& text) {
        try {
            parseIgc(text, "g.igc");
        } catch (const RecordingError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(err("HFDTE150717\n"),
              "g.igc:1: A record: not an IGC file: the first record must be the A (manufacturer) record");
    EXPECT_EQ(err("AXXX\nHFDTE991317\n"), "g.igc:2: HFDTE: expected the date as DDMMYY, got '991317'");
    EXPECT_EQ(err("AXXX\nB1200004600000N00700000EA0100001000\nB1200104600000X00700000EA0100001000\n"),
              "g.igc:3: B latitude: expected DDMMmmmN/S, got '4600000X'");
    EXPECT_EQ(err("AXXX\nB120000\n"), "g.igc:2: B record: a fix needs at least 35 characters, got 7");
    EXPECT_EQ(parseIgc("AXXX\nHFALGALTGPS:ELL\n" + body, "g.igc").altitudeDatum, "ELL");
    EXPECT_EQ(parseIgc("AXXX\nHFALGALTGPS:GEO\n" + body, "g.igc").altitudeDatum, "GEO");
    // Found by fuzz_igc: headers shorter than their key are ignored, not read past their end.
    const Recording shortHeaders = parseIgc(
        "AXXX\nH\nHF\nB1200004600000N00700000EA0100001000\nB1200014600010N00700000EA0100101010\n", "g.igc");
    EXPECT_EQ(shortHeaders.objects.at(0).track.size(), 2u);
    EXPECT_EQ(err("AXXX\nB1200004600000N00700000EA0100001000\n"),
              "g.igc: B record: an IGC flight needs at least 2 fixes, got 1");
}

TEST(EarthFrame, MatchesExactLocalEnuWithinStatedBound) {
    const double lat0 = 44.9, lon0 = 36.8;
    const EarthFrame frame(lat0, lon0);
    const GeographicLib::LocalCartesian exact(lat0, lon0, 0.0);
    for (double dist : {1000.0, 10000.0, 100000.0}) {
        for (double az : {0.0, 37.0, 90.0, 200.0, 315.0}) {
            // A point on the sea (alt 0) dist metres away: find its lat/lon through the frame's inverse.
            double lat = 0, lon = 0, alt = 0;
            frame.toGeodetic({dist * std::sin(az * M_PI / 180.0), dist * std::cos(az * M_PI / 180.0), 0.0},
                             lat, lon, alt);
            const glm::dvec3 w = frame.toWorld(lat, lon, 0.0);
            EXPECT_NEAR(std::hypot(w.x, w.y), dist, 1e-6);
            double ex = 0, ey = 0, ez = 0;
            exact.Forward(lat, lon, 0.0, ex, ey, ez);
            // The renderer draws it at z = -d^2/2R seen from the origin: within 0.05 m at 1 km, 0.5 m at 10
            // km and 8 m at 100 km of the exact ellipsoid (sphere-vs-ellipsoid sagitta + d^3/6R^2 shrinkage).
            const double drawn = pacifica::drawnZ(w, {0, 0, 0});
            const double bound = dist <= 1000 ? 0.05 : dist <= 10000 ? 0.5 : 8.0;
            EXPECT_LT(std::abs(drawn - ez), bound) << dist << " " << az;
            EXPECT_LT(std::hypot(w.x - ex, w.y - ey), bound) << dist << " " << az;
        }
    }
    // An object at altitude 0, 100 km out, sits on the rendered sea from a camera above it and from the
    // origin.
    const glm::dvec3 ship = frame.toWorld(lat0 + 0.9, lon0, 0.0);
    EXPECT_GT(ship.y, 99000.0);
    EXPECT_DOUBLE_EQ(pacifica::drawnZ(ship, ship + glm::dvec3(0, 0, 500)), 0.0);
    // Meridian convergence at 100 km east, ~0.9 deg (recording/EarthFrame.h): true north is rotated in the
    // grid.
    double lat = 0, lon = 0, alt = 0;
    frame.toGeodetic({100000.0, 0.0, 0.0}, lat, lon, alt);
    const double conv = frame.gridHeading(lat, lon, 0.0);
    EXPECT_GT(std::abs(std::remainder(conv, 360.0)), 0.7);
    EXPECT_LT(std::abs(std::remainder(conv, 360.0)), 1.2);
    EXPECT_NEAR(frame.gridHeading(lat0, lon0, 123.0), 123.0, 1e-9);
}

Recording scene() {
    const std::string text =
        std::string(HEADER) +
        "0,ReferenceLongitude=36\n0,ReferenceLatitude=44\n"
        "#0\n"
        "101,T=0.5|0.5|0|0|0|90,Type=Sea+Watercraft+Warship,Name=ALBATROS\n"
        "201,T=0.51|0.5|0|0|0|90,Type=Sea+Watercraft+Warship,Name=ALBATROS\n"
        "301,T=0.52|0.52|0,Type=Sea+Watercraft,Name=Anchored\n"
        "d01,T=0.5|0.49|1000|0|0|0,Type=Air+FixedWing,Name=F-14B,Pilot=Ace,CallSign=Dodge1\n"
        "e01,T=0.5|0.49|900,Type=Weapon+Bomb,Name=Mk-82\n"
        "e02,T=0.5|0.49|30,Type=Weapon+Missile,Name=AGM\n"
        "e03,T=0.5|0.49|900,Type=Weapon+Rocket,Name=Rkt\n"
        "f01,T=0.5|0.49|50,Type=Misc+Decoy+Flare\n"
        "c01,T=0.5|0.49|50,Type=Ground+Heavy+Armor,Name=Tank\n"
        "#10\n"
        "101,T=0.505|0.5|0\n"
        "e01,T=0.5|0.4905|2\n"  // ends 2 m above the sea: at the sea
        "e02,T=0.5|0.4905|30\n" // level at 30 m when removed: in the air
        "e03,T=0.5|0.4905|300\n"
        "#10.5\n"
        "e03,T=0.5|0.491|20\n" // 560 m/s descent: reaches the sea within 0.04 s
        "#11\n"
        "-e01\n-e02\n-e03\n"
        "#20\n"
        "d01,T=0.6|0.49|3\n"
        "0,Event=Destroyed|d01|\n"
        "-d01\n";
    return acmi(text);
}

TEST(SeaDrivers, ShipsImpactsAndLeftOutWithReasons) {
    const Recording r = scene();
    const EarthFrame frame = chooseFrame(r, nullptr, 0.0);
    const SeaDrivers d = seaDrivers(r, frame);
    ASSERT_EQ(d.ships.size(), 3u);
    EXPECT_DOUBLE_EQ(d.ships[0].length, 150.0);
    EXPECT_DOUBLE_EQ(d.ships[2].length, 60.0);
    ASSERT_EQ(d.ships[0].samples.size(), 2u);
    // 0.005 deg of longitude at 44.5 N in 10 s: ~39.7 m/s
    const glm::dvec3 a = d.ships[0].samples[0], b = d.ships[0].samples[1];
    EXPECT_NEAR(std::hypot(b.y - a.y, b.z - a.z) / (b.x - a.x), 39.7, 0.5);
    ASSERT_EQ(d.ships[2].samples.size(), 2u); // anchored: seen once, stays put (no wake: speed 0)
    EXPECT_EQ(d.ships[2].samples[0].y, d.ships[2].samples[1].y);

    ASSERT_EQ(d.impacts.size(), 3u);
    EXPECT_EQ(d.impacts[0].id, 0xe01u); // both removed at 11 s: file order
    EXPECT_DOUBLE_EQ(d.impacts[0].time, 11.0);
    EXPECT_DOUBLE_EQ(d.impacts[0].strength, 1.0);
    EXPECT_EQ(d.impacts[0].cause, "removed at the sea surface");
    EXPECT_EQ(d.impacts[1].id, 0xe03u); // last seen 20 m up at 560 m/s down: extrapolated to the sea
    EXPECT_DOUBLE_EQ(d.impacts[1].strength, 0.05);
    EXPECT_EQ(d.impacts[2].id, 0xd01u);
    EXPECT_DOUBLE_EQ(d.impacts[2].time, 20.0);
    EXPECT_EQ(d.impacts[2].cause, "destroyed at the sea surface");
    const glm::dvec3 bombAt = frame.toWorld(44.4905, 36.5, 0.0);
    EXPECT_NEAR(d.impacts[0].position.x, bombAt.x, 1e-6);
    EXPECT_NEAR(d.impacts[0].position.y, bombAt.y, 1e-6);
    // The rocket: 0.0005 deg north (55.6 m) over 280 m of descent; 20 m more down puts it 3.97 m further.
    const glm::dvec3 r1 = frame.toWorld(44.491, 36.5, 0.0);
    EXPECT_NEAR(d.impacts[1].position.y - r1.y, 55.6 * 20.0 / 280.0, 0.05);

    EXPECT_EQ(d.byType.at("Weapon+Missile").leftOut.at("ended above the sea (over land or in the air)"), 1);
    EXPECT_EQ(d.byType.at("Misc+Decoy+Flare").leftOut.at("not a ship, weapon or aircraft"), 1);
    EXPECT_EQ(d.byType.at("Ground+Heavy+Armor").leftOut.at("ground object"), 1);
    EXPECT_EQ(d.byType.at("Sea+Watercraft+Warship").ships, 2);
    EXPECT_EQ(d.byType.at("Air+FixedWing").explosions, 1);
}

TEST(LandMask, GshhgShorelinesTellLandFromWater) {
    // Debian's gmt-gshhg-low (installed by ./pacifica deps) holds the GSHHG binned shorelines.
    const std::optional<LandMask> mask = LandMask::loadDefault();
    ASSERT_TRUE(mask.has_value()) << "no GSHHG file: apt-get install gmt-gshhg-low";
    struct Place {
        const char* name;
        double lat, lon;
        bool land;
    };
    for (const Place& p :
         {Place{"Black Sea", 43.5, 34.0, false}, Place{"Anapa, inland", 45.0, 37.6, true},
          Place{"Crimea", 45.3, 34.3, true}, Place{"Sea of Azov", 46.0, 36.5, false},
          Place{"Caspian (a lake: water)", 42.0, 50.5, false}, Place{"Atlantic", 30.0, -40.0, false},
          Place{"Sahara", 25.0, 10.0, true}, Place{"Lake Victoria", -1.0, 33.0, false},
          Place{"Greenland", 72.0, -40.0, true}, Place{"Pacific", 0.0, -150.0, false},
          Place{"London", 51.5, -0.1, true}, Place{"North Sea", 55.0, 3.0, false},
          Place{"the DCS carrier group", 44.616, 36.885, false}})
        EXPECT_EQ(mask->isLand(p.lat, p.lon), p.land) << p.name;
    EXPECT_EQ(mask->isLand(43.5, 34.0 + 360.0), false); // longitudes wrap
    EXPECT_FALSE(mask->isLand(NAN, 0.0));
    EXPECT_THROW(LandMask("/nonexistent/binned_GSHHS_l.nc"), RecordingError);

    // A bomb removed at sea level over land (Anapa, inland) is left out by position, not exploded.
    const std::string text =
        std::string(HEADER) +
        "0,ReferenceLongitude=36\n0,ReferenceLatitude=44\n#0\n"
        "e1,T=1.6|1.0|2,Type=Weapon+Bomb\ne2,T=-2|-0.5|2,Type=Weapon+Bomb\n#1\n-e1\n-e2\n";
    const Recording r = acmi(text);
    const EarthFrame frame = chooseFrame(r, nullptr, 0.0);
    const SeaDrivers withMask = seaDrivers(r, frame, &*mask);
    ASSERT_EQ(withMask.impacts.size(), 1u);
    EXPECT_EQ(withMask.impacts[0].id, 0xe2u); // 43.5 N 34 E: the Black Sea
    EXPECT_EQ(withMask.byType.at("Weapon+Bomb").leftOut.at("ended over land (GSHHG shoreline)"), 1);
    EXPECT_EQ(seaDrivers(r, frame).impacts.size(), 2u); // without shorelines both count as at the sea
}

TEST(CameraRig, SelectionErrorsAndPoses) {
    const Recording r = scene();
    EXPECT_EQ(selectObject(r, "F-14B").id, 0xd01u);
    EXPECT_EQ(selectObject(r, "ace").id, 0xd01u);
    EXPECT_EQ(selectObject(r, "DODGE1").id, 0xd01u);
    EXPECT_EQ(selectObject(r, "0x201").id, 0x201u);
    try {
        selectObject(r, "ALBATROS");
        ADD_FAILURE();
    } catch (const RigError& e) {
        EXPECT_EQ(std::string(e.what()), "object 'ALBATROS' is ambiguous; name one by id:\n"
                                         "  101 Sea+Watercraft+Warship 'ALBATROS'\n"
                                         "  201 Sea+Watercraft+Warship 'ALBATROS'");
    }
    try {
        selectObject(r, "Tomcat");
        ADD_FAILURE();
    } catch (const RigError& e) {
        EXPECT_NE(std::string(e.what()).find("no object 'Tomcat'"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("d01 Air+FixedWing 'F-14B' pilot 'Ace' callsign 'Dodge1'"),
                  std::string::npos);
    }
    EXPECT_THROW(parseRigSpec("dolly:F-14B"), RigError);
    EXPECT_THROW(parseRigSpec("chase"), RigError);
    EXPECT_THROW(parseRigSpec("chase:F-14B,distance"), RigError);

    const RecordedObject& jet = selectObject(r, "F-14B");
    const EarthFrame frame = chooseFrame(r, &jet, 0.0);
    const glm::dvec3 at0 = frame.toWorld(44.49, 36.5, 1000.0);
    EXPECT_NEAR(glm::length(at0 - glm::dvec3(0, 0, 1000)), 0.0, 1e-6); // the origin is under the focus

    // Cockpit: the object's pose plus the eye offset in body axes (heading 0: forward is north).
    auto cockpit = makeRig(parseRigSpec("cockpit:d01,forward=5,up=1"), r, frame);
    const Pose c = cockpit->poseAt(0.0);
    EXPECT_NEAR(c.position.y, 5.0, 1e-6);
    EXPECT_NEAR(c.position.z, 1001.0, 1e-6);
    EXPECT_NEAR(c.headingDeg, 0.0, 1e-6);
    EXPECT_DOUBLE_EQ(cockpit->startTime(), 0.0);
    EXPECT_DOUBLE_EQ(cockpit->endTime(), 20.0);

    // Chase: behind (south of a north-facing jet) and above, looking at it.
    auto chase = makeRig(parseRigSpec("chase:F-14B,distance=50,height=10,smoothing=0"), r, frame);
    const Pose ch = chase->poseAt(0.0);
    EXPECT_NEAR(ch.position.y, -50.0, 1e-6);
    EXPECT_NEAR(ch.position.z, 1010.0, 1e-6);
    EXPECT_NEAR(ch.headingDeg, 0.0, 1e-6);
    EXPECT_NEAR(ch.pitchDeg, -std::atan2(10.0, 50.0) * 180.0 / M_PI, 1e-3);
    // Same pose whatever frame rate reached it (a pure function of t).
    EXPECT_EQ(chase->poseAt(7.3).position, chase->poseAt(7.3).position);

    // Orbit: at distance and elevation, looking back at the object.
    auto orbit = makeRig(parseRigSpec("orbit:d01,distance=200,elevation=30,rate=10"), r, frame);
    const Pose o1 = orbit->poseAt(9.0); // azimuth 90 deg: east of the jet
    const glm::dvec3 jet9 = frame.toWorldPose(jet.sampleAt(9.0)).position;
    EXPECT_NEAR(glm::length(o1.position - jet9), 200.0, 0.01);
    EXPECT_NEAR(o1.position.z - jet9.z, 100.0, 0.01);
    EXPECT_NEAR(o1.headingDeg, 270.0, 0.05);

    // lookat from a ship toward the jet; unknown keys and bad values name the key.
    auto look = makeRig(parseRigSpec("lookat:101,target=F-14B"), r, frame);
    EXPECT_GT(look->poseAt(0.0).pitchDeg, 0.0);
    EXPECT_THROW(makeRig(parseRigSpec("lookat:101"), r, frame), RigError);
    try {
        makeRig(parseRigSpec("orbit:d01,radius=5"), r, frame);
        ADD_FAILURE();
    } catch (const RigError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown key 'radius' for orbit"), std::string::npos);
    }
    EXPECT_THROW(makeRig(parseRigSpec("chase:d01,distance=nan"), r, frame), RigError);
    // A bomb recorded with 3-field T= only: no angles until a rig derives them from its track (falling
    // 898 m while drifting 55.6 m north in 10 s: heading north, pitch atan2(-89.8, 5.56) = -86.5 deg).
    EXPECT_EQ(selectObject(r, "Mk-82").attitude, "none");
    auto bomb = makeRig(parseRigSpec("cockpit:Mk-82,up=0"), r, frame);
    const Pose b = bomb->poseAt(5.0);
    EXPECT_NEAR(b.pitchDeg, std::atan2(-89.8, 5.56) * 180.0 / M_PI, 0.5);
    EXPECT_NEAR(std::abs(std::remainder(b.headingDeg, 360.0)), 0.0, 1.0);
    auto fixed = makeRig(parseRigSpec("fixed:d01,east=100,north=0,up=0"), r, frame);
    EXPECT_NEAR(fixed->poseAt(0.0).headingDeg, 270.0, 0.01);
}

void expectSameRecording(const Recording& a, const Recording& b) {
    ASSERT_EQ(a.objects.size(), b.objects.size());
    EXPECT_EQ(a.title, b.title);
    EXPECT_EQ(a.referenceTime, b.referenceTime);
    ASSERT_EQ(a.events.size(), b.events.size());
    for (size_t i = 0; i < a.objects.size(); ++i) {
        const RecordedObject& x = a.objects[i];
        const RecordedObject& y = b.objects[i];
        EXPECT_EQ(x.id, y.id);
        EXPECT_EQ(x.type, y.type);
        EXPECT_EQ(x.name, y.name);
        EXPECT_EQ(x.pilot, y.pilot);
        EXPECT_EQ(x.attitude, y.attitude);
        EXPECT_EQ(x.removedAt, y.removedAt);
        EXPECT_EQ(x.destroyedAt, y.destroyedAt);
        ASSERT_EQ(x.track.size(), y.track.size()) << x.describe();
        for (size_t k = 0; k < x.track.size(); ++k) {
            const ObjectSample &p = x.track[k], &q = y.track[k];
            ASSERT_NEAR(p.time, q.time, 5e-4);
            ASSERT_NEAR(p.lon, q.lon, 6e-8); // 7 decimals of a degree: ~1 cm
            ASSERT_NEAR(p.lat, q.lat, 6e-8);
            ASSERT_NEAR(p.alt, q.alt, 5e-3);
            ASSERT_NEAR(p.roll, q.roll, 0.051);
            ASSERT_NEAR(p.pitch, q.pitch, 0.051);
            ASSERT_NEAR(p.yaw, q.yaw, 0.051);
        }
    }
}

TEST(AcmiWriter, RoundTripsEscapesEventsRemovalsAndPositionOnlyTracks) {
    const Recording a = scene();
    std::ostringstream text;
    writeAcmi(a, text);
    const Recording b = acmi(text.str());
    expectSameRecording(a, b);
    // Escapes survive, and a NaN is refused rather than written.
    std::ostringstream out;
    AcmiWriter w(out, {"2024-01-01T00:00:00Z", 36, 44, "a, b\nc"});
    w.frame(0.0);
    w.object(0x10, {{"Name", "Tom, \"Maverick\"\nMitchell"}});
    w.transform(0x10, 36.5, 44.5, 100.0, 1.0, 2.0, 3.0);
    w.frame(1.0);
    w.transform(0x10, 36.5, 44.6, 100.0, 1.0, 2.0, 3.0);
    EXPECT_THROW(w.transform(0x10, NAN, 44.6, 100.0, 1.0, 2.0, 3.0), std::invalid_argument);
    EXPECT_THROW(w.frame(0.5), std::invalid_argument);
    EXPECT_NE(out.str().find("10,T=|0.6||||\n"), std::string::npos) << out.str(); // only latitude changed
    const Recording c = acmi(out.str());
    EXPECT_EQ(c.title, "a, b\nc");
    EXPECT_EQ(c.objects.at(0).name, "Tom, \"Maverick\"\nMitchell");
    EXPECT_DOUBLE_EQ(c.objects[0].track[1].lat, 44.6);
}

// Found by the writer/reader round-trip fuzzer (tests/fuzz/fuzz_acmi_roundtrip.cpp).
TEST(AcmiWriter, EscapedReferenceTimeHexLookingEventTextAndUnwritableEvents) {
    std::ostringstream out;
    AcmiWriter w(out, {"2024,01\\x", 0, 0, ""}); // ReferenceTime is unescaped like every other value
    w.frame(1.0);
    w.event("Bookmark", {}, "cafe"); // no ids: a text that reads as a hex id stays text
    w.event("Message", {0x1f}, "beef");
    EXPECT_THROW(w.event("", {}, "x"), std::invalid_argument);          // no type
    EXPECT_THROW(w.event("A|B", {}, "x"), std::invalid_argument);       // ACMI cannot escape '|'
    EXPECT_THROW(w.event("Message", {}, "a|b"), std::invalid_argument); // in the text either
    const Recording r = acmi(out.str());
    EXPECT_EQ(r.referenceTime, "2024,01\\x");
    ASSERT_EQ(r.events.size(), 2u) << out.str();
    EXPECT_TRUE(r.events[0].objects.empty());
    EXPECT_EQ(r.events[0].text, "cafe");
    EXPECT_EQ(r.events[1].objects, std::vector<uint64_t>{0x1f});
    EXPECT_EQ(r.events[1].text, "beef");
}

TEST(RealRecording, DcsBlackSeaF14) {
    const fs::path file = pacifica::testdata::sharedDir() / "data/flights/dcs-blacksea-f14b.txt.acmi";
    ASSERT_TRUE(fs::exists(file)) << file;
    const Recording r = readRecording(file);
    EXPECT_EQ(r.format, "acmi-text");
    EXPECT_EQ(r.fileVersion, "2.2");
    EXPECT_EQ(r.title, "F-14B_IA_Caucasus_Free Flight");
    EXPECT_DOUBLE_EQ(r.referenceLongitude, 33.0);
    EXPECT_EQ(r.objects.size(), 14u);
    const RecordedObject& f14 = selectObject(r, "F-14B");
    EXPECT_EQ(f14.pilot, "Nuevo apodo");
    EXPECT_EQ(f14.attitude, "recorded");
    EXPECT_GT(f14.track.size(), 1000u);
    EXPECT_GT(f14.endTime() - f14.startTime(), 200.0);
    double lo = 1e9, hi = -1e9;
    for (const ObjectSample& s : f14.track) {
        lo = std::min(lo, s.alt);
        hi = std::max(hi, s.alt);
    }
    EXPECT_NEAR(lo, 45.0, 5.0); // SOURCES.md: altitude 45-4570 m
    EXPECT_NEAR(hi, 4570.0, 5.0);
    const EarthFrame frame = chooseFrame(r, &f14, f14.startTime());
    const SeaDrivers d = seaDrivers(r, frame);
    EXPECT_EQ(d.ships.size(), 6u);
    EXPECT_EQ(d.byType.at("Navaid+Static+Bullseye").leftOut.at("not a ship, weapon or aircraft"), 3);
    for (const SeaShip& s : d.ships)
        EXPECT_GE(s.samples.size(), 2u) << s.label;
    // Written back as ACMI and read again: the same objects, tracks (to the written precision) and events.
    std::ostringstream text;
    writeAcmi(r, text);
    expectSameRecording(r, acmi(text.str()));
}

} // namespace
