// pacifica: the command-line tool. Subcommands:
//   replay FLIGHT --out DIR [--fps N] [--size WxH] [--start S --end S] [--display D --view V]
//          [--ocio-config FILE] [--no-images] [--env FILE] [--frames I-J] [ocean options: OceanOptions.h]
//   tonemap compare INPUT... --out DIR [--ocio-config FILE]... [--lut3d N] [--max-pixels N]
//   convert RECORDING OUT.txt.acmi
//   farm run RECORDING... --out RUN [--chunk-frames N] [--engine local|slurm] ... -- REPLAY OPTIONS
//   farm resume|status RUN; farm chunk RUN I; farm merge RUN (what the engines' tasks run)
// Any failure prints "pacifica: error: ..." naming the file/line/option and exits non-zero, leaving no
// partial output behind.
#include "ChunkFrames.h"
#include "Farm.h"
#include "OceanOptions.h"
#include "Replay.h"
#include "ReplayInput.h"
#include "TonemapCompare.h"
#include "engine/AtomicFile.h"
#include "engine/capture/Capture.h"

#include <recording/AcmiWriter.h>
#include <recording/Recording.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <optional>
#include <string>
#include <vector>

namespace {

namespace tools = pacifica::tools;

/// `pacifica replay`: its options as typed, then ReplayOptions (tools/src/Replay.h) from them.
struct ReplayCommand {
    CLI::App* app = nullptr;
    tools::ReplayOptions replay;
    std::string flight, outDir, size = "640x360", ocioConfig, start, end, video, environment, frames;
    std::string runKey; ///< the command line less --frames, --cuda-device and --no-progress (replayRunKey)
    /// The run key with the program's and the inputs' hashes (runKeyWithContents) even without --frames:
    /// the farm's plan, which must name what its chunks will. A plain run does not read them for nothing.
    bool keyWithContents = false;
    std::string imageCompression = "fast";
    std::vector<std::string> views;
    bool noImages = false, noProgress = false, listObjects = false, noEvents = false, noObjects = false;
    CLI::Option *videoOpt = nullptr, *startOpt = nullptr, *endOpt = nullptr, *ocioOpt = nullptr,
                *envOpt = nullptr, *framesOpt = nullptr;
    tools::OceanOptions ocean;

    void add(CLI::App& parent);
    void addOutputOptions();
    tools::ReplayOptions options() const;
    int run() const;
};

void ReplayCommand::add(CLI::App& parent) {
    app = parent.add_subcommand("replay", "render a flight (Tacview ACMI text/zip, IGC, or the CSV of "
                                          "docs/FLIGHT_FORMAT.md) to EXR + PNG frames");
    app->add_option("flight", flight, "flight file: Tacview ACMI (text or zip), IGC, or flight CSV")
        ->required();
    app->add_option("--out", outDir, "output directory (created if missing)");
    app->add_flag("--list-objects", listObjects,
                  "print the recording's objects (id, type, name, pilot, time span, altitudes, share at the "
                  "sea surface of --model/--wind... and over the sea) and exit");
    app->add_option("--rig", replay.rigs,
                    "camera rig KIND:OBJECT[,key=value...] (cockpit, chase, orbit, fixed, lookat; size=WxH, "
                    "fov=DEG, name=N); repeat for several views; CSV flights: path")
        ->expected(1)
        ->take_all();
    videoOpt = app->add_option("--video", video,
                               "also encode the first view as FILE.mp4 (H.264) or .mov (ProRes) with ffmpeg");
    app->add_option("--speed", replay.speed, "recording seconds per video second (time-lapse)")
        ->default_val(1.0);
    app->add_option("--max-frames", replay.maxFrames, "refuse runs with more frames than this")
        ->default_val(100000);
    app->add_option_function<std::string>(
           "--egl-device",
           [this](const std::string& v) {
               replay.eglDeviceAuto = v == "auto";
               if (!replay.eglDeviceAuto)
                   replay.eglDevice = std::stoi(v);
           },
           "render on EGL device N (eglQueryDevicesEXT's order, software included), or auto: the first GPU "
           "of CUDA_VISIBLE_DEVICES, as --cuda-device (default: the first GPU, else Mesa's surfaceless "
           "llvmpipe)")
        ->type_name("N|auto")
        ->check(CLI::IsMember({"auto"}) | CLI::Range(0, 15));
    app->add_option("--cuda-device", replay.cudaDevice,
                    "render on this CUDA device (an index as CUDA numbers the visible GPUs, or a GPU-UUID), "
                    "found through EGL_NV_device_cuda (docs/SCALE.md)");
    app->add_option("--fps", replay.fps, "frames per simulated second")->default_val(10.0);
    app->add_option("--size", size, "frame size WxH")->default_val("640x360");
    startOpt = app->add_option(
        "--start", start, "first frame time: seconds or UTC YYYY-MM-DDTHH:MM:SSZ (default: flight start)");
    endOpt = app->add_option("--end", end, "last frame time: seconds or UTC timestamp (default: flight end)");
    app->add_option("--display", replay.display, "OCIO display (default: the config's default)");
    app->add_option("--view", views,
                    "OCIO view (default: the display's default); repeat to tonemap the same render several "
                    "ways (frame_NNNNN.<view>.png per extra view)")
        ->expected(1)
        ->take_all();
    ocioOpt = app->add_option("--ocio-config", ocioConfig, "OCIO config file (overrides $OCIO)");
    addOutputOptions();
    tools::addOceanOptions(*app, ocean);
}

/// What is written and drawn, and --env (the order of --help stays as it was).
void ReplayCommand::addOutputOptions() {
    app->add_flag("--no-images", noImages, "render and read back but write no images (benchmarking)");
    app->add_flag("--no-progress", noProgress, "no progress line");
    app->add_option("--image-compression", imageCompression,
                    "zlib level of the lossless EXR (ZIP) and PNG files: fast (1; ~2x faster to encode, "
                    "1.1-1.3x the bytes) or small (6)")
        ->check(CLI::IsMember({"fast", "small"}))
        ->default_val("fast");
    app->add_flag(
        "--profile", replay.profile,
        "time every pass (sky, sea, effects, objects, tonemap, readback, encode) into summary.json");
    app->add_flag("--no-objects", noObjects, "do not draw the recording's aircraft, ships and weapons");
    app->add_flag("--no-events", noEvents,
                  "ignore the flight file's explosions and ships (the plain ocean, for comparisons)");
    app->add_option("--fov", replay.fovYDeg, "vertical field of view, degrees")->default_val(60.0f);
    framesOpt =
        app->add_option("--frames", frames,
                        "render only frames I-J (0-based, inclusive) of the run: a chunk of a sharded "
                        "run, resumable; its summary is chunk-IIIII-JJJJJ.json (docs/SCALE.md)");
    envOpt =
        app->add_option("--env", environment,
                        "HDR lat-long environment EXR for the sky and reflections (default: procedural)");
}

/// XXH64 of a file's bytes as 16 hex digits; null when it cannot be read (the run fails on it later).
nlohmann::json fileHash(const std::filesystem::path& path) {
    const std::optional<uint64_t> h = pacifica::capture::hashFileBytes(path);
    return h ? nlohmann::json(tools::hex64(*h)) : nlohmann::json(nullptr);
}

/// ReplayOptions::runKey: the command line's key (replayRunKey) with what the command line does not show --
/// this program's bytes (a rebuilt pacifica renders again) and every input file's (the recording, --env,
/// --ocio-config or $OCIO, --height-map), so a chunk never keeps frames of another build or another input.
std::string runKeyWithContents(const std::string& argsKey, const tools::ReplayOptions& r,
                               const std::vector<std::string>& heightMaps) {
    nlohmann::json inputs = nlohmann::json::object();
    const auto add = [&inputs](const std::filesystem::path& p) { inputs[p.string()] = fileHash(p); };
    add(r.flight);
    if (r.environment)
        add(*r.environment);
    if (r.ocioConfig)
        add(*r.ocioConfig);
    else if (const char* env = std::getenv("OCIO"); env && *env)
        add(env);
    for (const std::string& h : heightMaps)
        add(h);
    return nlohmann::json{{"args", nlohmann::json::parse(argsKey)},
                          {"program", fileHash("/proc/self/exe")},
                          {"inputs", std::move(inputs)}}
        .dump();
}

tools::ReplayOptions ReplayCommand::options() const {
    tools::ReplayOptions r = replay;
    r.flight = flight;
    if (!views.empty()) {
        r.view = views.front();
        r.extraViews.assign(views.begin() + 1, views.end());
    }
    if (videoOpt->count())
        r.video = video;
    r.outDir = outDir;
    r.events = !noEvents;
    r.objects = !noObjects;
    tools::parseSize(size, r.width, r.height);
    if (startOpt->count())
        r.start = start;
    if (endOpt->count())
        r.end = end;
    if (ocioOpt->count())
        r.ocioConfig = ocioConfig;
    if (envOpt->count()) {
        // Replay points the sun at the map's brightest direction (docs/ARCHITECTURE.md, Shading).
        if (ocean.sunElevationDeg || ocean.sunAzimuthDeg)
            throw tools::UsageError(
                "--sun-elevation/--sun-azimuth cannot be combined with --env: the sun is the "
                "environment map's brightest direction");
        r.environment = environment;
    }
    r.writeImages = !noImages;
    r.imageCompression = imageCompression == "small" ? pacifica::capture::Compression::Small
                                                     : pacifica::capture::Compression::Fast;
    r.ocean = tools::toOceanDesc(ocean);
    r.progress = !noProgress;
    if (framesOpt->count())
        r.frames = tools::parseFrameRange(frames);
    r.runKey = r.frames || keyWithContents ? runKeyWithContents(runKey, r, ocean.heightMaps) : runKey;
    return r;
}

int ReplayCommand::run() const {
    if (listObjects) {
        const tools::ReplayOptions o = options();
        const pacifica::recording::Recording rec = pacifica::recording::readRecording(flight);
        std::fputs(tools::listObjects(rec, tools::replayEarthFrame(rec, o.rigs, flight), o.ocean).c_str(),
                   stdout);
        return 0;
    }
    tools::runReplay(options());
    return 0;
}

/// `pacifica tonemap compare`.
struct CompareCommand {
    CLI::App* app = nullptr;
    tools::TonemapCompareOptions compare;
    std::vector<std::string> configs;
    bool noGpu = false;

    void add(CLI::App& parent) {
        CLI::App* tm = parent.add_subcommand("tonemap", "HDR display-transform tools");
        tm->require_subcommand(1);
        app = tm->add_subcommand("compare",
                                 "compare every OCIO view and the shipped tonemappers on scene-linear "
                                 "frames: contact sheets, metrics.json, report.md, report.html "
                                 "(docs/TONEMAP.md)");
        app->add_option("inputs", compare.inputs, "scene-linear EXRs, replay output folders, or flight files")
            ->required();
        app->add_option("--out", compare.outDir, "output directory")->required();
        app->add_option("--ocio-config", configs, "another OCIO config to compare (repeatable)");
        app->add_option("--lut3d", compare.lut3dSize, "edge of PBR Neutral's 3D LUT")->default_val(33);
        app->add_option("--max-pixels", compare.maxPixels, "refuse larger images")->default_val(50000000);
        app->add_option("--tile-width", compare.tileWidth, "contact-sheet tile width")->default_val(360);
        app->add_option("--pair", compare.pair,
                        "the two transforms of the wipe and difference sheets, A,B (parts of their labels)")
            ->default_val(compare.pair);
        app->add_flag("--no-gpu", noGpu, "skip the GPU path (no GPU-vs-CPU differences)");
        app->add_option("--frames", compare.framesPerFolder, "frames taken from a replay folder or flight")
            ->default_val(3)
            ->check(CLI::Range(1, 100));
    }
    int run() {
        for (const std::string& c : configs)
            compare.ocioConfigs.emplace_back(c);
        compare.gpu = !noGpu;
        tools::runTonemapCompare(compare);
        return 0;
    }
};

/// `pacifica convert`.
struct ConvertCommand {
    CLI::App* app = nullptr;
    std::string input, output;

    void add(CLI::App& parent) {
        app = parent.add_subcommand("convert",
                                    "write a recording (Tacview ACMI text/zip, IGC) as Tacview ACMI 2.2 "
                                    "text, e.g. an IGC flight for Tacview");
        app->add_option("input", input, "recording to read")->required();
        app->add_option("output", output, "ACMI text file to write (.txt.acmi)")->required();
    }
    int run() const {
        const pacifica::recording::Recording rec = pacifica::recording::readRecording(input);
        // Written beside the target and renamed on success: never a half-written file.
        pacifica::writeFileAtomically(output,
                                      [&](std::ostream& out) { pacifica::recording::writeAcmi(rec, out); });
        std::fprintf(stderr, "pacifica: wrote %zu objects (%lld samples) to %s\n", rec.objects.size(),
                     rec.samples, output.c_str());
        return 0;
    }
};

/// ReplayOptions::runKey: the arguments as a JSON array, less what differs between the chunks of one run
/// and leaves the pixels alone: --frames and --cuda-device (with their values) and --no-progress.
std::string replayRunKey(const std::vector<std::string>& args) {
    std::vector<std::string> kept;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--frames" || a == "--cuda-device")
            ++i;
        else if (a.rfind("--frames=", 0) != 0 && a.rfind("--cuda-device=", 0) != 0 && a != "--no-progress")
            kept.push_back(a);
    }
    return nlohmann::json(kept).dump();
}

/// tools::ReplayParser: a replay command line (after `pacifica replay`) parsed as the CLI parses it.
tools::ReplayOptions parseReplayArgs(const std::vector<std::string>& args) {
    CLI::App app{"pacifica"};
    ReplayCommand cmd;
    cmd.add(app);
    std::vector<std::string> reversed = {"replay"};
    reversed.insert(reversed.end(), args.begin(), args.end());
    cmd.runKey = replayRunKey(reversed);
    cmd.keyWithContents = true;
    std::reverse(reversed.begin(), reversed.end()); // CLI11 takes a vector last argument first
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        throw tools::UsageError(std::string("the replay options after --: ") + e.what());
    }
    if (cmd.listObjects)
        throw tools::UsageError("the replay options after --: --list-objects renders nothing");
    return cmd.options();
}

/// `pacifica farm run|resume|status|chunk|merge` (tools/src/Farm.h); the replay's options follow `--`.
struct FarmCommand {
    CLI::App *app = nullptr, *runApp = nullptr, *resumeApp = nullptr, *statusApp = nullptr,
             *chunkApp = nullptr, *mergeApp = nullptr;
    tools::FarmOptions farm;
    std::vector<std::string> recordings;
    std::string runDir;
    long long chunkIndex = 0;
    int resubmit = 0;

    void engineOptions(CLI::App* a) {
        a->add_option("--engine", farm.engine.name, "local (a pool of processes here) or slurm (sbatch)")
            ->check(CLI::IsMember({"local", "slurm"}));
        a->add_option("--workers", farm.engine.workers, "local: chunks at once")->check(CLI::Range(1, 256));
        a->add_option("--gpus", farm.engine.gpus, "local: worker slot s renders on GPU s % N (CUDA index)")
            ->check(CLI::Range(0, 64));
        a->add_option("--retries", farm.engine.retries, "times a failing chunk is run again")
            ->check(CLI::Range(0, 100));
        a->add_option("--throttle", farm.engine.throttle, "slurm: array tasks at once (0: no limit)")
            ->check(CLI::Range(0, 100000));
        a->add_option("--gpus-per-chunk", farm.engine.gpusPerChunk, "slurm: --gres=gpu:N per chunk")
            ->check(CLI::Range(0, 16));
        a->add_option("--partition", farm.engine.partition, "slurm: the partition");
        a->add_flag("--wait", farm.engine.wait, "slurm: wait for the merge's report.json");
    }
    void add(CLI::App& parent) {
        app = parent.add_subcommand("farm",
                                    "a replay sharded into chunks on Slurm or a local pool: one summary "
                                    "per recording, resumable (docs/SCALE.md)");
        app->require_subcommand(1);
        runApp =
            app->add_subcommand("run", "plan and run: RECORDING... --out RUN [options] -- REPLAY OPTIONS");
        runApp->add_option("recordings", recordings, "recordings (ACMI, IGC, flight CSV)")->required();
        runApp->add_option("--out", runDir, "the run's folder (plan.json, a folder per recording)")
            ->required();
        runApp->add_option("--chunk-frames", farm.chunkFrames, "frames per chunk")->default_val(100);
        runApp->add_flag("--dry-run", farm.dryRun, "print the plan and the chunks' commands, write nothing");
        runApp
            ->add_option(
                "--video", farm.video,
                "mp4 (H.264) or mov (ProRes): a video per view of each recording, RUN/NAME/VIEW.EXT, "
                "encoded once from the chunks' PNGs after the merge")
            ->check(CLI::IsMember({"mp4", "mov"}));
        engineOptions(runApp);
        resumeApp = app->add_subcommand("resume", "run the chunks of RUN that are not done, then merge");
        resumeApp->add_option("run", runDir, "the run's folder")->required();
        engineOptions(resumeApp);
        statusApp = app->add_subcommand("status", "chunks and frames done, and failures, of RUN");
        statusApp->add_option("run", runDir, "the run's folder")->required();
        chunkApp = app->add_subcommand("chunk", "run chunk I of RUN (what each engine's task runs)");
        chunkApp->add_option("run", runDir, "the run's folder")->required();
        chunkApp->add_option("index", chunkIndex, "the chunk")->required();
        mergeApp = app->add_subcommand("merge", "merge RUN's chunks (Slurm: resubmit unfinished ones first)");
        mergeApp->add_option("run", runDir, "the run's folder")->required();
        mergeApp->add_option("--resubmit", resubmit, "rounds of resubmission left")->default_val(0);
    }
    int run(const std::vector<std::string>& replayArgs) {
        if (runApp->parsed()) {
            farm.recordings.assign(recordings.begin(), recordings.end());
            farm.runDir = runDir;
            farm.replayArgs = replayArgs;
            farm.exe = std::filesystem::read_symlink("/proc/self/exe");
            return tools::farmRun(farm, parseReplayArgs);
        }
        if (!replayArgs.empty())
            throw tools::UsageError("farm: only `farm run` takes replay options after --");
        if (resumeApp->parsed())
            return tools::farmResume(runDir, [this](tools::FarmEngine& e) {
                for (const char* name : {"--engine", "--workers", "--gpus", "--retries", "--throttle",
                                         "--gpus-per-chunk", "--partition", "--wait"})
                    if (resumeApp->get_option(name)->count() == 0)
                        continue;
                    else if (std::string(name) == "--engine")
                        e.name = farm.engine.name;
                    else if (std::string(name) == "--workers")
                        e.workers = farm.engine.workers;
                    else if (std::string(name) == "--gpus")
                        e.gpus = farm.engine.gpus;
                    else if (std::string(name) == "--retries")
                        e.retries = farm.engine.retries;
                    else if (std::string(name) == "--throttle")
                        e.throttle = farm.engine.throttle;
                    else if (std::string(name) == "--gpus-per-chunk")
                        e.gpusPerChunk = farm.engine.gpusPerChunk;
                    else if (std::string(name) == "--partition")
                        e.partition = farm.engine.partition;
                    else
                        e.wait = farm.engine.wait;
            });
        if (statusApp->parsed())
            return tools::farmStatus(runDir);
        if (chunkApp->parsed())
            return tools::farmChunk(runDir, chunkIndex);
        return tools::farmMerge(runDir, resubmit);
    }
};

} // namespace

int main(int argc, char** argv) {
    std::signal(SIGPIPE, SIG_IGN); // a dying ffmpeg (--video) must give an error, not kill the process
    CLI::App app{"pacifica: Pacifica ocean tools (replay flights into headless EGL captures)"};
    app.require_subcommand(1);
    ReplayCommand replay;
    replay.add(app);
    CompareCommand compare;
    compare.add(app);
    ConvertCommand convert;
    convert.add(app);
    FarmCommand farm;
    farm.add(app);
    // `farm run ... -- REPLAY OPTIONS`: what follows -- is the replay's, not the farm's.
    std::vector<std::string> args(argv + 1, argv + argc), replayArgs;
    if (!args.empty() && args[0] == "farm")
        if (auto dash = std::find(args.begin(), args.end(), "--"); dash != args.end()) {
            replayArgs.assign(dash + 1, args.end());
            args.erase(dash, args.end());
        }
    try {
        std::vector<std::string> reversed(args.rbegin(), args.rend());
        app.parse(reversed);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // Same contract as every other bad input: one "pacifica: error:" line, exit status 2.
        std::fprintf(stderr, "pacifica: error: %s\nRun with --help for usage.\n", e.what());
        return 2;
    }
    replay.runKey = replayRunKey(args);
    try {
        if (farm.app->parsed())
            return farm.run(replayArgs);
        if (convert.app->parsed())
            return convert.run();
        if (compare.app->parsed())
            return compare.run();
        if (replay.app->parsed())
            return replay.run();
    } catch (const tools::UsageError& e) {
        std::fprintf(stderr, "pacifica: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
