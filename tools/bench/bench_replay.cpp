// pacifica-bench: the replay benchmarks of the foundation issue — replay throughput at 640x360 (frames/s with
// and without writing images) and the time to the first frame of a fresh `pacifica replay` process. The
// per-frame benchmarks repeat the work runReplay() (tools/src/Replay.cpp) does for one frame (all of it but
// the frame's summary.json record and progress line), in one headless GL context shared by all benchmarks;
// the time-to-first-frame benchmark runs the real CLI as a subprocess. Speed targets live here, never in
// tests (docs/BENCHMARKS.md says how to run and read it).
//
// Own flags, read before Google Benchmark sees the command line:
//   --pacifica-cli=PATH   the CLI binary to time (default: `pacifica` next to this binary)
// Environment: PACIFICA_SOURCE_DIR overrides the repository root compiled in (tools/data/demo_flight.csv).
#include "FlightPath.h"
#include "engine/Ecs.h"
#include "engine/Log.h"
#include "engine/Space.h"
#include "engine/capture/Capture.h"
#include "engine/color/ColorPipeline.h"
#include "engine/color/Tonemapper.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "ocean/Ocean.h"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <numbers>
#include <optional>
#include <spawn.h>
#include <stdexcept>
#include <string>
#include <string_view>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace pacifica;
using Clock = std::chrono::steady_clock;

constexpr int WIDTH = 640;
constexpr int HEIGHT = 360;
constexpr double FRAME_STEP_S = 0.1;     // the CLI's default --fps 10
constexpr float FOV_Y_DEG = 60.0f;       // the CLI's default --fov
constexpr int REPETITIONS = 5;           // medians of 5 unless --benchmark_repetitions says otherwise
constexpr double FRAME_MIN_TIME_S = 1.5; // per repetition (a frame is 0.3-0.6 s on 2-core llvmpipe) unless
                                         // --benchmark_min_time says otherwise

fs::path sourceDir() {
    if (const char* env = std::getenv("PACIFICA_SOURCE_DIR"); env && *env)
        return env;
    return PACIFICA_SOURCE_DIR;
}

/// A fresh directory under the system temp directory, removed (with everything in it) on destruction.
class TempDir {
public:
    explicit TempDir(const std::string& tag) {
        std::string pattern = (fs::temp_directory_path() / ("pacifica-bench-" + tag + "-XXXXXX")).string();
        if (!mkdtemp(pattern.data()))
            throw std::runtime_error("mkdtemp(" + pattern + "): " + std::strerror(errno));
        mPath = pattern;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(mPath, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return mPath; }

private:
    fs::path mPath;
};

/// Everything one replay frame needs, built once in one headless context: the same objects, in the same
/// order, as runReplay() builds them.
struct ReplayScene {
    tools::FlightPath flight;
    color::ColorPipeline colour;
    std::unique_ptr<gl::GlContext> context; // declared before every GL object: destroyed after them
    ecs::Registry registry;
    ocean::OceanRenderer renderer;
    gl::FrameTargets targets;
    color::Tonemapper tonemapper;
    gl::GpuTimer gpuTimer;
    std::vector<float> scene, display;

    explicit ReplayScene(const fs::path& flightFile)
        : flight(tools::FlightPath::load(flightFile)), colour(makeColour()),
          context(gl::createHeadlessContext()), renderer(), targets(WIDTH, HEIGHT), tonemapper(colour),
          gpuTimer(context->info()) {
        registry.emplace<ocean::OceanComponent>(registry.create(), ocean::makeOcean({}));
    }

    static color::ColorPipeline makeColour() {
        color::ColorPipeline c = color::ColorPipeline::fromEnvironmentOr(std::nullopt);
        c.select("", "");
        return c;
    }

    /// Frame k of a run: successive times 1/10 s apart, wrapping within the flight.
    double timeOfFrame(long long k) const {
        const double duration = flight.endTime() - flight.startTime();
        return flight.startTime() + std::fmod(static_cast<double>(k) * FRAME_STEP_S, duration);
    }

    /// One frame of `pacifica replay` (the body of runReplay()'s loop): render + tonemap (timed by the
    /// GpuTimer, as the CLI does), both readbacks, then either the half conversion + hash (--no-images) or
    /// the EXR + PNG writes into dir (files overwritten every frame). Returns the frame's pixel hash.
    uint64_t renderFrame(long long k, const fs::path* imageDir) {
        const double t = timeOfFrame(k);
        const Pose pose = flight.poseAt(t);
        const ocean::OceanFrame frame =
            ocean::makeOceanFrame(pose, FOV_Y_DEG * static_cast<float>(std::numbers::pi / 180.0), WIDTH,
                                  HEIGHT, t, targets.sceneFramebuffer().id());

        gpuTimer.begin();
        renderer.render(registry, frame);
        tonemapper.run(targets.sceneColor(), targets.displayFramebuffer(), WIDTH, HEIGHT);
        gpuTimer.end();
        targets.readScene(scene); // glReadPixels into client memory: waits for the GPU
        targets.readDisplay(display);

        if (!imageDir) {
            const std::vector<uint16_t> half = capture::toHalf(scene.data(), scene.size());
            return capture::hashHalfPixels(half.data(), half.size());
        }
        capture::Metadata meta;
        meta.numbers = {{"frame", static_cast<double>(k)},   {"time_s", t},
                        {"camera_x_m", pose.position.x},     {"camera_y_m", pose.position.y},
                        {"camera_z_m", pose.position.z},     {"camera_heading_deg", pose.headingDeg},
                        {"camera_pitch_deg", pose.pitchDeg}, {"camera_roll_deg", pose.rollDeg}};
        meta.strings = {{"ocio_config", colour.configDescription()},
                        {"ocio_display", colour.selectedDisplay()},
                        {"ocio_view", colour.selectedView()},
                        {"gl_renderer", context->info().renderer},
                        {"flight", "demo_flight.csv"}};
        const uint64_t hash =
            capture::writeExrHalf(*imageDir / "frame.exr", WIDTH, HEIGHT, 4, scene.data(), meta);
        capture::writePng8(*imageDir / "frame.png", WIDTH, HEIGHT, 4, display.data());
        return hash;
    }
};

ReplayScene* gScene = nullptr;
fs::path gCli;
bool gFailed = false; // a benchmark skipped with an error: the process exits non-zero

/// BM_ReplayFrame/no_images and /with_images: one replay frame per iteration. Manual time: steady_clock
/// around the whole frame (pose to hash or image writes); the readbacks inside it wait for the GPU, so GPU
/// work is included on any driver. Each variant has its own frame counter that starts at the flight's
/// first frame and carries on across its runs (estimation and repetitions), so both variants walk the
/// same frame sequence and the repetitions do not all re-render the same frames.
void replayFrame(benchmark::State& state, bool writeImages) {
    static long long nextFrame[2] = {0, 0};
    long long& k = nextFrame[writeImages ? 1 : 0];
    std::optional<TempDir> dir;
    if (writeImages)
        dir.emplace("frames");
    const size_t gpuSamples0 = gScene->gpuTimer.samples().size();
    uint64_t hashes = 0;
    for (auto _ : state) {
        const auto t0 = Clock::now();
        hashes ^= gScene->renderFrame(k++, dir ? &dir->path() : nullptr);
        state.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
    }
    benchmark::DoNotOptimize(hashes);
    state.SetItemsProcessed(state.iterations()); // items = frames: items_per_second is frames/s
    const std::vector<double>& gpu = gScene->gpuTimer.samples();
    double gpuMs = 0.0;
    for (size_t i = gpuSamples0; i < gpu.size(); ++i)
        gpuMs += gpu[i];
    if (gpu.size() > gpuSamples0)
        state.counters["gpu_ms"] = gpuMs / static_cast<double>(gpu.size() - gpuSamples0);
    state.SetLabel("frame: manual steady_clock; gpu_ms: render+tonemap, " +
                   std::string(gScene->gpuTimer.clockName()));
}

/// Runs `pacifica replay` for one frame; returns the wall seconds from spawn to exit and, if it could be
/// read, summary.json's timings.time_to_first_frame_s. Throws with the CLI's output tail on failure.
struct CliRun {
    double wallSeconds = 0.0;
    std::optional<double> summaryFirstFrameSeconds;
};

CliRun runCliOnce(const fs::path& work, const std::vector<std::string>& extraEnv) {
    const fs::path out = work / "out", log = work / "cli.log";
    std::error_code ec;
    fs::remove_all(out, ec);
    const std::string flight = (sourceDir() / "tools/data/demo_flight.csv").string();
    std::vector<std::string> args = {gCli.string(), "replay",  flight,    "--out",
                                     out.string(),  "--start", "0",       "--end",
                                     "0",           "--size",  "640x360", "--no-progress"};
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e) {
        const std::string_view var(*e);
        bool replaced = false;
        for (const std::string& x : extraEnv)
            replaced = replaced || var.substr(0, var.find('=') + 1) == x.substr(0, x.find('=') + 1);
        if (!replaced)
            env.emplace_back(var);
    }
    env.insert(env.end(), extraEnv.begin(), extraEnv.end());
    std::vector<char*> argv, envp;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    for (std::string& e : env)
        envp.push_back(e.data());
    envp.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);

    CliRun run;
    const auto t0 = Clock::now();
    pid_t pid = 0;
    const int spawnErr = posix_spawn(&pid, gCli.c_str(), &actions, nullptr, argv.data(), envp.data());
    int status = 0;
    if (spawnErr == 0)
        waitpid(pid, &status, 0);
    run.wallSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    posix_spawn_file_actions_destroy(&actions);
    if (spawnErr != 0)
        throw std::runtime_error("cannot start " + gCli.string() + ": " + std::strerror(spawnErr) +
                                 " (pass --pacifica-cli=PATH)");
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::ifstream in(log);
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (text.size() > 600)
            text = "..." + text.substr(text.size() - 600);
        throw std::runtime_error(gCli.string() + " replay failed (status " + std::to_string(status) +
                                 "): " + text);
    }
    try {
        std::ifstream in(out / "summary.json");
        const nlohmann::json summary = nlohmann::json::parse(in);
        run.summaryFirstFrameSeconds = summary.at("timings").at("time_to_first_frame_s").get<double>();
    } catch (const std::exception&) {
        // Optional figure: a missing or reshaped summary leaves the counter out, the timing stands.
    }
    return run;
}

/// BM_TimeToFirstFrame/cold_shader_cache and /warm_shader_cache: a fresh `pacifica replay` process that
/// renders one 640x360 frame, timed with steady_clock from spawn to exit (process start, dynamic linking
/// incl. OIIO's libraries, EGL context, shader compiles, ocean map generation, the first frame with its
/// EXR + PNG, summary.json). Mesa's shader cache makes a large difference on llvmpipe, so it is pinned:
/// cold = MESA_SHADER_CACHE_DISABLE=true; warm = a private MESA_SHADER_CACHE_DIR primed by one untimed run.
void timeToFirstFrame(benchmark::State& state, bool warmCache) {
    try {
        TempDir work("ttff");
        std::vector<std::string> env;
        if (warmCache) {
            env = {"MESA_SHADER_CACHE_DISABLE=false",
                   "MESA_SHADER_CACHE_DIR=" + (work.path() / "mesa").string()};
            runCliOnce(work.path(), env); // primes the cache; not timed
        } else {
            env = {"MESA_SHADER_CACHE_DISABLE=true"};
        }
        double summarySum = 0.0;
        int summaryCount = 0;
        for (auto _ : state) {
            const CliRun run = runCliOnce(work.path(), env);
            state.SetIterationTime(run.wallSeconds);
            if (run.summaryFirstFrameSeconds) {
                summarySum += *run.summaryFirstFrameSeconds;
                ++summaryCount;
            }
        }
        if (summaryCount > 0)
            state.counters["in_process_s"] = summarySum / summaryCount;
        state.SetLabel("spawn->exit steady_clock; in_process_s: summary.json time_to_first_frame_s");
    } catch (const std::exception& e) {
        gFailed = true;
        state.SkipWithError(e.what());
    }
}

/// Extracts --pacifica-cli=PATH (Google Benchmark rejects flags it does not know) and notes whether the
/// command line sets its own repetitions or minimum time: a benchmark's own Repetitions() / MinTime()
/// would override those flags, so they are only set when the command line leaves them out.
void parseOwnFlags(int& argc, char** argv, bool& userRepetitions, bool& userMinTime) {
    gCli = fs::read_symlink("/proc/self/exe").parent_path() / "pacifica";
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a(argv[i]);
        if (a.starts_with("--pacifica-cli=")) {
            gCli = fs::absolute(std::string(a.substr(std::strlen("--pacifica-cli="))));
            continue;
        }
        if (a.starts_with("--benchmark_repetitions"))
            userRepetitions = true;
        if (a.starts_with("--benchmark_min_time"))
            userMinTime = true;
        argv[kept++] = argv[i];
    }
    argc = kept;
    argv[argc] = nullptr;
}

} // namespace

int main(int argc, char** argv) {
    bool userRepetitions = false, userMinTime = false;
    parseOwnFlags(argc, argv, userRepetitions, userMinTime);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;
    try {
        ReplayScene scene(sourceDir() / "tools/data/demo_flight.csv");
        gScene = &scene;
        // Warm-up, untimed: the first frames pay llvmpipe's lazy shader JIT and the ocean's map generation,
        // which BM_TimeToFirstFrame measures; the frame benchmarks measure the steady state.
        for (long long k = 0; k < 2; ++k)
            scene.renderFrame(k, nullptr);
        logInfo("pacifica-bench: GL_RENDERER=" + scene.context->info().renderer +
                ", clock: " + scene.gpuTimer.clockName() + ", CLI: " + gCli.string());
        benchmark::AddCustomContext("gl_renderer", scene.context->info().renderer);
        benchmark::AddCustomContext("gl_version", scene.context->info().version);
        benchmark::AddCustomContext("gpu_clock", scene.gpuTimer.clockName());
        benchmark::AddCustomContext("frame_clock", "steady_clock wall time (manual time) per frame");
        benchmark::AddCustomContext("frame_size", std::to_string(WIDTH) + "x" + std::to_string(HEIGHT));
        benchmark::AddCustomContext("ocio_config", scene.colour.configDescription());
        benchmark::AddCustomContext("pacifica_cli", gCli.string());

        auto common = [&](benchmark::internal::Benchmark* b) {
            b->UseManualTime()->Unit(benchmark::kMillisecond);
            if (!userRepetitions)
                b->Repetitions(REPETITIONS)->ReportAggregatesOnly(true);
        };
        for (const bool images : {false, true}) {
            benchmark::internal::Benchmark* b = benchmark::RegisterBenchmark(
                images ? "BM_ReplayFrame/with_images" : "BM_ReplayFrame/no_images", replayFrame, images);
            common(b);
            if (!userMinTime)
                b->MinTime(FRAME_MIN_TIME_S);
        }
        // One process per iteration: each is 1.5-5 s on llvmpipe, so the median of 5 single runs.
        common(benchmark::RegisterBenchmark("BM_TimeToFirstFrame/cold_shader_cache", timeToFirstFrame, false)
                   ->Iterations(1));
        common(benchmark::RegisterBenchmark("BM_TimeToFirstFrame/warm_shader_cache", timeToFirstFrame, true)
                   ->Iterations(1));

        const size_t ran = benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        gScene = nullptr;
        if (ran == 0) {
            std::fprintf(stderr, "pacifica-bench: error: no benchmark matched the filter\n");
            return 1;
        }
        if (gFailed) {
            std::fprintf(stderr, "pacifica-bench: error: a benchmark failed (see its error above)\n");
            return 1;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica-bench: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
