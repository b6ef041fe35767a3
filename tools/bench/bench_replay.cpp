// pacifica-bench: the replay benchmarks of the foundation issue — replay throughput at 640x360 (frames/s with
// and without writing images) and the time to the first frame of a fresh `pacifica replay` process. The
// per-frame benchmarks time the frames of the real replay run (tools::ReplaySession, the same code as
// `pacifica replay`) in-process; the time-to-first-frame benchmark runs the CLI as a subprocess. Speed
// targets live here, never in tests (docs/BENCHMARKS.md says how to run and read it).
//
// Own flags, read before Google Benchmark sees the command line:
//   --pacifica-cli=PATH   the CLI binary to time (default: `pacifica` next to this binary)
// Environment: PACIFICA_SOURCE_DIR overrides the repository root compiled in (tools/data/demo_flight.csv).
#include "OceanOptions.h"
#include "Replay.h"
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

/// The replay run a frame benchmark times: `pacifica replay tools/data/demo_flight.csv --size 640x360` (the
/// CLI's defaults: --fps 10, --fov 60, the high preset), into a temporary directory, without the flight's
/// events and objects (the plain ocean), with or without images. One session lives at a time (each has its
/// own GL context): switching variants replaces it, and a new one renders two frames untimed first.
class Sessions {
public:
    tools::ReplaySession& get(bool writeImages) {
        if (!mSession || mImages != writeImages) {
            mSession.reset();
            mDir.reset();
            mDir = std::make_unique<TempDir>(writeImages ? "frames" : "hashes");
            tools::ReplayOptions o;
            o.flight = sourceDir() / "tools/data/demo_flight.csv";
            o.outDir = mDir->path() / "out";
            o.width = WIDTH;
            o.height = HEIGHT;
            o.writeImages = writeImages;
            o.events = false;
            o.objects = false;
            o.progress = false;
            o.ocean = tools::toOceanDesc(tools::OceanOptions{});
            mSession = std::make_unique<tools::ReplaySession>(o);
            mImages = writeImages;
            // Warm-up, untimed: the first frames of a context pay llvmpipe's lazy shader JIT and the
            // ocean's map generation, which BM_TimeToFirstFrame measures; the frame benchmarks measure the
            // steady state.
            for (long long k = 0; k < 2; ++k)
                mSession->renderFrame(k);
        }
        return *mSession;
    }
    void reset() {
        mSession.reset();
        mDir.reset();
    }

private:
    std::unique_ptr<TempDir> mDir; // outlives the session: its staging directory is inside
    std::unique_ptr<tools::ReplaySession> mSession;
    bool mImages = false;
};

Sessions gSessions;
fs::path gCli;
bool gFailed = false; // a benchmark skipped with an error: the process exits non-zero

/// BM_ReplayFrame/no_images and /with_images: one frame of the real replay run per iteration
/// (ReplaySession::renderFrame: the pose, render + objects pass + tonemap inside the GpuTimer, both
/// readbacks, then the half conversion + hash, or the EXR + PNG handed to the encoder thread as the CLI
/// does, and the frame's summary record). Manual time: steady_clock around the frame; the readbacks wait for
/// the GPU, so GPU work is included on any driver. Each variant has its own frame counter that carries on
/// across its runs (estimation and repetitions), wrapping within the flight, so both variants walk the same
/// frame sequence and the repetitions do not all re-render the same frames.
void replayFrame(benchmark::State& state, bool writeImages) {
    static long long nextFrame[2] = {0, 0};
    long long& k = nextFrame[writeImages ? 1 : 0];
    try {
        tools::ReplaySession& session = gSessions.get(writeImages);
        const std::vector<double>& gpu = *session.info().gpuMs;
        const size_t gpuSamples0 = gpu.size();
        for (auto _ : state) {
            const auto t0 = Clock::now();
            session.renderFrame(k++ % session.frameCount());
            state.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
        }
        state.SetItemsProcessed(state.iterations()); // items = frames: items_per_second is frames/s
        double gpuMs = 0.0;
        for (size_t i = gpuSamples0; i < gpu.size(); ++i)
            gpuMs += gpu[i];
        if (gpu.size() > gpuSamples0)
            state.counters["gpu_ms"] = gpuMs / static_cast<double>(gpu.size() - gpuSamples0);
        state.SetLabel("frame: manual steady_clock; gpu_ms: render+objects+tonemap, " +
                       session.info().gpuClock);
    } catch (const std::exception& e) {
        gFailed = true;
        state.SkipWithError(e.what());
    }
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
        const tools::ReplayRunInfo& info = gSessions.get(false).info();
        logInfo("pacifica-bench: GL_RENDERER=" + info.glRenderer + ", clock: " + info.gpuClock +
                ", CLI: " + gCli.string());
        benchmark::AddCustomContext("gl_renderer", info.glRenderer);
        benchmark::AddCustomContext("gl_version", info.glVersion);
        benchmark::AddCustomContext("gpu_clock", info.gpuClock);
        benchmark::AddCustomContext("frame_clock", "steady_clock wall time (manual time) per frame");
        benchmark::AddCustomContext("frame_size", std::to_string(WIDTH) + "x" + std::to_string(HEIGHT));
        benchmark::AddCustomContext("ocio_config", info.ocioConfig);
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
        gSessions.reset();
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
