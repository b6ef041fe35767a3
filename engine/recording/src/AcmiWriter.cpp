// AcmiWriter: Tacview ACMI 2.2 text output (AcmiWriter.h).
#include "recording/AcmiWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pacifica::recording {

namespace {

std::string fixed(double v, int decimals) {
    char b[48];
    std::snprintf(b, sizeof b, "%.*f", decimals, v);
    std::string s = b;
    if (s.find('.') != std::string::npos) { // trim trailing zeros: "12.50" -> "12.5", "3.0" -> "3"
        while (s.back() == '0')
            s.pop_back();
        if (s.back() == '.')
            s.pop_back();
    }
    if (s == "-0")
        s = "0";
    return s;
}

} // namespace

std::string AcmiWriter::escape(const std::string& value) {
    std::string out;
    for (char c : value) {
        if (c == ',' || c == '\\')
            out.push_back('\\');
        if (c == '\n') {
            out += "\\\n";
            continue;
        }
        if (c != '\r')
            out.push_back(c);
    }
    return out;
}

AcmiWriter::AcmiWriter(std::ostream& out, const AcmiHeader& header) : mOut(out), mHeader(header) {
    mOut << "FileType=text/acmi/tacview\nFileVersion=2.2\n";
    if (!header.referenceTime.empty())
        mOut << "0,ReferenceTime=" << escape(header.referenceTime) << "\n";
    mOut << "0,ReferenceLongitude=" << fixed(header.referenceLongitude, 7) << "\n";
    mOut << "0,ReferenceLatitude=" << fixed(header.referenceLatitude, 7) << "\n";
    if (!header.title.empty())
        mOut << "0,Title=" << escape(header.title) << "\n";
}

void AcmiWriter::frame(double t) {
    if (!std::isfinite(t) || t < mTime)
        throw std::invalid_argument("AcmiWriter::frame: time " + std::to_string(t) + " goes back from " +
                                    std::to_string(mTime));
    if (t == mTime && mFrameWritten)
        return;
    mTime = t;
    mFrameWritten = true;
    mOut << "#" << fixed(t, 3) << "\n";
}

void AcmiWriter::object(uint64_t id, const std::vector<std::pair<std::string, std::string>>& properties) {
    if (properties.empty())
        return;
    mOut << hexId(id);
    for (const auto& [k, v] : properties)
        mOut << "," << k << "=" << escape(v);
    mOut << "\n";
}

void AcmiWriter::transform(uint64_t id, double lon, double lat, double alt, double roll, double pitch,
                           double yaw) {
    const double v[6] = {
        lon - mHeader.referenceLongitude, lat - mHeader.referenceLatitude, alt, roll, pitch, yaw};
    writeTransform(id, v, 6);
}

void AcmiWriter::transform(uint64_t id, double lon, double lat, double alt) {
    const double v[3] = {lon - mHeader.referenceLongitude, lat - mHeader.referenceLatitude, alt};
    writeTransform(id, v, 3);
}

void AcmiWriter::writeTransform(uint64_t id, const double* v, int n) {
    for (int k = 0; k < n; ++k)
        if (!std::isfinite(v[k]))
            throw std::invalid_argument("AcmiWriter::transform: object " + hexId(id) +
                                        " has a non-finite value");
    const int decimals[6] = {7, 7, 2, 1, 1, 1};
    auto [it, fresh] = mLast.try_emplace(id);
    std::string line = hexId(id) + ",T=";
    for (int k = 0; k < n; ++k) {
        const std::string f = fixed(v[k], decimals[k]);
        if (k > 0)
            line.push_back('|');
        if (fresh || f != it->second.fields[k]) { // empty = unchanged (but everything the first time)
            line += f;
            it->second.fields[k] = f;
        }
    }
    mOut << line << "\n";
}

void AcmiWriter::remove(uint64_t id) {
    mOut << "-" << hexId(id) << "\n";
    mLast.erase(id);
}

void AcmiWriter::event(const std::string& type, const std::vector<uint64_t>& ids, const std::string& text) {
    // Event=Type|Id|...|Text has no escape for '|', and a type is required.
    if (type.empty() || type.find('|') != std::string::npos || text.find('|') != std::string::npos)
        throw std::invalid_argument("AcmiWriter::event: the type must be non-empty and neither type nor text "
                                    "may hold '|' (ACMI cannot escape it), got type '" +
                                    type + "', text '" + text + "'");
    mOut << "0,Event=" << escape(type);
    for (uint64_t id : ids)
        mOut << "|" << hexId(id);
    // "Type|Text" with a text that reads as a hex id would read back as an id: an empty id field keeps it
    // text.
    const bool hexText = !text.empty() && text.size() <= 16 &&
                         text.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
    if (ids.empty() && hexText)
        mOut << "|";
    mOut << "|" << escape(text) << "\n";
}

void writeAcmi(const Recording& rec, std::ostream& out) {
    AcmiWriter w(out, {rec.referenceTime, std::round(rec.referenceLongitude),
                       std::round(rec.referenceLatitude), rec.title});
    // Everything that happens, merged by time: (time, order, object index, sample index); order keeps a
    // frame's properties before its transform and removals last.
    struct Item {
        double t;
        int order; // 0 transform, 1 event, 2 removal
        size_t a, b;
    };
    std::vector<Item> items;
    for (size_t i = 0; i < rec.objects.size(); ++i) {
        const RecordedObject& o = rec.objects[i];
        for (size_t k = 0; k < o.track.size(); ++k)
            items.push_back({o.track[k].time, 0, i, k});
        if (o.removedAt)
            items.push_back({*o.removedAt, 2, i, 0});
    }
    for (size_t e = 0; e < rec.events.size(); ++e)
        items.push_back({rec.events[e].time, 1, e, 0});
    std::stable_sort(items.begin(), items.end(), [](const Item& x, const Item& y) {
        return x.t < y.t || (x.t == y.t && x.order < y.order);
    });
    std::vector<bool> declared(rec.objects.size(), false);
    for (const Item& it : items) {
        w.frame(it.t);
        if (it.order == 1) {
            const RecordedEvent& e = rec.events[it.a];
            w.event(e.type, e.objects, e.text);
            continue;
        }
        const RecordedObject& o = rec.objects[it.a];
        if (it.order == 2) {
            w.remove(o.id);
            continue;
        }
        const ObjectSample& s = o.track[it.b];
        if (!declared[it.a]) {
            std::vector<std::pair<std::string, std::string>> props;
            for (const auto& [k, v] : {std::pair<const char*, const std::string*>{"Type", &o.type},
                                       {"Name", &o.name},
                                       {"Pilot", &o.pilot},
                                       {"CallSign", &o.callsign},
                                       {"Coalition", &o.coalition},
                                       {"Color", &o.color},
                                       {"Group", &o.group}})
                if (!v->empty())
                    props.emplace_back(k, *v);
            if (o.length > 0.0)
                props.emplace_back("Length", std::to_string(o.length));
            w.object(o.id, props);
            declared[it.a] = true;
        }
        if (o.attitude == "none") // 3-field: the reader derives the angles again when a rig needs them
            w.transform(o.id, s.lon, s.lat, s.alt);
        else
            w.transform(o.id, s.lon, s.lat, s.alt, s.roll, s.pitch, s.yaw);
    }
}

} // namespace pacifica::recording
