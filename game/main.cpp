// pacifica-game: a small flight viewer that embeds the ocean component through its public API only.
// Keys: W/S pitch, A/D roll, Q/E yaw, R/F throttle, B drops a bomb on the sea ahead, Escape quits. A ship
// circles ahead of the start, leaving its wake (ocean/Effects.h: effects are created by events). The
// simulation runs on a fixed step in double precision; the camera starts far from the origin (10^6 m) to
// exercise camera-relative rendering.
//   pacifica-game [--frames N] [--record FILE.txt.acmi]
//     --frames N   N > 0: fly a scripted manoeuvre for N frames, check the image, exit
//                  (0 = rendered finite, non-black frames; 1 = not).
//     --record F   write the session as Tacview ACMI 2.2 (the player, the ship, bombs and their impacts) for
//                  `pacifica replay F` or Tacview; the world is placed on the Earth at MAP_ORIGIN
//                  (EarthFrame).
#include <engine/Ecs.h>
#include <engine/Log.h>
#include <engine/Space.h>
#include <engine/Time.h>
#include <engine/color/ColorPipeline.h>
#include <engine/color/Tonemapper.h>
#include <engine/gl/FrameTargets.h>
#include <engine/gl/GlContext.h>
#include <ocean/Effects.h>
#include <ocean/Ocean.h>
#include <recording/AcmiWriter.h>
#include <recording/EarthFrame.h>

#include <epoxy/gl.h>
// GLFW only for its key codes: the window itself comes from engine's GlContext.
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Aircraft {
    pacifica::Pose pose;
    double speed = 120.0; // m/s
};

struct Controls {
    double pitch = 0, roll = 0, yaw = 0, throttle = 0; // -1..1
};

Controls readKeys(const pacifica::gl::GlContext& ctx) {
    auto axis = [&](int plus, int minus) {
        return (ctx.keyDown(plus) ? 1.0 : 0.0) - (ctx.keyDown(minus) ? 1.0 : 0.0);
    };
    return {axis(GLFW_KEY_S, GLFW_KEY_W), axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q),
            axis(GLFW_KEY_R, GLFW_KEY_F)};
}

/// The scripted manoeuvre for unattended runs: a gentle climbing right turn.
Controls scripted(double t) {
    return {0.25 * std::sin(t * 0.7), 0.5, 0.1, 0.0};
}

void step(Aircraft& a, const Controls& c, double dt) {
    a.pose.pitchDeg = std::clamp(a.pose.pitchDeg + c.pitch * 30.0 * dt, -80.0, 80.0);
    a.pose.rollDeg = std::clamp(a.pose.rollDeg + c.roll * 60.0 * dt, -85.0, 85.0);
    // Coordinated turn: heading rate from bank angle, g tan(roll) / v (plus rudder).
    const double turnRate = 9.81 * std::tan(a.pose.rollDeg * std::numbers::pi / 180.0) / a.speed;
    a.pose.headingDeg = std::fmod(
        a.pose.headingDeg + (turnRate * 180.0 / std::numbers::pi + c.yaw * 10.0) * dt + 360.0, 360.0);
    a.speed = std::clamp(a.speed + c.throttle * 20.0 * dt, 30.0, 400.0);
    const glm::dmat3 att = pacifica::attitudeMatrix(a.pose.headingDeg, a.pose.pitchDeg, a.pose.rollDeg);
    a.pose.position += att[0] * a.speed * dt;
    a.pose.position.z = std::max(a.pose.position.z, 2.0); // do not fly into the sea
}

/// Where the game's flat world sits on the Earth, for recordings: the world point MAP_ORIGIN_WORLD (the
/// start, far from the world origin to exercise camera-relative rendering) is at MAP_ORIGIN_LAT/LON (the
/// Black Sea).
constexpr double MAP_ORIGIN_LAT = 44.5, MAP_ORIGIN_LON = 37.0;
const glm::dvec3 MAP_ORIGIN_WORLD{1.0e6, -2.0e6, 0.0};
/// Recording time = game time + this, so the ship's history before the first frame has positive times.
constexpr double RECORD_OFFSET_S = 180.0;

/// Writes the session as ACMI: world poses -> WGS84 through the EarthFrame, grid headings -> true headings.
class SessionRecorder {
public:
    explicit SessionRecorder(const std::string& file)
        : mFile(file), mTmp(file + ".tmp"), mOut(mTmp, std::ios::binary | std::ios::trunc),
          mFrame(MAP_ORIGIN_LAT, MAP_ORIGIN_LON),
          mWriter(mOut, {"2024-06-01T10:00:00Z", MAP_ORIGIN_LON, MAP_ORIGIN_LAT, "Pacifica game session"}) {
        if (!mOut)
            throw std::runtime_error(file + ": cannot write the recording");
    }
    using Properties = std::vector<std::pair<std::string, std::string>>;
    void pose(double t, uint64_t id, const pacifica::Pose& p, bool declare, const Properties& props) {
        double lat = 0, lon = 0, alt = 0;
        mFrame.toGeodetic(p.position - MAP_ORIGIN_WORLD, lat, lon, alt);
        const double trueYaw = p.headingDeg - mFrame.gridHeading(lat, lon, 0.0); // grid -> true north
        mWriter.frame(t + RECORD_OFFSET_S);
        if (declare)
            mWriter.object(id, props);
        mWriter.transform(id, lon, lat, alt, p.rollDeg, p.pitchDeg, std::fmod(trueYaw + 360.0, 360.0));
    }
    /// A bomb meeting the sea at world (x, y) at time t: a bomb object there, removed at once (replay turns a
    /// weapon removed at sea level into an explosion at that place and time).
    void impact(double t, const glm::dvec2& at) {
        pacifica::Pose p;
        p.position = {at.x, at.y, 0.0};
        const uint64_t id = 0x300 + mBombs++;
        pose(t, id, p, true, {{"Type", "Weapon+Bomb"}, {"Name", "Mk-82"}});
        mWriter.remove(id);
        double lat = 0, lon = 0, alt = 0;
        mFrame.toGeodetic(p.position - MAP_ORIGIN_WORLD, lat, lon, alt);
        std::printf("pacifica-game: impact t=%.6f lat=%.9f lon=%.9f\n", t + RECORD_OFFSET_S, lat, lon);
    }
    /// Prints where the ship is at the end (lat/lon), for the record -> replay test.
    void report(double t, const glm::dvec2& ship) const {
        double lat = 0, lon = 0, alt = 0;
        mFrame.toGeodetic(glm::dvec3(ship, 0.0) - MAP_ORIGIN_WORLD, lat, lon, alt);
        std::printf("pacifica-game: ship t=%.6f lat=%.9f lon=%.9f\n", t + RECORD_OFFSET_S, lat, lon);
    }
    /// Closes the file and moves it into place (a failed session leaves no half-written recording).
    void finish() {
        mOut.flush();
        if (!mOut)
            throw std::runtime_error(mFile + ": write failed");
        mOut.close();
        std::rename(mTmp.c_str(), mFile.c_str());
        mDone = true;
    }
    ~SessionRecorder() {
        if (!mDone)
            std::remove(mTmp.c_str());
    }

private:
    std::string mFile, mTmp;
    std::ofstream mOut;
    pacifica::recording::EarthFrame mFrame;
    pacifica::recording::AcmiWriter mWriter;
    int mBombs = 0;
    bool mDone = false;
};

} // namespace

int main(int argc, char** argv) {
    long long scriptedFrames = 0;
    std::string recordFile;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--record") == 0 && i + 1 < argc) {
            recordFile = argv[++i];
            continue;
        }
        if (std::strcmp(argv[i], "--frames") == 0 && i + 1 < argc) {
            scriptedFrames = std::atoll(argv[++i]);
            if (scriptedFrames <= 0) {
                std::fprintf(stderr, "pacifica-game: error: --frames needs a positive integer\n");
                return 2;
            }
        } else {
            std::fprintf(stderr, "usage: pacifica-game [--frames N] [--record FILE.txt.acmi]\n");
            return 2;
        }
    }
    try {
        auto ctx = pacifica::gl::createWindowContext({.width = 1280, .height = 720, .title = "Pacifica"});
        pacifica::color::ColorPipeline colour =
            pacifica::color::ColorPipeline::fromEnvironmentOr(std::nullopt);
        colour.select("", "");
        pacifica::color::Tonemapper tonemapper(colour);

        pacifica::ecs::Registry registry;
        registry.emplace<pacifica::ocean::OceanComponent>(registry.create(), pacifica::ocean::makeOcean({}));
        pacifica::ocean::OceanRenderer renderer;
        pacifica::ecs::EventQueue events;
        pacifica::ocean::EffectsSystem effects(registry, events);

        Aircraft plane;
        plane.pose.position = MAP_ORIGIN_WORLD + glm::dvec3(0.0, 0.0, 60.0);
        plane.pose.headingDeg = 80.0;
        plane.pose.pitchDeg = -3.0;

        // A ship circling (radius 600 m, 12 m/s) 2 km ahead of the start; its path since t = -180 s is
        // recorded before the first frame so the wake is already there.
        const glm::dvec2 shipCentre =
            glm::dvec2(plane.pose.position) + 2000.0 * glm::dvec2(std::sin(80.0 * std::numbers::pi / 180.0),
                                                                  std::cos(80.0 * std::numbers::pi / 180.0));
        auto shipAt = [&](double t) {
            const double a = 12.0 / 600.0 * t;
            return shipCentre + 600.0 * glm::dvec2(std::cos(a), std::sin(a));
        };
        const pacifica::ecs::Entity ship = registry.create();
        registry.emplace<pacifica::ocean::Ship>(ship, pacifica::ocean::Ship{shipAt(-180.0), 80.0});
        events.enqueue(pacifica::ocean::AttachShipTrail{ship, pacifica::ocean::WakeParams{}});
        std::optional<SessionRecorder> recorder;
        if (!recordFile.empty())
            recorder.emplace(recordFile);
        auto shipPose = [&](double t) {
            const double a = 12.0 / 600.0 * t;
            pacifica::Pose p;
            p.position = glm::dvec3(shipAt(t), 0.0);
            p.headingDeg =
                std::fmod(std::atan2(-std::sin(a), std::cos(a)) * 180.0 / std::numbers::pi + 360.0, 360.0);
            return p;
        };
        const SessionRecorder::Properties SHIP_PROPS = {
            {"Type", "Sea+Watercraft+Warship"}, {"Name", "Circling Ship"}, {"Length", "80"}};
        for (double t = -180.0; t < 0.0; t += 0.5) {
            registry.get<pacifica::ocean::Ship>(ship).position = shipAt(t);
            events.dispatch();
            effects.update(t, plane.pose.position);
            if (recorder)
                recorder->pose(t, 0x200, shipPose(t), t == -180.0, SHIP_PROPS);
        }
        bool bombKeyWasDown = false;
        pacifica::FixedStepClock clock(1.0 / 120.0);
        std::unique_ptr<pacifica::gl::FrameTargets> targets;
        auto last = std::chrono::steady_clock::now();
        long long frame = 0;
        int badFrames = 0;
        while (!ctx->shouldClose()) {
            ctx->pollEvents();
            if (ctx->keyDown(GLFW_KEY_ESCAPE))
                break;
            const auto now = std::chrono::steady_clock::now();
            // Scripted runs advance exactly one 1/30 s per frame so they are reproducible.
            const double realDt =
                scriptedFrames ? 1.0 / 30.0 : std::chrono::duration<double>(now - last).count();
            last = now;
            const int steps = clock.advance(realDt);
            for (int s = 0; s < steps; ++s)
                step(plane, scriptedFrames ? scripted(clock.time()) : readKeys(*ctx), clock.step());

            // B (or the script's 2nd frame): a bomb hits the sea where the nose points, or 400 m ahead.
            const bool bombKey = scriptedFrames ? frame == 1 : ctx->keyDown(GLFW_KEY_B);
            if (bombKey && !bombKeyWasDown) {
                const double h = glm::radians(plane.pose.headingDeg);
                const glm::dvec2 at =
                    glm::dvec2(plane.pose.position) + 400.0 * glm::dvec2(std::sin(h), std::cos(h));
                // Strength 1 = a 500 kg bomb: what replay gives a recorded Weapon+Bomb (SeaDrivers.h).
                events.enqueue(pacifica::ocean::SpawnExplosion{at, clock.time(), 1.0});
                if (recorder)
                    recorder->impact(clock.time(), at);
            }
            bombKeyWasDown = bombKey;
            registry.get<pacifica::ocean::Ship>(ship).position = shipAt(clock.time());
            if (recorder) {
                recorder->pose(clock.time(), 0x100, plane.pose, frame == 0,
                               {{"Type", "Air+FixedWing"},
                                {"Name", "Pacifica Jet"},
                                {"Pilot", "Player"},
                                {"CallSign", "Pacifica1"}});
                recorder->pose(clock.time(), 0x200, shipPose(clock.time()), false, SHIP_PROPS);
            }
            events.dispatch();
            effects.update(clock.time(), plane.pose.position);

            const glm::ivec2 size = ctx->framebufferSize();
            if (size.x <= 0 || size.y <= 0)
                continue; // minimised
            if (!targets || targets->width() != size.x || targets->height() != size.y)
                targets = std::make_unique<pacifica::gl::FrameTargets>(size.x, size.y);
            pacifica::ocean::OceanFrame f;
            f.camera = pacifica::makeCameraFrame(plane.pose, 60.0f * std::numbers::pi_v<float> / 180.0f,
                                                 float(size.x) / float(size.y), 0.05f);
            f.time = clock.time();
            f.targetFramebuffer = targets->sceneFramebuffer().id();
            f.width = size.x;
            f.height = size.y;
            renderer.render(registry, f);
            // The host lends its default framebuffer to the tonemap pass.
            tonemapper.run(targets->sceneColor(), pacifica::gl::Framebuffer::wrap(0), size.x, size.y);
            if (scriptedFrames) {
                float px[4] = {0, 0, 0, 0};
                glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
                glReadBuffer(GL_BACK);
                glReadPixels(size.x / 2, size.y / 3, 1, 1, GL_RGBA, GL_FLOAT, px);
                if (!(std::isfinite(px[0]) && px[0] + px[1] + px[2] > 0.01f))
                    ++badFrames;
            }
            ctx->swapBuffers();
            ++frame;
            if (scriptedFrames && frame >= scriptedFrames)
                break;
        }
        if (recorder) {
            recorder->finish();
            recorder->report(clock.time(), shipAt(clock.time()));
        }
        if (scriptedFrames) {
            const pacifica::ocean::OceanStats& st = renderer.lastStats();
            std::printf("pacifica-game: %lld frames, t = %.3f s, position (%.1f, %.1f, %.1f), %d bad frames, "
                        "explosions %d, wakes %d, %s\n",
                        frame, clock.time(), plane.pose.position.x, plane.pose.position.y,
                        plane.pose.position.z, badFrames, st.explosions.active, st.wakes.active,
                        ctx->info().renderer.c_str());
            // The script drops one bomb and the ship sails: both effects must be alive at the end.
            const bool effectsAlive = st.explosions.active == 1 && st.wakes.active == 1;
            return badFrames == 0 && frame == scriptedFrames && effectsAlive ? 0 : 1;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica-game: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
