// SessionRecorder: writes a game session as Tacview ACMI 2.2 text for `pacifica replay` or Tacview -- the
// player, the carrier and the target ships (Sea+Watercraft: replay gives them wakes along the recorded
// tracks), every bomb and rocket in flight (removed where it meets the sea: replay turns that into an
// explosion), Destroyed events for sunk ships and a ditched player. The game's flat world sits on the Earth
// through an EarthFrame: the world point `worldOrigin` is at (originLat, originLon). The file is written to
// FILE.tmp and renamed on finish(): a failed session leaves no half-written recording.
#pragma once

#include "game/World.h"

#include <recording/AcmiWriter.h>
#include <recording/EarthFrame.h>

#include <fstream>
#include <string>
#include <vector>

namespace pacifica::game {

struct RecorderDesc {
    double originLat = 44.5, originLon = 37.0; ///< the Black Sea
    glm::dvec3 worldOrigin{1.0e6, -2.0e6, 0.0};
    /// Recording time = game time + this (the ships' tracks start before the first frame).
    double timeOffset = 180.0;
    std::string referenceTime = "2024-06-01T10:00:00Z";
};

class SessionRecorder {
public:
    /// Throws std::runtime_error "FILE: cannot write the recording".
    SessionRecorder(const std::string& file, const RecorderDesc& desc = {});
    ~SessionRecorder();
    SessionRecorder(const SessionRecorder&) = delete;
    SessionRecorder& operator=(const SessionRecorder&) = delete;

    /// The ships at time t (before the first frame: their history, so replay draws their wakes at once).
    void recordShips(const World& world, double t);
    /// Everything at the world's current time plus this step's events (World::takeEvents()).
    void record(const World& world, const std::vector<GameEvent>& events);
    /// Flushes, checks the stream and renames FILE.tmp to FILE. Throws std::runtime_error on a write error.
    void finish();

    /// World point -> (lat, lon, alt) as recorded.
    glm::dvec3 geodetic(const glm::dvec3& world) const;
    double recordTime(double gameTime) const { return gameTime + mDesc.timeOffset; }

private:
    void pose(uint64_t id, const Pose& p);
    std::string mFile, mTmp;
    RecorderDesc mDesc;
    std::ofstream mOut;
    recording::EarthFrame mFrame;
    recording::AcmiWriter mWriter;
    std::vector<uint64_t> mDeclared, mRemoved;
    bool mPlayerDeclared = false, mPlayerGone = false, mDone = false;
};

} // namespace pacifica::game
