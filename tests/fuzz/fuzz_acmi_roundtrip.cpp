// libFuzzer target: the ACMI writer and reader round trip (engine/recording/src/AcmiWriter.cpp, Acmi.cpp).
// The input is decoded (FuzzedDataProvider) into a Recording of what ACMI can hold -- objects with unique
// non-zero ids, free-text properties (commas, backslashes, line breaks, '=', '|', any byte but CR and NUL),
// tracks at whole milliseconds with or without attitude, removals and events -- written by writeAcmi(), read
// back by AcmiParser, and compared: every property, removal and event equal, every sample equal to what the
// writer's decimals keep (7 for degrees, 2 for metres, 1 for angles). A mismatch aborts (a finding).
#include <recording/AcmiWriter.h>
#include <recording/Recording.h>

#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>
#include <string>

namespace {

using namespace pacifica::recording;

std::string gWritten; // the text under test, printed with a mismatch

[[noreturn]] void mismatch(const std::string& what) {
    std::fprintf(stderr, "ACMI round trip mismatch: %s\nthe writer's text:\n%s\n", what.c_str(),
                 gWritten.c_str());
    std::abort();
}

std::string text(FuzzedDataProvider& in, size_t maxLength) {
    std::string s = in.ConsumeRandomLengthString(maxLength);
    std::string out;
    for (char c : s)
        if (c != '\r' && c != '\0') // the writer drops CR (ACMI lines end in LF or CRLF); NUL ends nothing
            out.push_back(c);
    return out;
}

void expectNear(double a, double b, double tolerance, const std::string& what) {
    if (!(std::fabs(a - b) <= tolerance))
        mismatch(what + ": wrote " + std::to_string(a) + ", read " + std::to_string(b));
}

Recording decode(FuzzedDataProvider& in) {
    Recording rec;
    rec.referenceTime = text(in, 40);
    rec.title = text(in, 40);
    rec.referenceLongitude = in.ConsumeIntegralInRange(-180, 180);
    rec.referenceLatitude = in.ConsumeIntegralInRange(-90, 90);
    const int objects = in.ConsumeIntegralInRange(0, 6);
    std::set<uint64_t> ids;
    for (int i = 0; i < objects; ++i) {
        RecordedObject o;
        o.id = in.ConsumeIntegralInRange<uint64_t>(1, UINT64_MAX);
        if (!ids.insert(o.id).second)
            continue;
        for (std::string* s : {&o.type, &o.name, &o.pilot, &o.callsign, &o.coalition, &o.color, &o.group})
            *s = in.ConsumeBool() ? text(in, 24) : "";
        o.length = in.ConsumeBool() ? in.ConsumeIntegralInRange(1, 1999999) / 1000.0 : 0.0;
        o.attitude = in.ConsumeBool() ? "recorded" : "none";
        long long ms = in.ConsumeIntegralInRange<long long>(0, 100000000);
        const int samples = in.ConsumeIntegralInRange(1, 8);
        for (int k = 0; k < samples; ++k) {
            ObjectSample s;
            s.time = static_cast<double>(ms) / 1000.0;
            s.lon = in.ConsumeFloatingPointInRange(-180.0, 180.0);
            s.lat = in.ConsumeFloatingPointInRange(-90.0, 90.0);
            s.alt = in.ConsumeFloatingPointInRange(-500.0, 30000.0);
            if (o.attitude == "recorded") {
                s.roll = static_cast<float>(in.ConsumeFloatingPointInRange(-180.0, 180.0));
                s.pitch = static_cast<float>(in.ConsumeFloatingPointInRange(-90.0, 90.0));
                s.yaw = static_cast<float>(in.ConsumeFloatingPointInRange(0.0, 359.9));
            }
            o.track.push_back(s);
            ms += in.ConsumeIntegralInRange(1, 5000);
        }
        if (in.ConsumeBool())
            o.removedAt = static_cast<double>(ms) / 1000.0;
        rec.objects.push_back(o);
    }
    const int events = in.ConsumeIntegralInRange(0, 4);
    for (int i = 0; i < events; ++i) {
        RecordedEvent e;
        e.time = in.ConsumeIntegralInRange(0, 100000000) / 1000.0;
        e.type = text(in, 16);
        for (int k = in.ConsumeIntegralInRange(0, 3); k > 0; --k)
            e.objects.push_back(in.ConsumeIntegralInRange<uint64_t>(1, UINT64_MAX));
        e.text = text(in, 32);
        rec.events.push_back(e);
    }
    std::stable_sort(rec.events.begin(), rec.events.end(),
                     [](const RecordedEvent& a, const RecordedEvent& b) { return a.time < b.time; });
    return rec;
}

void compare(const Recording& w, const Recording& r) {
    if (r.referenceTime != w.referenceTime || r.title != w.title)
        mismatch("header: time '" + r.referenceTime + "' title '" + r.title + "'");
    if (r.objects.size() != w.objects.size())
        mismatch("object count " + std::to_string(r.objects.size()));
    for (const RecordedObject& a : w.objects) { // the reader keeps them in order of first appearance
        const std::string who = "object " + hexId(a.id);
        const RecordedObject* found = r.find(a.id);
        if (!found)
            mismatch(who + " missing");
        const RecordedObject& b = *found;
        if (a.type != b.type || a.name != b.name || a.pilot != b.pilot || a.callsign != b.callsign ||
            a.coalition != b.coalition || a.color != b.color || a.group != b.group)
            mismatch(who + ": properties (read '" + b.type + "' '" + b.name + "' '" + b.pilot + "' '" +
                     b.callsign + "' '" + b.coalition + "' '" + b.color + "' '" + b.group + "')");
        expectNear(a.length, b.length, 1e-6, who + " length");
        if (a.attitude != b.attitude || a.removedAt != b.removedAt || a.track.size() != b.track.size())
            mismatch(who + ": attitude, removal or sample count");
        for (size_t k = 0; k < a.track.size(); ++k) {
            const ObjectSample &s = a.track[k], &t = b.track[k];
            if (s.time != t.time)
                mismatch(who + " sample time");
            expectNear(s.lon, t.lon, 0.51e-7 + 1e-12, who + " longitude");
            expectNear(s.lat, t.lat, 0.51e-7 + 1e-12, who + " latitude");
            expectNear(s.alt, t.alt, 0.0051, who + " altitude");
            expectNear(s.roll, t.roll, 0.051, who + " roll");
            expectNear(s.pitch, t.pitch, 0.051, who + " pitch");
            expectNear(s.yaw, t.yaw, 0.051, who + " yaw");
        }
    }
    if (r.events.size() != w.events.size())
        mismatch("event count " + std::to_string(r.events.size()));
    for (size_t i = 0; i < w.events.size(); ++i) {
        const RecordedEvent &a = w.events[i], &b = r.events[i];
        if (a.time != b.time || a.type != b.type || a.objects != b.objects || a.text != b.text)
            mismatch("event " + std::to_string(i) + ": read '" + b.type + "' text '" + b.text + "'");
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    FuzzedDataProvider in(data, size);
    const Recording rec = decode(in);
    std::ostringstream out;
    try {
        writeAcmi(rec, out);
    } catch (const std::invalid_argument&) {
        return 0; // what ACMI cannot say (an event type or text with '|'): refused, never written wrong
    }
    gWritten = out.str();
    AcmiParser parser("roundtrip.acmi");
    try {
        parser.feed(gWritten);
        compare(rec, parser.finish());
    } catch (const RecordingError& e) {
        mismatch(std::string("the reader refused the writer's text: ") + e.what());
    }
    return 0;
}
