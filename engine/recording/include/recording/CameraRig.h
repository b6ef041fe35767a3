// CameraRig: cameras that follow recorded objects -- cockpit, chase, orbit, fixed, lookat -- and the parsing
// of their one-line spec, shared by `pacifica replay --rig` and the game. Every rig is a pure function of
// the time (smoothing looks back along the track instead of integrating frame by frame), so a replay is the
// same at any frame rate and from any --start.
//
// Spec: KIND:OBJECT[,key=value...]   (OBJECT: hex id, name, pilot or callsign; see selectObject())
//   cockpit:OBJ[,forward=M,right=M,up=M]                  the object's pose plus an eye offset (body axes)
//   chase:OBJ[,distance=M,height=M,smoothing=S]           behind and above, heading smoothed over S seconds
//   orbit:OBJ[,distance=M,elevation=DEG,rate=DEG/S,azimuth=DEG]   circling the object, looking at it
//   fixed:OBJ[,east=M,north=M,up=M,at=S]                  a world point (offset from the object at time S,
//                                                         default its first sample) looking at the object
//   lookat:OBJ,target=OBJ2[,up=M]                         from OBJ (eye up M) toward OBJ2
// Every kind also takes size=WxH, fov=DEG and name=TEXT (the view's own image size, field of view and file
// prefix when several rigs render in one run).
#pragma once

#include "recording/EarthFrame.h"
#include "recording/Recording.h"

#include <engine/CameraPoses.h>
#include <engine/Pose.h>

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace pacifica::recording {

/// Bad rig spec or object query; what() names the option and lists the valid choices or candidates.
class RigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct RigSpec {
    std::string text; ///< as given
    std::string kind; ///< cockpit, chase, orbit, fixed, lookat
    std::string object;
    std::map<std::string, std::string> params; ///< key=value pairs, validated by makeRig()
};

/// Splits "KIND:OBJECT,key=value,...". Throws RigError naming --rig for an unknown kind or a malformed pair.
RigSpec parseRigSpec(const std::string& text);

/// The object a query names: a hex id ("d01", "0xd01"), else an exact (case-insensitive) name, pilot or
/// callsign. Objects without a track are never chosen. Unknown or ambiguous: RigError listing candidates.
const RecordedObject& selectObject(const Recording& rec, const std::string& query);

/// An object's track in the world frame, sampled by interpolatePose() (clamped to the track).
class WorldTrack {
public:
    WorldTrack(const RecordedObject& o, const EarthFrame& frame);
    Pose poseAt(double t) const;
    double startTime() const { return mTimes.front(); }
    double endTime() const { return mTimes.back(); }

private:
    std::vector<double> mTimes;
    std::vector<Pose> mPoses;
};

class CameraRig {
public:
    virtual ~CameraRig() = default;
    virtual Pose poseAt(double t) const = 0;
    /// The time span the rig's object(s) are recorded over: the default replay range.
    double startTime() const { return mStart; }
    double endTime() const { return mEnd; }
    /// The main object followed.
    const RecordedObject& object() const { return *mObject; }

protected:
    double mStart = 0.0, mEnd = 0.0;
    const RecordedObject* mObject = nullptr;
};

/// Builds a rig (size/fov/name keys are ignored here: they belong to the view). Throws RigError naming the
/// bad key or value.
std::unique_ptr<CameraRig> makeRig(const RigSpec& spec, const Recording& rec, const EarthFrame& frame);

} // namespace pacifica::recording
