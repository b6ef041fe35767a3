// SessionRecorder: the game session as ACMI 2.2 (SessionRecorder.h).
#include "game/SessionRecorder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pacifica::game {

namespace {
constexpr uint64_t PLAYER_ID = 0x100;
} // namespace

SessionRecorder::SessionRecorder(const std::string& file, const RecorderDesc& desc)
    : mFile(file), mTmp(file + ".tmp"), mDesc(desc), mOut(mTmp, std::ios::binary | std::ios::trunc),
      mFrame(desc.originLat, desc.originLon),
      mWriter(mOut, {desc.referenceTime, desc.originLon, desc.originLat, "Pacifica game session"}) {
    if (!mOut)
        throw std::runtime_error(file + ": cannot write the recording");
}

SessionRecorder::~SessionRecorder() {
    if (!mDone) {
        mOut.close();
        std::remove(mTmp.c_str());
    }
}

glm::dvec3 SessionRecorder::geodetic(const glm::dvec3& world) const {
    double lat = 0, lon = 0, alt = 0;
    mFrame.toGeodetic(world - mDesc.worldOrigin, lat, lon, alt);
    return {lat, lon, alt};
}

void SessionRecorder::pose(uint64_t id, const Pose& p) {
    const glm::dvec3 g = geodetic(p.position);
    const double trueYaw = p.headingDeg - mFrame.gridHeading(g.x, g.y, 0.0); // grid -> true north
    mWriter.transform(id, g.y, g.x, g.z, p.rollDeg, p.pitchDeg, std::fmod(trueYaw + 360.0, 360.0));
}

void SessionRecorder::recordShips(const World& world, double t) {
    mWriter.frame(recordTime(t));
    for (const ShipState& s : world.ships()) {
        if (std::find(mDeclared.begin(), mDeclared.end(), s.id) == mDeclared.end()) {
            mDeclared.push_back(s.id);
            mWriter.object(
                s.id, {{"Type", s.spec.carrier ? "Sea+Watercraft+AircraftCarrier" : "Sea+Watercraft+Warship"},
                       {"Name", s.spec.name},
                       {"Length", std::to_string(static_cast<int>(s.spec.length))},
                       {"Coalition", s.spec.target ? "Enemies" : "Allies"}});
        }
        if (s.visibleAt(t)) {
            Pose p = s.pose;
            p.position.z = 0.0; // a sinking hull is drawn lower; its track stays at sea level
            pose(s.id, p);
        }
    }
}

void SessionRecorder::record(const World& world, const std::vector<GameEvent>& events) {
    const double t = world.time();
    // Events first, each in a frame at its own time (between the last record() and now): an impact is
    // recorded when it happened, not at the next frame.
    for (const GameEvent& e : events) {
        if (e.kind == GameEvent::Kind::Impact || e.kind == GameEvent::Kind::WeaponLost ||
            e.kind == GameEvent::Kind::ShipSunk || e.kind == GameEvent::Kind::Ditched)
            mWriter.frame(recordTime(e.time));
        switch (e.kind) {
        case GameEvent::Kind::Impact: {
            // The weapon's last sample is where it met the sea; removal there = an explosion in replay.
            if (std::find(mDeclared.begin(), mDeclared.end(), e.weapon) == mDeclared.end()) {
                mDeclared.push_back(e.weapon); // launched and landed within one frame
                mWriter.object(
                    e.weapon, {{"Type", e.weaponKind == WeaponKind::Bomb ? "Weapon+Bomb" : "Weapon+Rocket"}});
            }
            const glm::dvec3 g = geodetic(glm::dvec3(glm::dvec2(e.position), 0.0));
            mWriter.transform(e.weapon, g.y, g.x, g.z);
            mWriter.remove(e.weapon);
            break;
        }
        case GameEvent::Kind::WeaponLost:
            mWriter.remove(e.weapon);
            break;
        case GameEvent::Kind::ShipSunk:
            mWriter.event("Destroyed", {world.ships()[e.ship].id}, world.ships()[e.ship].spec.name + " sunk");
            break;
        case GameEvent::Kind::Ditched: {
            Pose p = world.player().pose;
            p.position = glm::dvec3(glm::dvec2(e.position), 0.0);
            pose(PLAYER_ID, p);
            mWriter.event("Destroyed", {PLAYER_ID}, "ditched");
            mWriter.remove(PLAYER_ID);
            mPlayerGone = true;
            break;
        }
        default:
            break;
        }
    }
    recordShips(world, t);
    if (!mPlayerGone) {
        if (!mPlayerDeclared) {
            mWriter.object(PLAYER_ID, {{"Type", "Air+FixedWing"},
                                       {"Name", "Pacifica Jet"},
                                       {"Pilot", "Player"},
                                       {"CallSign", "Pacifica1"},
                                       {"Coalition", "Allies"}});
            mPlayerDeclared = true;
        }
        pose(PLAYER_ID, world.player().pose);
    }
    for (const Weapon& w : world.weapons()) {
        if (std::find(mDeclared.begin(), mDeclared.end(), w.id) == mDeclared.end()) {
            mDeclared.push_back(w.id);
            mWriter.object(w.id, {{"Type", w.kind == WeaponKind::Bomb ? "Weapon+Bomb" : "Weapon+Rocket"},
                                  {"Name", w.kind == WeaponKind::Bomb ? "Mk-82" : "Hydra 70"},
                                  {"Parent", "100"}});
        }
        const glm::dvec3 g = geodetic(w.position);
        mWriter.transform(w.id, g.y, g.x, g.z);
    }
    // Ships gone under: removed once they have settled.
    for (const ShipState& s : world.ships()) {
        if (s.sunkAt && !s.visibleAt(t) &&
            std::find(mRemoved.begin(), mRemoved.end(), s.id) == mRemoved.end()) {
            mRemoved.push_back(s.id);
            mWriter.remove(s.id);
        }
    }
}

void SessionRecorder::finish() {
    mOut.flush();
    if (!mOut)
        throw std::runtime_error(mFile + ": write failed");
    mOut.close();
    if (std::rename(mTmp.c_str(), mFile.c_str()) != 0)
        throw std::runtime_error(mFile + ": cannot move the finished recording into place");
    mDone = true;
}

} // namespace pacifica::game
