// pacifica-bench-storm-frames: a storm in real frames -- what the CPU update and the GPU frame cost while a
// scene throws more at the effects system than its caps hold, and what the counters say was dropped or
// rejected.
//
// The run, at --fps frames per simulated second, camera 300 m up, 2e5 m east of the origin, looking east
// 20 degrees down (60 degree vertical field of view), the default ocean:
//   calm:  1 s without effects (the baseline);
//   storm: at its first frame --ships ships appear at once, 0.5-8 km ahead, each with a trail; through its
//          first simulated second --explosions explosions are spawned evenly, 0.3-3 km ahead, every 7th
//          event carrying bad data (a NaN centre, an infinite or a 1e9 strength, a centre 1e12 m out), which
//          must be rejected; 10 trails are attached to entities that are no ship, and every 100th ship
//          reports a NaN position through the storm's second second (a lost track); the storm goes on
//          --seconds while the ships sail and the explosions evolve.
// Per frame: the CPU's dispatch + EffectsSystem::update (steady_clock), and render() on the GPU
// (gl::GpuTimer: GL_TIME_ELAPSED on hardware; steady_clock around glFinish on llvmpipe, whose timer queries
// are wrong).
//
// Checks (exit 1 when one fails; each is in storm.json): no frame holds more than the caps (EffectsDesc:
// 1024 explosions, 256 wakes drawn); every bad event was rejected, and every good one spawned or dropped by
// the cap; every frame time is finite; with --max-frame-ms > 0, the storm's slowest GPU frame is at most that
// (0 leaves it unchecked: the test suite does, timing being a benchmark's business). Outputs in --out:
// storm.json and storm.md. `./pacifica bench storm-frames --out DIR`; docs/RELIABILITY.md
// ("Storms").
#include "engine/Ecs.h"
#include "engine/Events.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanHost.h"

#include "BenchCli.h"
#include "BenchMain.h"
#include "BenchText.h"

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace pacifica;

namespace {

constexpr double ALTITUDE = 300.0;    // m
constexpr double CAMERA_EAST = 2.0e5; // m from the origin
constexpr int BAD_EVERY = 7;          // every 7th spawn event carries bad data
constexpr int LOST_SHIP_EVERY = 100; // every 100th ship reports a NaN position through the storm's 2nd second
constexpr int BAD_TRAILS = 10;       // trails attached to entities that are no ship
constexpr double CALM_SECONDS = 1.0; // baseline
constexpr double SPAWN_SECONDS = 1.0; // the explosions arrive within this

struct Args {
    std::pair<int, int> size{1920, 1080};
    double seconds = 10.0;
    double fps = 60.0;
    int explosions = 10000;
    int ships = 1000;
    double maxFrameMs = 0.0;
    std::string outDir = "storm";
    std::string commandLine;
};

std::optional<int> parseArgs(int argc, char** argv, Args& a) {
    CLI::App app(
        "pacifica-bench-storm-frames: a storm of explosions and ships in real frames; CPU and GPU frame "
        "time, caps and rejected events",
        "pacifica-bench-storm-frames");
    std::string size = "1920x1080";
    app.add_option("--size", size, "frame size WxH (default 1920x1080)")->check(bench::sizeValidator());
    app.add_option("--seconds", a.seconds, "simulated seconds of storm (default 10)")
        ->check(CLI::Range(1.0, 3600.0));
    app.add_option("--fps", a.fps, "frames per simulated second (default 60)")->check(CLI::Range(1.0, 240.0));
    app.add_option("--explosions", a.explosions, "explosions spawned in the first second (default 10000)")
        ->check(CLI::Range(0, 1000000));
    app.add_option("--ships", a.ships, "ships appearing at once (default 1000)")
        ->check(CLI::Range(0, 100000));
    app.add_option("--max-frame-ms", a.maxFrameMs, "bound on the storm's slowest GPU frame; 0 = unchecked")
        ->check(CLI::Range(0.0, 1e6));
    app.add_option("--out", a.outDir, "output folder (default storm)");
    if (const auto code = bench::parseCommandLine(app, argc, argv))
        return code;
    a.size = *bench::parseSize(size);
    a.commandLine = bench::commandLine(argc, argv);
    return std::nullopt;
}

/// A point `ahead` m in front of the camera (east) and `side` m to its left, from a low-discrepancy pair.
glm::dvec2 scattered(long long k, double near, double far, double width) {
    const double u = std::fmod(static_cast<double>(k) * 0.618033988749895, 1.0);
    const double v = std::fmod(static_cast<double>(k) * 0.754877666246693, 1.0);
    return {CAMERA_EAST + near + (far - near) * u, width * (v - 0.5)};
}

/// Spawn event k: every BAD_EVERY-th carries one of four kinds of bad data.
ocean::SpawnExplosion spawnEvent(long long k, double t) {
    ocean::SpawnExplosion s{scattered(k, 300.0, 3000.0, 3000.0), t, 0.5 + static_cast<double>(k % 4) * 0.5};
    if (k % BAD_EVERY == BAD_EVERY - 1)
        switch ((k / BAD_EVERY) % 4) {
        case 0:
            s.position.x = std::numeric_limits<double>::quiet_NaN();
            break;
        case 1:
            s.strength = std::numeric_limits<double>::infinity();
            break;
        case 2:
            s.strength = 1e9;
            break;
        default:
            s.position.y = 1e12;
            break;
        }
    return s;
}

struct Frame {
    double t = 0.0, cpuMs = 0.0;
    int explosions = 0, wakes = 0, droppedExplosions = 0, droppedWakes = 0, rejected = 0, spawned = 0;
    int programsBuilt = 0; ///< shader variants compiled in the frame (first use): its time is the driver's
};

struct Stats {
    double median = 0.0, p95 = 0.0, max = 0.0;
};

Stats stats(std::vector<double> v) {
    if (v.empty())
        return {};
    std::sort(v.begin(), v.end());
    const auto at = [&](double q) { return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1))]; };
    return {at(0.5), at(0.95), v.back()};
}

nlohmann::json toJson(const Stats& s) {
    return {{"median_ms", s.median}, {"p95_ms", s.p95}, {"max_ms", s.max}};
}

/// The storm's world and its run.
class Storm {
public:
    explicit Storm(const Args& a) : mArgs(a), mFx(mRegistry, mEvents), mTargets(a.size.first, a.size.second) {
        mRegistry.emplace<ocean::OceanComponent>(mRegistry.create(), ocean::makeOcean({}));
    }

    /// Runs calm then storm; returns the frames (calm first) with `gpuMs` filled from the timer.
    std::vector<Frame> run(gl::GpuTimer& timer, long long& calmFrames, long long& badSpawns,
                           long long& badEvents) {
        const double dt = 1.0 / mArgs.fps;
        const auto calm = static_cast<long long>(std::llround(CALM_SECONDS * mArgs.fps));
        const auto storm = static_cast<long long>(std::llround(mArgs.seconds * mArgs.fps));
        const auto spawnFrames = std::max<long long>(1, std::llround(SPAWN_SECONDS * mArgs.fps));
        std::vector<Frame> frames;
        long long spawned = 0;
        badSpawns = badEvents = 0;
        for (long long f = 0; f < calm + storm; ++f) {
            const double t = 1000.0 + static_cast<double>(f) * dt;
            const long long s = f - calm; // storm frame, < 0 while calm
            const auto start = std::chrono::steady_clock::now();
            if (s == 0)
                badEvents += launchShips(t);
            badEvents += sailShips(t, s >= spawnFrames && s < 2 * spawnFrames);
            // Spawns due by the end of this frame: explosions * (s + 1) / spawnFrames, evenly.
            const long long due =
                s < 0 ? 0 : std::min<long long>(mArgs.explosions, mArgs.explosions * (s + 1) / spawnFrames);
            for (; spawned < due; ++spawned) {
                mEvents.enqueue(spawnEvent(spawned, t));
                badSpawns += spawned % BAD_EVERY == BAD_EVERY - 1;
            }
            mEvents.dispatch();
            mFx.update(t, camera());
            const double cpuMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            timer.begin();
            render(t);
            timer.end();
            const ocean::EffectCounters& c = mFx.counters();
            const ocean::OceanStats& r = mRenderer.lastStats();
            frames.push_back({t, cpuMs, r.explosions.active, r.wakes.active, c.droppedExplosions,
                              c.droppedWakes, c.rejected, c.spawned, r.programsBuilt});
        }
        calmFrames = calm;
        badEvents += badSpawns;
        return frames;
    }

private:
    glm::dvec3 camera() const { return {CAMERA_EAST, 0.0, ALTITUDE}; }

    void render(double t) {
        Pose pose;
        pose.position = camera();
        pose.headingDeg = 90.0;
        pose.pitchDeg = -20.0;
        ocean::render(mRenderer, mRegistry,
                      ocean::makeOceanFrame(pose, static_cast<float>(60.0 * std::numbers::pi / 180.0),
                                            mTargets.width(), mTargets.height(), t,
                                            mTargets.sceneFramebuffer().id(), 0.5f));
    }

    /// The ships, and BAD_TRAILS trails for entities that are no ship; returns the bad events.
    long long launchShips(double t) {
        for (int k = 0; k < mArgs.ships; ++k) {
            const ecs::Entity e = mRegistry.create();
            const glm::dvec2 start = scattered(k, 500.0, 8000.0, 8000.0);
            mRegistry.emplace<ocean::Ship>(e, ocean::Ship{start, 20.0 + 10.0 * static_cast<double>(k % 4)});
            mEvents.enqueue(ocean::AttachShipTrail{e, {}});
            mShips.push_back({e, start, t, 5.0 + static_cast<double>(k % 3) * 5.0});
        }
        for (int k = 0; k < BAD_TRAILS; ++k)
            mEvents.enqueue(ocean::AttachShipTrail{mRegistry.create(), {}});
        return BAD_TRAILS;
    }

    /// Moves the ships; with `lose`, every LOST_SHIP_EVERY-th reports a NaN position (a lost track) this
    /// frame. Returns the NaN positions set, each a bad value the effects update must reject.
    long long sailShips(double t, bool lose) {
        long long lost = 0;
        for (size_t k = 0; k < mShips.size(); ++k) {
            const Sailing& s = mShips[k];
            glm::dvec2& p = mRegistry.get<ocean::Ship>(s.entity).position;
            p = s.start + glm::dvec2(0.0, s.speed) * (t - s.born);
            if (lose && k % LOST_SHIP_EVERY == LOST_SHIP_EVERY - 1) {
                p.x = std::numeric_limits<double>::quiet_NaN();
                ++lost;
            }
        }
        return lost;
    }

    struct Sailing {
        ecs::Entity entity;
        glm::dvec2 start;
        double born = 0.0, speed = 0.0;
    };

    const Args& mArgs;
    ecs::Registry mRegistry;
    ecs::EventQueue mEvents;
    ocean::EffectsSystem mFx;
    ocean::OceanRenderer mRenderer;
    gl::FrameTargets mTargets;
    std::vector<Sailing> mShips;
};

struct Check {
    std::string name;
    bool passed = true;
    std::string detail;
};

std::vector<Check> check(const std::vector<Frame>& frames, const std::vector<double>& gpuMs, long long calm,
                         long long badSpawns, long long badEvents, const Args& a,
                         const ocean::EffectsDesc& caps) {
    int maxExplosions = 0, maxWakes = 0;
    long long rejected = 0, spawned = 0;
    bool finite = gpuMs.size() == frames.size();
    for (size_t i = 0; i < frames.size(); ++i) {
        maxExplosions = std::max(maxExplosions, frames[i].explosions);
        maxWakes = std::max(maxWakes, frames[i].wakes);
        rejected += frames[i].rejected;
        spawned += frames[i].spawned;
        finite = finite && std::isfinite(frames[i].cpuMs) && i < gpuMs.size() && std::isfinite(gpuMs[i]);
    }
    double slowest = 0.0; // of the storm's frames that built no program
    for (size_t i = static_cast<size_t>(calm); i < frames.size() && i < gpuMs.size(); ++i)
        if (frames[i].programsBuilt == 0)
            slowest = std::max(slowest, gpuMs[i]);
    std::ostringstream caps1, rej, time;
    caps1 << "at most " << maxExplosions << " explosions (cap " << caps.maxExplosions << ") and " << maxWakes
          << " wakes drawn (cap " << caps.maxWakes << ")";
    long long dropped = 0;
    for (const Frame& f : frames)
        dropped += f.droppedExplosions;
    const long long good = a.explosions - badSpawns;
    // Every good event was spawned or dropped at once by the cap (dropped also counts live ones it replaced).
    const bool accounted = spawned <= good && spawned + dropped >= good;
    rej << rejected << " rejected of " << badEvents << " bad values (" << badSpawns
        << " spawns, the rest lost ships' NaN positions and trails for no ship); of " << good
        << " good spawns " << spawned << " spawned, the rest dropped by the cap (" << dropped
        << " drops in all)";
    time << "slowest storm frame " << slowest << " ms" << (a.maxFrameMs > 0.0 ? " <= " : " (bound unchecked)")
         << (a.maxFrameMs > 0.0 ? std::to_string(a.maxFrameMs) + " ms" : "");
    return {{"caps hold", maxExplosions <= caps.maxExplosions && maxWakes <= caps.maxWakes, caps1.str()},
            {"bad events rejected", rejected == badEvents && accounted, rej.str()},
            {"frame times finite", finite, finite ? "every frame" : "a frame time is missing or not finite"},
            {"frame time bounded", a.maxFrameMs <= 0.0 || slowest <= a.maxFrameMs, time.str()}};
}

void writeReports(const Args& a, const std::string& renderer, const char* clock,
                  const std::vector<Frame>& frames, const std::vector<double>& gpuMs, long long calm,
                  const std::vector<Check>& checks) {
    const long long spawnEnd = calm + std::max<long long>(1, std::llround(SPAWN_SECONDS * a.fps));
    const auto part = [&](long long from, long long to, bool gpu) {
        std::vector<double> v;
        const auto n = static_cast<long long>(std::min(frames.size(), gpuMs.size()));
        for (long long i = from; i < to && i < n; ++i)
            if (frames[static_cast<size_t>(i)].programsBuilt == 0) // a first use's compile is reported apart
                v.push_back(gpu ? gpuMs[static_cast<size_t>(i)] : frames[static_cast<size_t>(i)].cpuMs);
        return stats(v);
    };
    int buildFrames = 0;
    double slowestBuild = 0.0;
    for (size_t i = 0; i < frames.size() && i < gpuMs.size(); ++i)
        if (frames[i].programsBuilt > 0) {
            ++buildFrames;
            slowestBuild = std::max(slowestBuild, gpuMs[i]);
        }
    const long long n = static_cast<long long>(frames.size());
    int peakExplosions = 0, peakWakes = 0, peakDroppedWakes = 0;
    long long dropped = 0;
    for (const Frame& f : frames) {
        peakExplosions = std::max(peakExplosions, f.explosions);
        peakWakes = std::max(peakWakes, f.wakes);
        peakDroppedWakes = std::max(peakDroppedWakes, f.droppedWakes);
        dropped += f.droppedExplosions;
    }
    nlohmann::json j;
    j["command"] = a.commandLine;
    j["date"] = bench::utcNow();
    j["gl_renderer"] = renderer;
    j["clock"] = {{"gpu", clock}, {"cpu", "steady_clock around events.dispatch() + EffectsSystem::update()"}};
    j["size"] = {a.size.first, a.size.second};
    j["gpu"] = {{"calm", toJson(part(0, calm, true))},
                {"spawning", toJson(part(calm, spawnEnd, true))},
                {"after", toJson(part(spawnEnd, n, true))}};
    j["cpu"] = {{"calm", toJson(part(0, calm, false))},
                {"spawning", toJson(part(calm, spawnEnd, false))},
                {"after", toJson(part(spawnEnd, n, false))}};
    j["counters"] = {{"peak_explosions_drawn", peakExplosions},
                     {"peak_wakes_drawn", peakWakes},
                     {"explosions_dropped_by_the_cap", dropped},
                     {"peak_wakes_dropped_per_frame", peakDroppedWakes}};
    j["program_builds"] = {{"frames", buildFrames}, {"slowest_ms", slowestBuild}};
    bool ok = true;
    for (const Check& c : checks) {
        j["checks"][c.name] = {{"passed", c.passed}, {"detail", c.detail}};
        ok = ok && c.passed;
    }
    j["passed"] = ok;
    writeFileAtomically(a.outDir + "/storm.json", j.dump(2) + "\n");
    std::ostringstream md;
    md << "# Storm: " << a.explosions << " explosions in 1 s, " << a.ships << " ships at once\n\n`"
       << a.commandLine << "`, " << renderer << ", GPU clock: " << clock
       << ".\n\n| phase | GPU median | p95 | max | CPU median | max |\n"
       << "|---|---|---|---|---|---|\n";
    for (const char* phase : {"calm", "spawning", "after"})
        md << "| " << phase << " | " << j["gpu"][phase]["median_ms"].get<double>() << " | "
           << j["gpu"][phase]["p95_ms"].get<double>() << " | " << j["gpu"][phase]["max_ms"].get<double>()
           << " | " << j["cpu"][phase]["median_ms"].get<double>() << " | "
           << j["cpu"][phase]["max_ms"].get<double>() << " |\n";
    md << "\nPeak explosions drawn " << peakExplosions << ", dropped by the cap " << dropped
       << "; peak wakes drawn " << peakWakes << ", at most " << peakDroppedWakes << " dropped a frame. "
       << buildFrames << " frames compiled shader variants on first use (not in the table; the slowest took "
       << slowestBuild << " ms).\n";
    writeFileAtomically(a.outDir + "/storm.md", md.str());
}

} // namespace

int main(int argc, char** argv) {
    Args a;
    if (const auto code = parseArgs(argc, argv, a))
        return *code;
    return bench::runGlBench("pacifica-bench-storm-frames", a.outDir, {}, [&](gl::GlContext& context) {
        const std::string renderer = context.info().renderer;
        std::fprintf(stderr,
                     "pacifica-bench-storm-frames: GL_RENDERER %s; %dx%d, %d explosions, %d ships, %g s\n",
                     renderer.c_str(), a.size.first, a.size.second, a.explosions, a.ships, a.seconds);
        gl::GpuTimer timer(context.info(), 8);
        Storm storm(a);
        long long calm = 0, badSpawns = 0, bad = 0;
        const std::vector<Frame> frames = storm.run(timer, calm, badSpawns, bad);
        timer.drain();
        const std::vector<double>& gpuMs = timer.samples();
        const std::vector<Check> checks = check(frames, gpuMs, calm, badSpawns, bad, a, ocean::EffectsDesc{});
        writeReports(a, renderer, timer.clockName(), frames, gpuMs, calm, checks);
        bool ok = true;
        for (const Check& c : checks) {
            std::printf("%-22s %s: %s\n", c.name.c_str(), c.passed ? "ok" : "FAILED", c.detail.c_str());
            ok = ok && c.passed;
        }
        std::printf("wrote %s/storm.json, storm.md\n", a.outDir.c_str());
        return ok ? 0 : 1;
    });
}
