// pacifica-bench-soak: a long run of the ocean with effects coming and going, recording what would betray
// a leak or a drift -- resident memory, the GL objects alive by kind (gl::liveObjects), GPU memory where the
// driver reports it (GL_NVX_gpu_memory_info), frame time -- and checking that each stays flat.
//
// The scene, per frame of `--dt` seconds of sim time: the camera flies at 40 m/s, 300 m up; an explosion is
// spawned ahead of it every second (the cap at 32, so that their number is steady after a minute and the
// cap's drop path runs every second); a ship appears ahead every 15 s and leaves (its entity destroyed) 120 s
// later, so 8 sail at once; the number of views rendered per frame cycles 1, 2, 3 every 8 s, each view with
// its own targets (made when the count rises, freed when it falls). Every frame is render() of each view and
// glFinish(); frame time is the wall clock (steady_clock) around that, on any driver. A drain (ships gone, no
// spawns, 1 view, 400 s of sim time) shows what is left once the effects have ended; one after a minute of
// priming sets the baseline (every shader variant and pooled resource made once), one ends the run.
//
// Checks (exit 1 when one fails; each is in soak.json with its figures): after the warm-up (the first 10% of
// the samples), (1) no GL object kind holds more objects in the second half of the run than its peak in the
// first half; (2) after the final drain every kind is back to its baseline count;
// (3) resident memory grows by at most `--rss-growth-mib` from its peak in the first half to its peak in
// the second; (4) the median frame time of the last 10% of samples is at most `--frame-time-ratio` times
// that of samples 10-20% (0 leaves it unchecked: the test suite does, timing being a benchmark's business).
//
// Outputs in --out: soak.csv (one row per sample), soak.json (the checks), soak.gp and soak.png (gnuplot,
// when installed). `./pacifica bench soak --out DIR [--frames N]`; docs/RELIABILITY.md ("Soak").
#include "engine/Ecs.h"
#include "engine/Events.h"
#include "engine/Space.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanHost.h"

#include "BenchCli.h"
#include "BenchMain.h"
#include "BenchPlot.h"
#include "BenchText.h"

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

using namespace pacifica;

namespace {

constexpr double T0 = 1000.0;           // sim time of the first frame, s
constexpr double CAMERA_SPEED = 40.0;   // m/s, heading east
constexpr double ALTITUDE = 300.0;      // m
constexpr double SHIP_INTERVAL = 15.0;  // s between ships
constexpr double SHIP_LIFE = 120.0;     // s a ship sails before it leaves
constexpr double SHIP_SPEED = 10.0;     // m/s
constexpr double VIEW_PERIOD = 8.0;     // s per view count
constexpr double DRAIN_SECONDS = 400.0; // sim time of the drain
constexpr double DRAIN_DT = 8.0;        // s per drain frame
constexpr double WARM_UP_SHARE = 0.1;   // of the samples
constexpr int MAX_EXPLOSIONS = 32;      // the cap: a steady state within a minute, the drop path every second
constexpr double PRIME_SECONDS = 60.0;  // sim time of the priming run
constexpr double PRIME_DT = 1.0;        // s per priming frame

/// 1, 2, 3 views, VIEW_PERIOD seconds each.
int viewsAt(double t) {
    return 1 + static_cast<int>(std::fmod(std::floor(t / VIEW_PERIOD), 3.0));
}

struct Args {
    long long frames = 100000;
    std::pair<int, int> size{64, 36};
    double dt = 1.0 / 60.0;
    int samples = 500;
    double rssGrowthMiB = 16.0;
    double frameTimeRatio = 1.5;
    int leakTexturesEvery = 0; // self-test of the checks: keep a texture every N frames (0 = never)
    std::string outDir = "soak";
    std::string commandLine;
};

std::optional<int> parseArgs(int argc, char** argv, Args& a) {
    CLI::App app("pacifica-bench-soak: a long run with effects coming and going; RSS, GL objects by kind, "
                 "GPU memory and frame time must stay flat",
                 "pacifica-bench-soak");
    std::string size = "64x36";
    app.add_option("--frames", a.frames, "frames to render (default 100000)")
        ->check(CLI::Range(50LL, 100000000LL));
    app.add_option("--size", size, "view size WxH (default 64x36)")->check(bench::sizeValidator());
    app.add_option("--dt", a.dt, "sim seconds per frame (default 1/60)")->check(CLI::Range(1e-3, 10.0));
    app.add_option("--samples", a.samples, "rows of soak.csv (default 500)")->check(CLI::Range(10, 100000));
    app.add_option("--rss-growth-mib", a.rssGrowthMiB, "bound on the resident memory's growth (default 16)")
        ->check(CLI::Range(0.0, 1e6));
    app.add_option("--frame-time-ratio", a.frameTimeRatio,
                   "bound on late / early median frame time; 0 = unchecked (default 1.5)")
        ->check(CLI::Range(0.0, 1e6));
    app.add_option("--out", a.outDir, "output folder (default soak)");
    app.add_option(
           "--leak-textures-every", a.leakTexturesEvery,
           "self-test: keep one 4x4 texture every N frames, which the checks must catch (default 0: off)")
        ->check(CLI::Range(0, 1000000));
    if (const auto code = bench::parseCommandLine(app, argc, argv))
        return code;
    a.size = *bench::parseSize(size);
    a.commandLine = bench::commandLine(argc, argv);
    return std::nullopt;
}

double residentMiB() {
    std::ifstream statm("/proc/self/statm");
    long long pages = 0, resident = 0;
    statm >> pages >> resident;
    return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

/// GPU memory in use (MiB) where the driver reports it (GL_NVX_gpu_memory_info), else NaN.
double gpuMemoryUsedMiB() {
    if (!epoxy_has_gl_extension("GL_NVX_gpu_memory_info"))
        return std::nan("");
    GLint totalKiB = 0, availableKiB = 0;
    glGetIntegerv(GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX, &totalKiB);
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &availableKiB);
    return static_cast<double>(totalKiB - availableKiB) / 1024.0;
}

double median(std::vector<double> v) {
    if (v.empty())
        return std::nan("");
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

struct Sample {
    long long frame = 0;
    double simTime = 0.0, rssMiB = 0.0, gpuMiB = 0.0, frameMs = 0.0;
    gl::LiveObjects objects;
    int explosions = 0, wakes = 0, ships = 0, views = 0;
};

struct LiveShip {
    ecs::Entity entity;
    glm::dvec2 start;
    double born = 0.0;
};

/// The soak's world: the ocean, the effects system, the ships, the views' targets.
class Soak {
public:
    explicit Soak(const Args& a) : mArgs(a), mFx(mRegistry, mEvents, {.maxExplosions = MAX_EXPLOSIONS}) {
        mRegistry.emplace<ocean::OceanComponent>(mRegistry.create(), ocean::makeOcean({}));
    }

    glm::dvec3 camera(double t) const { return {2.0e5 + CAMERA_SPEED * (t - T0), -3.0e5, ALTITUDE}; }

    /// One frame at sim time t: spawns and ships when `effects`, then every view rendered; returns the
    /// wall-clock ms of the rendering (render() of each view and glFinish()).
    double frame(double t, bool effects, int views) {
        const glm::dvec3 cam = camera(t);
        if (effects)
            spawn(t, cam);
        else
            removeShips(std::numeric_limits<double>::infinity());
        for (const LiveShip& s : mShips)
            mRegistry.get<ocean::Ship>(s.entity).position =
                s.start + glm::dvec2(0.0, SHIP_SPEED) * (t - s.born);
        mEvents.dispatch();
        mFx.update(t, cam);
        setViews(views);
        const auto t0 = std::chrono::steady_clock::now();
        for (size_t v = 0; v < mTargets.size(); ++v) {
            Pose pose;
            pose.position = cam;
            pose.headingDeg = 90.0 + 120.0 * static_cast<double>(v);
            pose.pitchDeg = -20.0;
            const gl::FrameTargets& target = *mTargets[v];
            render(mRenderer, mRegistry,
                   ocean::makeOceanFrame(pose, static_cast<float>(60.0 * std::numbers::pi / 180.0),
                                         target.width(), target.height(), t, target.sceneFramebuffer().id(),
                                         0.5f));
        }
        glFinish();
        if (mArgs.leakTexturesEvery > 0 && ++mFrames % mArgs.leakTexturesEvery == 0 && effects)
            mLeaked.push_back(gl::Texture::create2D(GL_RGBA8, 4, 4));
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }

    /// DRAIN_SECONDS without spawns, ships or extra views, from t on.
    void drain(double t) {
        for (double d = DRAIN_DT; d <= DRAIN_SECONDS; d += DRAIN_DT)
            frame(t + d, false, 1);
    }

    Sample sample(long long frame, double t, double frameMs) const {
        const ocean::OceanStats& s = mRenderer.lastStats();
        return {frame,
                t,
                residentMiB(),
                gpuMemoryUsedMiB(),
                frameMs,
                gl::liveObjects(),
                s.explosions.active,
                s.wakes.active,
                static_cast<int>(mShips.size()),
                static_cast<int>(mTargets.size())};
    }

private:
    // An explosion 300-900 m ahead every whole second; a ship 1-2 km ahead every SHIP_INTERVAL; ships older
    // than SHIP_LIFE leave.
    void spawn(double t, const glm::dvec3& cam) {
        const auto second = static_cast<long long>(std::floor(t));
        if (second != mLastSecond) {
            mLastSecond = second;
            const double ahead = 300.0 + 600.0 * std::fmod(second * 0.618033988749895, 1.0);
            const double side = 400.0 * (std::fmod(second * 0.754877666246693, 1.0) - 0.5);
            mEvents.enqueue(ocean::SpawnExplosion{glm::dvec2(cam) + glm::dvec2(ahead, side), t,
                                                  1.0 + static_cast<double>(second % 3) * 0.5});
        }
        removeShips(t - SHIP_LIFE);
        if (t >= mNextShip) {
            mNextShip = t + SHIP_INTERVAL;
            const ecs::Entity e = mRegistry.create();
            const glm::dvec2 start = glm::dvec2(cam) + glm::dvec2(1000.0 + 1000.0 * std::fmod(t * 0.37, 1.0),
                                                                  -600.0 + 1200.0 * std::fmod(t * 0.61, 1.0));
            mRegistry.emplace<ocean::Ship>(
                e, ocean::Ship{start, 40.0 + 10.0 * static_cast<double>(mShips.size() % 4)});
            mEvents.enqueue(ocean::AttachShipTrail{e, {}});
            mShips.push_back({e, start, t});
        }
    }

    void removeShips(double bornBefore) {
        std::erase_if(mShips, [&](const LiveShip& s) {
            if (s.born >= bornBefore)
                return false;
            mRegistry.destroy(s.entity);
            return true;
        });
    }

    void setViews(int n) {
        while (static_cast<int>(mTargets.size()) < n)
            mTargets.push_back(std::make_unique<gl::FrameTargets>(mArgs.size.first, mArgs.size.second));
        while (static_cast<int>(mTargets.size()) > n)
            mTargets.pop_back();
    }

    const Args& mArgs;
    ecs::Registry mRegistry;
    ecs::EventQueue mEvents;
    ocean::EffectsSystem mFx;
    ocean::OceanRenderer mRenderer;
    std::vector<std::unique_ptr<gl::FrameTargets>> mTargets;
    std::vector<LiveShip> mShips;
    std::vector<gl::Texture> mLeaked; // --leak-textures-every
    long long mFrames = 0;
    long long mLastSecond = -1;
    double mNextShip = 0.0;
};

struct Check {
    std::string name;
    bool passed = true;
    std::string detail;
};

/// The four checks of the header over `samples` (after the warm-up), `first` (after the priming's drain)
/// and `drained` (after the final drain).
std::vector<Check> check(const std::vector<Sample>& samples, const gl::LiveObjects& first,
                         const gl::LiveObjects& drained, const Args& a) {
    const size_t n = samples.size(), warm = std::max<size_t>(1, static_cast<size_t>(n * WARM_UP_SHARE)),
                 half = warm + (n - warm) / 2;
    std::vector<Check> out;
    Check grow{"gl_objects_do_not_grow", true, ""};
    Check drain{"gl_objects_return_after_drain", true, ""};
    for (int k = 0; k < gl::OBJECT_KIND_COUNT; ++k) {
        const auto kind = static_cast<gl::ObjectKind>(k);
        long long early = 0, late = 0;
        for (size_t i = warm; i < n; ++i)
            (i < half ? early : late) = std::max(i < half ? early : late, samples[i].objects.of(kind));
        grow.detail += std::string(k ? ", " : "") + gl::toString(kind) + " " + std::to_string(early) +
                       " -> " + std::to_string(late);
        grow.passed = grow.passed && late <= early;
        drain.detail += std::string(k ? ", " : "") + gl::toString(kind) + " " +
                        std::to_string(first.of(kind)) + " -> " + std::to_string(drained.of(kind));
        drain.passed = drain.passed && drained.of(kind) == first.of(kind);
    }
    out.push_back(grow);
    out.push_back(drain);
    double rssEarly = 0.0, rssLate = 0.0;
    for (size_t i = warm; i < n; ++i)
        (i < half ? rssEarly : rssLate) = std::max(i < half ? rssEarly : rssLate, samples[i].rssMiB);
    out.push_back({"rss_flat", rssLate - rssEarly <= a.rssGrowthMiB,
                   "peak " + bench::num(rssEarly, 5) + " MiB in the first half, " + bench::num(rssLate, 5) +
                       " MiB in the second (bound +" + bench::num(a.rssGrowthMiB) + ")"});
    std::vector<double> early, late;
    for (size_t i = 0; i < n; ++i) {
        if (i >= n / 10 && i < n / 5)
            early.push_back(samples[i].frameMs);
        if (i >= n - n / 10)
            late.push_back(samples[i].frameMs);
    }
    const double ratio = median(late) / median(early);
    out.push_back(
        {"frame_time_flat", a.frameTimeRatio <= 0.0 || ratio <= a.frameTimeRatio,
         "median " + bench::num(median(early), 4) + " ms at 10-20% of the run, " +
             bench::num(median(late), 4) + " ms in the last 10%: ratio " + bench::num(ratio, 3) +
             (a.frameTimeRatio > 0.0 ? " (bound " + bench::num(a.frameTimeRatio) + ")" : " (unchecked)")});
    return out;
}

void writeCsv(const std::string& path, const std::vector<Sample>& samples) {
    writeFileAtomically(path, [&](std::ostream& o) {
        o << "frame,sim_time_s,rss_mib,gpu_memory_used_mib,frame_ms_median";
        for (int k = 0; k < gl::OBJECT_KIND_COUNT; ++k)
            o << ",gl_" << gl::toString(static_cast<gl::ObjectKind>(k));
        o << ",gl_total,explosions_active,wakes_active,ships,views\n";
        for (const Sample& s : samples) {
            o << s.frame << ',' << bench::num(s.simTime, 9) << ',' << bench::num(s.rssMiB, 6) << ','
              << (std::isnan(s.gpuMiB) ? std::string() : bench::num(s.gpuMiB, 6)) << ','
              << bench::num(s.frameMs, 5);
            for (long long c : s.objects.count)
                o << ',' << c;
            o << ',' << s.objects.total() << ',' << s.explosions << ',' << s.wakes << ',' << s.ships << ','
              << s.views << '\n';
        }
    });
}

void writePlotScript(const std::string& path, const std::string& renderer, const Args& a) {
    std::ostringstream gp;
    gp << "# pacifica-bench-soak's curves: cd into this folder, then gnuplot soak.gp\n"
       << "set terminal pngcairo size 1400,1000 font 'DejaVu Sans,11' noenhanced\n"
       << "set output 'soak.png'\nset datafile separator ','\nset key autotitle columnhead\n"
       << "set multiplot layout 2,2 title \""
       << "pacifica-bench-soak, " << a.frames << " frames at " << a.size.first << "x" << a.size.second << ", "
       << renderer << "\"\n"
       << "set grid\nset xlabel 'frame'\n"
       << "set title 'resident memory since the first sample (MiB; dashed: the bound)'\n"
       << "set yrange [-1:" << a.rssGrowthMiB + 1.0 << "]\n"
       << "first = system(\"sed -n 2p soak.csv | cut -d, -f3\") + 0\n"
       << "plot 'soak.csv' using 1:($3 - first) with lines lw 2 title 'rss_mib', " << a.rssGrowthMiB
       << " with lines dt 2 title 'bound'\nset autoscale y\n"
       << "set title 'GL objects alive'\nplot for [c=6:13] 'soak.csv' using 1:c with steps, "
          "'soak.csv' using 1:14 with steps lw 2\n"
       << "set title 'frame time, median of each sample window (ms, steady_clock around render + glFinish)'\n"
       << "plot 'soak.csv' using 1:5 with lines\n"
       << "set title 'effects and views'\nplot for [c=15:18] 'soak.csv' using 1:c with steps\n"
       << "unset multiplot\n";
    writeFileAtomically(path, gp.str());
}

} // namespace

int main(int argc, char** argv) {
    Args a;
    if (const auto code = parseArgs(argc, argv, a))
        return *code;
    return bench::runGlBench("pacifica-bench-soak", a.outDir, {"soak.png"}, [&](gl::GlContext& context) {
        const std::string renderer = context.info().renderer;
        std::fprintf(stderr, "pacifica-bench-soak: GL_RENDERER %s; %lld frames at %dx%d, dt %g s\n",
                     renderer.c_str(), a.frames, a.size.first, a.size.second, a.dt);
        Soak soak(a);
        // Priming: a minute of the same scene (every shader variant and pooled resource made once), then a
        // drain; what is alive after it is the baseline that the main run's drain must return to.
        double t = T0 - PRIME_SECONDS - DRAIN_SECONDS;
        for (; t < T0 - DRAIN_SECONDS; t += PRIME_DT)
            soak.frame(t, true, viewsAt(t));
        soak.drain(t);
        const gl::LiveObjects first = gl::liveObjects();
        const long long every = std::max<long long>(1, a.frames / a.samples);
        std::vector<Sample> samples;
        std::vector<double> window;
        for (long long f = 0; f < a.frames; ++f) {
            t = T0 + static_cast<double>(f) * a.dt;
            window.push_back(soak.frame(t, true, viewsAt(t)));
            if ((f + 1) % every == 0) {
                samples.push_back(soak.sample(f, t, median(window)));
                window.clear();
            }
        }
        soak.drain(t);
        const gl::LiveObjects drained = gl::liveObjects();
        const std::vector<Check> checks = check(samples, first, drained, a);
        writeCsv(a.outDir + "/soak.csv", samples);
        nlohmann::json j;
        j["command"] = a.commandLine;
        j["date"] = bench::utcNow();
        j["gl_renderer"] = renderer;
        j["clock"] = "steady_clock around render() of every view + glFinish()";
        bool ok = true;
        for (const Check& c : checks) {
            j["checks"][c.name] = {{"passed", c.passed}, {"detail", c.detail}};
            ok = ok && c.passed;
            std::printf("%-32s %s: %s\n", c.name.c_str(), c.passed ? "ok" : "FAILED", c.detail.c_str());
        }
        j["passed"] = ok;
        writeFileAtomically(a.outDir + "/soak.json", j.dump(2) + "\n");
        writePlotScript(a.outDir + "/soak.gp", renderer, a);
        const bool plotted = bench::runGnuplot(a.outDir, "soak.gp", "soak.png");
        std::printf("wrote %s/soak.csv, soak.json%s\n", a.outDir.c_str(), plotted ? ", soak.png" : "");
        return ok ? 0 : 1;
    });
}
