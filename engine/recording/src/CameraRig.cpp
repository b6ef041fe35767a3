// Camera rigs over recorded objects (CameraRig.h). Smoothing is a look-back window over the track, so each
// pose depends on t alone (deterministic at any frame rate).
#include "recording/CameraRig.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>

namespace pacifica::recording {

namespace {

const std::set<std::string> KINDS = {"cockpit", "chase", "orbit", "fixed", "lookat"};
const std::set<std::string> VIEW_KEYS = {"size", "fov", "name"};

std::string lower(std::string_view s) {
    std::string o(s);
    for (char& c : o)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return o;
}

/// Reads the numeric parameters of a rig, checking each key is one the kind knows.
class Params {
public:
    Params(const RigSpec& spec, std::set<std::string> allowed) : mSpec(spec) {
        for (const auto& [k, v] : spec.params) {
            if (!allowed.count(k) && !VIEW_KEYS.count(k)) {
                std::string list;
                for (const std::string& a : allowed)
                    list += (list.empty() ? "" : ", ") + a;
                throw RigError("--rig " + spec.text + ": unknown key '" + k + "' for " + spec.kind +
                               " (valid: " + (list.empty() ? std::string("none") : list) +
                               ", size, fov, name)");
            }
        }
    }
    double get(const std::string& key, double fallback, double lo, double hi) const {
        const auto it = mSpec.params.find(key);
        if (it == mSpec.params.end())
            return fallback;
        double v = 0.0;
        const std::string& s = it->second;
        const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v) || v < lo || v > hi)
            throw RigError("--rig " + mSpec.text + ": " + key + " must be a number in [" +
                           std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + s + "'");
        return v;
    }
    bool has(const std::string& key) const { return mSpec.params.count(key) > 0; }

private:
    const RigSpec& mSpec;
};

class CockpitRig : public CameraRig {
public:
    CockpitRig(const RecordedObject& o, const EarthFrame& f, const Params& p)
        : mTrack(o, f), mEye(p.get("forward", 0.0, -500, 500), p.get("right", 0.0, -500, 500),
                             p.get("up", 1.0, -500, 500)) {
        mObject = &o;
        mStart = mTrack.startTime();
        mEnd = mTrack.endTime();
    }
    Pose poseAt(double t) const override { return cockpitPose(mTrack.poseAt(t), mEye); }

private:
    WorldTrack mTrack;
    glm::dvec3 mEye;
};

class ChaseRig : public CameraRig {
public:
    ChaseRig(const RecordedObject& o, const EarthFrame& f, const Params& p)
        : mTrack(o, f), mDistance(p.get("distance", 40.0, 1.0, 1e5)),
          mHeight(p.get("height", 8.0, -1e4, 1e4)), mSmoothing(p.get("smoothing", 1.0, 0.0, 60.0)) {
        mObject = &o;
        mStart = mTrack.startTime();
        mEnd = mTrack.endTime();
    }
    Pose poseAt(double t) const override {
        return chasePose([this](double tt) { return mTrack.poseAt(tt); }, t, mDistance, mHeight, mSmoothing);
    }

private:
    WorldTrack mTrack;
    double mDistance, mHeight, mSmoothing;
};

class OrbitRig : public CameraRig {
public:
    OrbitRig(const RecordedObject& o, const EarthFrame& f, const Params& p)
        : mTrack(o, f), mDistance(p.get("distance", 300.0, 1.0, 1e6)),
          mElevation(p.get("elevation", 20.0, -89.0, 89.0)), mRate(p.get("rate", 6.0, -360.0, 360.0)),
          mAzimuth(p.get("azimuth", 0.0, -360.0, 360.0)) {
        mObject = &o;
        mStart = mTrack.startTime();
        mEnd = mTrack.endTime();
    }
    Pose poseAt(double t) const override {
        return orbitPose(mTrack.poseAt(t).position, mDistance, mElevation, mAzimuth + mRate * (t - mStart));
    }

private:
    WorldTrack mTrack;
    double mDistance, mElevation, mRate, mAzimuth;
};

class FixedRig : public CameraRig {
public:
    FixedRig(const RecordedObject& o, const EarthFrame& f, const Params& p) : mTrack(o, f) {
        mObject = &o;
        mStart = mTrack.startTime();
        mEnd = mTrack.endTime();
        const double at = p.get("at", mStart, -1e12, 1e12);
        mEye = mTrack.poseAt(at).position + glm::dvec3(p.get("east", 300.0, -1e6, 1e6),
                                                       p.get("north", -300.0, -1e6, 1e6),
                                                       p.get("up", 30.0, -1e4, 1e5));
    }
    Pose poseAt(double t) const override { return lookAtPose(mEye, mTrack.poseAt(t).position); }

private:
    WorldTrack mTrack;
    glm::dvec3 mEye;
};

class LookAtRig : public CameraRig {
public:
    LookAtRig(const RecordedObject& from, const RecordedObject& to, const EarthFrame& f, const Params& p)
        : mFrom(from, f), mTo(to, f), mUp(p.get("up", 2.0, -1e4, 1e4)) {
        mObject = &from;
        mStart = std::max(mFrom.startTime(), mTo.startTime());
        mEnd = std::min(mFrom.endTime(), mTo.endTime());
        if (mEnd < mStart) { // no overlap: the first object's span, the other clamped
            mStart = mFrom.startTime();
            mEnd = mFrom.endTime();
        }
    }
    Pose poseAt(double t) const override {
        return lookAtPose(mFrom.poseAt(t).position + glm::dvec3(0.0, 0.0, mUp), mTo.poseAt(t).position);
    }

private:
    WorldTrack mFrom, mTo;
    double mUp;
};

} // namespace

RigSpec parseRigSpec(const std::string& text) {
    RigSpec spec;
    spec.text = text;
    const size_t colon = text.find(':');
    std::string kinds;
    for (const std::string& k : KINDS)
        kinds += (kinds.empty() ? "" : ", ") + k;
    if (colon == std::string::npos)
        throw RigError("--rig '" + text + "': expected KIND:OBJECT[,key=value...] with KIND one of " + kinds);
    spec.kind = lower(text.substr(0, colon));
    if (!KINDS.count(spec.kind))
        throw RigError("--rig '" + text + "': unknown rig kind '" + spec.kind + "' (valid: " + kinds + ")");
    std::string rest = text.substr(colon + 1);
    const size_t comma = rest.find(',');
    spec.object = rest.substr(0, comma);
    if (spec.object.empty())
        throw RigError("--rig '" + text + "': no object named after '" + spec.kind + ":'");
    rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
    while (!rest.empty()) {
        const size_t c = rest.find(',');
        const std::string pair = rest.substr(0, c);
        rest = c == std::string::npos ? "" : rest.substr(c + 1);
        const size_t eq = pair.find('=');
        if (eq == std::string::npos || eq == 0)
            throw RigError("--rig '" + text + "': expected key=value, got '" + pair + "'");
        spec.params[lower(pair.substr(0, eq))] = pair.substr(eq + 1);
    }
    return spec;
}

const RecordedObject& selectObject(const Recording& rec, const std::string& query) {
    std::string q = lower(query);
    // A hex id first (exact), then names.
    std::string idText = q.rfind("0x", 0) == 0 ? q.substr(2) : q;
    uint64_t id = 0;
    const auto [ptr, ec] = std::from_chars(idText.data(), idText.data() + idText.size(), id, 16);
    if (ec == std::errc() && ptr == idText.data() + idText.size() && !idText.empty()) {
        const RecordedObject* o = rec.find(id);
        if (o && !o->track.empty())
            return *o;
    }
    std::vector<const RecordedObject*> hits;
    for (const RecordedObject& o : rec.objects) {
        if (o.track.empty())
            continue;
        if (lower(o.name) == q || lower(o.pilot) == q || lower(o.callsign) == q)
            hits.push_back(&o);
    }
    if (hits.size() == 1)
        return *hits.front();
    std::string list;
    auto add = [&](const RecordedObject& o) { list += "\n  " + o.describe(); };
    if (hits.size() > 1) {
        for (const RecordedObject* o : hits)
            add(*o);
        throw RigError("object '" + query + "' is ambiguous; name one by id:" + list);
    }
    int shown = 0, total = 0;
    for (const RecordedObject& o : rec.objects) {
        if (o.track.empty() || !(o.hasTag("Air") || o.hasTag("Sea") || o.hasTag("Weapon")))
            continue;
        ++total;
        if (shown < 25) {
            add(o);
            ++shown;
        }
    }
    if (total > shown)
        list +=
            "\n  ... and " + std::to_string(total - shown) + " more (pacifica replay FILE --list-objects)";
    throw RigError("no object '" + query + "' (id, name, pilot or callsign) in " + rec.source +
                   "; candidates:" + list);
}

WorldTrack::WorldTrack(const RecordedObject& recorded, const EarthFrame& frame) {
    RecordedObject derived;
    if (recorded.attitude == "none") { // no recorded angles: derive them from the track (Recording.h)
        derived = recorded;
        deriveAttitude(derived);
    }
    const RecordedObject& o = recorded.attitude == "none" ? derived : recorded;
    mTimes.reserve(o.track.size());
    mPoses.reserve(o.track.size());
    for (const ObjectSample& s : o.track) {
        if (!mTimes.empty() && s.time <= mTimes.back())
            continue;
        mTimes.push_back(s.time);
        mPoses.push_back(frame.toWorldPose(s));
    }
    if (mTimes.empty()) {
        mTimes.push_back(0.0);
        mPoses.emplace_back();
    }
}

Pose WorldTrack::poseAt(double t) const {
    if (!(t > mTimes.front()))
        return mPoses.front();
    if (t >= mTimes.back())
        return mPoses.back();
    const size_t i = static_cast<size_t>(std::upper_bound(mTimes.begin(), mTimes.end(), t) - mTimes.begin());
    const double s = (t - mTimes[i - 1]) / (mTimes[i] - mTimes[i - 1]);
    return interpolatePose(mPoses[i - 1], mPoses[i], s);
}

std::unique_ptr<CameraRig> makeRig(const RigSpec& spec, const Recording& rec, const EarthFrame& frame) {
    const RecordedObject& o = selectObject(rec, spec.object);
    if (spec.kind == "cockpit")
        return std::make_unique<CockpitRig>(o, frame, Params(spec, {"forward", "right", "up"}));
    if (spec.kind == "chase")
        return std::make_unique<ChaseRig>(o, frame, Params(spec, {"distance", "height", "smoothing"}));
    if (spec.kind == "orbit")
        return std::make_unique<OrbitRig>(o, frame,
                                          Params(spec, {"distance", "elevation", "rate", "azimuth"}));
    if (spec.kind == "fixed")
        return std::make_unique<FixedRig>(o, frame, Params(spec, {"east", "north", "up", "at"}));
    // lookat
    const auto it = spec.params.find("target");
    if (it == spec.params.end())
        throw RigError("--rig " + spec.text + ": lookat needs target=OBJECT");
    const RecordedObject& to = selectObject(rec, it->second);
    return std::make_unique<LookAtRig>(o, to, frame, Params(spec, {"target", "up"}));
}

} // namespace pacifica::recording
