// ReplayInput: flight file -> views, ships, explosions (ReplayInput.h).
#include "ReplayInput.h"

#include "Usage.h"

#include <engine/Log.h>

#include <recording/LandMask.h>

#include "ocean/SeaQuery.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace pacifica::tools {

namespace {

/// Applies the view keys of a rig spec (size, fov, name) to a view.
void applyViewKeys(const recording::RigSpec& spec, ReplayView& view) {
    for (const auto& [k, v] : spec.params) {
        if (k == "size") {
            try {
                parseSize(v, view.width, view.height);
            } catch (const UsageError&) {
                throw UsageError("--rig " + spec.text + ": size must be WxH with 16 <= W,H <= 8192, got '" +
                                 v + "'");
            }
        } else if (k == "fov") {
            float f = 0.0f;
            const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), f);
            if (ec != std::errc() || ptr != v.data() + v.size() || !(f >= 1.0f && f <= 170.0f))
                throw UsageError("--rig " + spec.text + ": fov must be in [1, 170] degrees, got '" + v + "'");
            view.fovYDeg = f;
        } else if (k == "name") {
            if (v.empty() ||
                v.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
                    std::string::npos)
                throw UsageError("--rig " + spec.text + ": name must be letters, digits, '_' or '-', got '" +
                                 v + "'");
            view.name = v;
        }
    }
}

const recording::RecordedObject* defaultFocus(const recording::Recording& rec) {
    const recording::RecordedObject* firstAir = nullptr;
    const recording::RecordedObject* first = nullptr;
    for (const recording::RecordedObject& o : rec.objects) {
        if (o.track.empty() || o.hasTag("Navaid"))
            continue;
        if (!first)
            first = &o;
        if (o.hasTag("Air")) {
            if (!o.pilot.empty())
                return &o;
            if (!firstAir)
                firstAir = &o;
        }
    }
    return firstAir ? firstAir : first;
}

} // namespace

std::vector<ReplayObject> replayObjects(const ReplayInput& in, double start, double end) {
    std::vector<ReplayObject> out;
    if (!in.recording)
        return out;
    const recording::Recording& rec = *in.recording;
    for (const recording::RecordedObject& o : rec.objects) {
        if (o.track.empty() || o.hasTag("Parachutist") || o.hasTag("Shell") || o.hasTag("Decoy"))
            continue;
        ReplayObject r;
        r.id = o.id;
        if (o.hasTag("Watercraft")) {
            r.shape = o.hasTag("AircraftCarrier") ? ObjectShape::Carrier : ObjectShape::Ship;
            r.length = recording::shipLength(o);
        } else if (o.hasTag("Rotorcraft")) {
            r.shape = ObjectShape::Rotorcraft;
            r.length = o.length > 0.0 ? o.length : 18.0;
        } else if (o.hasTag("Air")) {
            r.shape = ObjectShape::Aircraft;
            r.length = o.length > 0.0 ? o.length : 19.0;
        } else if (o.hasTag("Weapon")) {
            r.shape = ObjectShape::Weapon;
            r.length = o.length > 0.0        ? o.length
                       : o.hasTag("Torpedo") ? 6.0
                       : o.hasTag("Missile") ? 4.0
                                             : 3.0;
        } else {
            continue;
        }
        r.start = o.startTime();
        r.end = o.removedAt ? *o.removedAt : std::max(o.endTime(), rec.endTime);
        if (r.end < start || r.start > end)
            continue;
        r.track = std::make_shared<const recording::WorldTrack>(o, *in.frame);
        out.push_back(std::move(r));
    }
    return out;
}

double parseTimeArgument(const std::string& text, const std::optional<double>& referenceUnix,
                         const std::string& option) {
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec == std::errc() && ptr == text.data() + text.size()) {
        if (!std::isfinite(v))
            throw UsageError(option + ": expected finite seconds, got '" + text + "'");
        return v;
    }
    const std::optional<double> utc = recording::parseIsoUtc(text);
    if (!utc)
        throw UsageError(option + ": expected seconds or a UTC time YYYY-MM-DDTHH:MM:SS[.f]Z, got '" + text +
                         "'");
    if (!referenceUnix)
        throw UsageError(option + " " + text + ": this flight has no reference time; give seconds instead");
    return *utc - *referenceUnix;
}

namespace {

/// The project's CSV (also for unrecognised text: FlightPath names the line that is wrong): one view along
/// its own camera path, its ships and explosions.
void loadCsvFlight(ReplayInput& in, const std::filesystem::path& flight, bool recognised,
                   const std::vector<std::string>& rigs, int defaultWidth, int defaultHeight,
                   float defaultFov) {
    if (!recognised) {
        // Only fall back to the CSV reader for text that could be CSV; otherwise list the formats.
        try {
            in.csv = std::make_shared<const FlightPath>(FlightPath::load(flight));
        } catch (const FlightError& e) {
            throw recording::RecordingError(flight.string(), 0, "",
                                            "unrecognised flight file format (as CSV: " + e.message() +
                                                "); supported: " + recording::supportedFormats());
        }
    } else {
        in.csv = std::make_shared<const FlightPath>(FlightPath::load(flight));
    }
    in.format = "csv";
    for (const std::string& r : rigs)
        if (r != "path")
            throw UsageError("--rig " + r +
                             ": a CSV flight is its own camera path (--rig path); rigs over "
                             "objects need a recording (Tacview ACMI or IGC)");
    ReplayView v;
    v.rig = "path";
    v.width = defaultWidth;
    v.height = defaultHeight;
    v.fovYDeg = defaultFov;
    std::shared_ptr<const FlightPath> csv = in.csv;
    v.camera = [csv](double t) { return csv->poseAt(t); };
    in.views.push_back(std::move(v));
    in.startTime = in.csv->startTime();
    in.endTime = in.csv->endTime();
    in.ships = in.csv->ships();
    in.shipLengths.assign(in.ships.size(), 60.0);
    in.explosions = in.csv->explosions();
    in.summary = nullptr;
}

/// The --rig specs over a recording's objects; without any, a chase camera on its default object.
std::vector<recording::RigSpec> rigSpecs(const std::vector<std::string>& rigs,
                                         const recording::Recording& rec,
                                         const std::filesystem::path& flight) {
    std::vector<recording::RigSpec> specs;
    for (const std::string& r : rigs) {
        if (r == "path")
            throw UsageError(
                "--rig path: a recording has no camera path of its own; use cockpit, chase, orbit, "
                "fixed or lookat over one of its objects");
        specs.push_back(recording::parseRigSpec(r));
    }
    if (specs.empty()) {
        const recording::RecordedObject* focus = defaultFocus(rec);
        if (!focus)
            throw recording::RecordingError(flight.string(), 0, "",
                                            "the recording has no object with a position");
        specs.push_back(recording::parseRigSpec("chase:" + recording::hexId(focus->id)));
    }
    return specs;
}

/// The world frame of a replay with these rigs: its origin is the first rig's object where its track starts.
recording::EarthFrame earthFrameFor(const recording::Recording& rec,
                                    const std::vector<recording::RigSpec>& specs) {
    const recording::RecordedObject& focus = recording::selectObject(rec, specs.front().object);
    return recording::chooseFrame(rec, &focus, focus.startTime());
}

/// One view per rig (named when there are several; names must differ); the first rig's object sets the
/// replay's time span. Returns summary.json's "rigs".
nlohmann::json addRigViews(ReplayInput& in, const std::vector<recording::RigSpec>& specs, int defaultWidth,
                           int defaultHeight, float defaultFov) {
    nlohmann::json rigsJson = nlohmann::json::array();
    for (size_t i = 0; i < specs.size(); ++i) {
        std::shared_ptr<const recording::CameraRig> rig =
            recording::makeRig(specs[i], *in.recording, *in.frame);
        ReplayView v;
        v.rig = specs[i].text;
        v.width = defaultWidth;
        v.height = defaultHeight;
        v.fovYDeg = defaultFov;
        if (specs.size() > 1)
            v.name = "view" + std::to_string(i) + "-" + specs[i].kind;
        applyViewKeys(specs[i], v);
        v.camera = [rig](double t) { return rig->poseAt(t); };
        if (specs[i].kind == "cockpit")
            v.hiddenObject = rig->object().id;
        if (i == 0) {
            in.startTime = rig->startTime();
            in.endTime = rig->endTime();
        }
        rigsJson.push_back({{"spec", specs[i].text},
                            {"kind", specs[i].kind},
                            {"object", rig->object().describe()},
                            {"view", v.name}});
        in.rigs.push_back(rig);
        in.views.push_back(std::move(v));
    }
    for (size_t i = 0; i < in.views.size(); ++i)
        for (size_t j = 0; j < i; ++j)
            if (in.views[i].name == in.views[j].name)
                throw UsageError("--rig: two views are named '" + in.views[i].name +
                                 "'; give each its own name=");
    return rigsJson;
}

/// What the recording drives on the sea: ship tracks and impacts (recording/SeaDrivers.h).
void addSeaDrivers(ReplayInput& in, const recording::SeaDrivers& drivers) {
    for (const recording::SeaShip& s : drivers.ships) {
        ShipTrack t;
        t.id = recording::hexId(s.id);
        for (const glm::dvec3& p : s.samples)
            t.samples.push_back({p.x, p.y, p.z});
        in.ships.push_back(std::move(t));
        in.shipLengths.push_back(s.length);
    }
    for (const recording::SeaImpact& x : drivers.impacts)
        in.explosions.push_back({x.time, x.position.x, x.position.y, x.strength, 0});
}

/// summary.json's "recording": the file, the origin, the rigs, and what was read per object type, which
/// ships and impacts drive the sea and what was left out.
nlohmann::json recordingSummary(const ReplayInput& in, const recording::SeaDrivers& drivers,
                                const std::optional<recording::LandMask>& mask, nlohmann::json rigsJson) {
    const recording::Recording& rec = *in.recording;
    nlohmann::json types = nlohmann::json::object();
    for (const auto& [type, tally] : drivers.byType) {
        nlohmann::json left = nlohmann::json::object();
        for (const auto& [why, n] : tally.leftOut)
            left[why] = n;
        types[type] = {{"read", tally.read},
                       {"ships", tally.ships},
                       {"explosions", tally.explosions},
                       {"left_out", left}};
    }
    nlohmann::json impacts = nlohmann::json::array();
    for (const recording::SeaImpact& x : drivers.impacts) {
        double lat = 0.0, lon = 0.0, alt = 0.0;
        in.frame->toGeodetic({x.position.x, x.position.y, 0.0}, lat, lon, alt);
        impacts.push_back({{"id", recording::hexId(x.id)},
                           {"latitude_deg", lat},
                           {"longitude_deg", lon},
                           {"type", x.type},
                           {"time_s", x.time},
                           {"x_m", x.position.x},
                           {"y_m", x.position.y},
                           {"strength", x.strength},
                           {"cause", x.cause}});
    }
    nlohmann::json ships = nlohmann::json::array();
    for (const recording::SeaShip& s : drivers.ships)
        ships.push_back({{"id", recording::hexId(s.id)}, {"object", s.label}, {"length_m", s.length}});
    return {{"format", rec.format},
            {"file_version", rec.fileVersion},
            {"title", rec.title},
            {"reference_time", rec.referenceTime},
            {"objects", rec.objects.size()},
            {"samples", rec.samples},
            {"events", rec.events.size()},
            {"time_span_s", {rec.startTime, rec.endTime}},
            {"origin",
             {{"latitude_deg", in.frame->originLatitude()},
              {"longitude_deg", in.frame->originLongitude()},
              {"frame", "WGS84 azimuthal equidistant (GeographicLib), z = altitude MSL"}}},
            {"altitude_datum", rec.altitudeDatum},
            {"rigs", std::move(rigsJson)},
            {"land_mask", mask ? nlohmann::json(mask->source()) : nlohmann::json(nullptr)},
            {"by_type", types},
            {"ships", ships},
            {"explosions", impacts}};
}

} // namespace

ReplayInput loadReplayInput(const std::filesystem::path& flight, const std::vector<std::string>& rigs,
                            int defaultWidth, int defaultHeight, float defaultFov) {
    ReplayInput in;
    std::error_code ec;
    // A missing file goes to the CSV reader, whose error names it ("cannot open flight file").
    const std::string format =
        std::filesystem::is_regular_file(flight, ec) ? recording::detectFormat(flight) : "csv";
    in.format = format;
    if (format == "csv" || format.empty()) {
        loadCsvFlight(in, flight, !format.empty(), rigs, defaultWidth, defaultHeight, defaultFov);
        return in;
    }
    auto rec = std::make_shared<const recording::Recording>(recording::readRecording(flight));
    in.recording = rec;
    if (rec->altitudeDatum == "ELL")
        logWarning(flight.string() +
                   ": GNSS altitudes are above the WGS84 ellipsoid (HFALGALTGPS:ELL) and are "
                   "taken as above sea level (no geoid model installed; it differs by -106..+85 m)");
    in.referenceUnix = rec->referenceUnix;
    const std::vector<recording::RigSpec> specs = rigSpecs(rigs, *rec, flight);
    in.frame = std::make_shared<const recording::EarthFrame>(earthFrameFor(*rec, specs));
    nlohmann::json rigsJson = addRigViews(in, specs, defaultWidth, defaultHeight, defaultFov);
    // GSHHG shorelines when installed (gmt-gshhg-*): impacts over land are left out by position, not
    // altitude.
    const std::optional<recording::LandMask> mask = recording::LandMask::loadDefault();
    const recording::SeaDrivers drivers = recording::seaDrivers(*rec, *in.frame, mask ? &*mask : nullptr);
    addSeaDrivers(in, drivers);
    in.summary = recordingSummary(in, drivers, mask, std::move(rigsJson));
    return in;
}

namespace {

/// How many of each object's samples lie within SEA_CONTACT_M of the sea surface drawn under them at their
/// time (the waves alone: the recording's own explosions and wakes are left out). Samples are taken in time
/// order, every object's samples at one time in one batched query.
std::vector<size_t> samplesAtTheSurface(const recording::Recording& rec, const recording::EarthFrame& frame,
                                        const ocean::OceanDesc& desc) {
    ocean::OceanComponent ocean;
    if (const ocean::Status s = ocean::makeOcean(desc, ocean); !s)
        throw UsageError("--list-objects: the sea: " + s.message);
    ocean::SeaQuery sea;
    ocean::SeaQueryDesc queryDesc;
    queryDesc.threads = 0;
    // The FFT sea is transformed every 0.5 s of the recording and advanced by its time derivative between
    // (docs/RECORDINGS.md: 3.6x faster on a 220 s recording); the error grows as dt^2, to ~0.7 m at 0.5 s
    // (docs/ACCURACY.md: 0.115 m at 0.2 s), inside the 5 m of contact.
    queryDesc.fftResampleInterval = 0.5;
    if (const ocean::Status s = sea.init(ocean, queryDesc); !s)
        throw UsageError("--list-objects: the sea's queries: " + s.message);
    struct Sample {
        double time;
        uint32_t object;
        double alt;
        glm::dvec2 at;
    };
    std::vector<Sample> samples;
    for (uint32_t i = 0; i < rec.objects.size(); ++i)
        for (const recording::ObjectSample& s : rec.objects[i].track) {
            const glm::dvec3 w = frame.toWorld(s.lat, s.lon, s.alt);
            samples.push_back({s.time, i, s.alt, {w.x, w.y}});
        }
    std::stable_sort(samples.begin(), samples.end(),
                     [](const Sample& a, const Sample& b) { return a.time < b.time; });
    std::vector<size_t> atSea(rec.objects.size(), 0);
    std::vector<glm::dvec2> points;
    std::vector<double> heights;
    for (size_t first = 0, last = 0; first < samples.size(); first = last) {
        while (last < samples.size() && samples[last].time == samples[first].time)
            ++last;
        points.clear();
        for (size_t k = first; k < last; ++k)
            points.push_back(samples[k].at);
        heights.resize(points.size());
        ocean::Status s = sea.update(samples[first].time);
        if (s)
            s = sea.heights(points, heights);
        if (!s)
            throw UsageError("--list-objects: the sea's heights at t = " +
                             std::to_string(samples[first].time) + " s: " + s.message);
        for (size_t k = first; k < last; ++k)
            atSea[samples[k].object] +=
                std::abs(samples[k].alt - heights[k - first]) <= recording::SEA_CONTACT_M ? 1 : 0;
    }
    return atSea;
}

} // namespace

recording::EarthFrame replayEarthFrame(const recording::Recording& rec, const std::vector<std::string>& rigs,
                                       const std::filesystem::path& flight) {
    return earthFrameFor(rec, rigSpecs(rigs, rec, flight));
}

std::string listObjects(const recording::Recording& rec, const recording::EarthFrame& frame,
                        const ocean::OceanDesc& sea) {
    const std::vector<size_t> atSea = samplesAtTheSurface(rec, frame, sea);
    const std::optional<recording::LandMask> mask = recording::LandMask::loadDefault();
    std::string out;
    char line[512];
    std::snprintf(line, sizeof line, "%-10s %-36s %-16s %-16s %9s %9s %8s %8s %8s%s\n", "id", "type", "name",
                  "pilot", "start_s", "end_s", "alt_min", "alt_max", "at_sea", mask ? " over_sea" : "");
    out += line;
    for (size_t i = 0; i < rec.objects.size(); ++i) {
        const recording::RecordedObject& o = rec.objects[i];
        if (o.track.empty())
            continue;
        double lo = o.track.front().alt, hi = lo;
        size_t overSea = 0;
        for (const recording::ObjectSample& s : o.track) {
            lo = std::min(lo, s.alt);
            hi = std::max(hi, s.alt);
            overSea += mask && !mask->isLand(s.lat, s.lon) ? 1 : 0;
        }
        const double n = static_cast<double>(o.track.size());
        std::snprintf(line, sizeof line, "%-10s %-36s %-16s %-16s %9.2f %9.2f %8.0f %8.0f %7.0f%%",
                      recording::hexId(o.id).c_str(), o.type.substr(0, 36).c_str(),
                      o.name.substr(0, 16).c_str(), o.pilot.substr(0, 16).c_str(), o.startTime(), o.endTime(),
                      lo, hi, 100.0 * static_cast<double>(atSea[i]) / n);
        out += line;
        if (mask) {
            std::snprintf(line, sizeof line, " %7.0f%%", 100.0 * static_cast<double>(overSea) / n);
            out += line;
        }
        out += "\n";
    }
    out += "(at_sea: share of samples within " + std::to_string(static_cast<int>(recording::SEA_CONTACT_M)) +
           " m of the sea surface drawn under them at their time; ";
    out += mask ? "over_sea: share of samples over the sea by " + mask->source() + ")\n"
                : "no GSHHG shorelines installed: apt-get install gmt-gshhg-low for over_sea)\n";
    return out;
}

} // namespace pacifica::tools
