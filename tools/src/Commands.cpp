// Commands: the `pacifica` command line, parsed apart from running anything (Commands.h).
#include "Commands.h"

#include "ChunkFrames.h"
#include "OutputTransaction.h"
#include "engine/capture/Capture.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <ostream>

namespace pacifica::tools {

namespace {

/// `text` as JSON: the string itself when it is UTF-8, else {"hex": its bytes} -- a Linux argument or file
/// name may be any bytes, and nlohmann::json refuses to write a string that is not UTF-8.
nlohmann::json argumentJson(const std::string& text) {
    if (isUtf8(text))
        return text;
    static const char* digits = "0123456789abcdef";
    std::string hex;
    for (const unsigned char c : text)
        hex += {digits[c >> 4], digits[c & 15]};
    return {{"hex", hex}};
}

/// XXH64 of a file's bytes as 16 hex digits; null when it cannot be read (the run fails on it later).
nlohmann::json fileHash(const FileHasher& hash, const std::filesystem::path& path) {
    const std::optional<uint64_t> h = hash ? hash(path) : capture::hashFileBytes(path);
    return h ? nlohmann::json(hex64(*h)) : nlohmann::json(nullptr);
}

/// ReplayOptions::runKey: the command line's key (replayRunKey) with what the command line does not show --
/// this program's bytes (a rebuilt pacifica renders again) and every input file's (the recording, --env,
/// --ocio-config or $OCIO, --height-map), so a chunk never keeps frames of another build or another input.
std::string runKeyWithContents(const std::string& argsKey, const ReplayOptions& r,
                               const std::vector<std::string>& heightMaps, const FileHasher& hash) {
    nlohmann::json inputs = nlohmann::json::object();
    const auto add = [&](const std::filesystem::path& p) {
        const nlohmann::json name = argumentJson(p.string());
        inputs[name.is_string() ? name.get<std::string>() : "hex:" + name["hex"].get<std::string>()] =
            fileHash(hash, p);
    };
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
                          {"program", fileHash(hash, "/proc/self/exe")},
                          {"inputs", std::move(inputs)}}
        .dump();
}

} // namespace

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
        ->check(CLI::Validator(
            [](std::string& v) {
                // Decimal only, as the callback reads it (CLI::Range would also take "017" or "0x1").
                const bool number = !v.empty() && v.size() <= 2 &&
                                    v.find_first_not_of("0123456789") == std::string::npos &&
                                    std::stoi(v) <= 15;
                return v == "auto" || number ? std::string()
                                             : "expects auto or a device 0..15, got '" + v + "'";
            },
            "N|auto"));
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
    app->add_option("--exposure", replay.exposureEv,
                    "exposure, stops: every light x 2^EV, so the frame and the EXR hold radiance x 2^EV "
                    "(default 0; a moonlit night wants ~17)")
        ->check(CLI::Range(-40.0, 40.0));
    app->add_option("--light", replay.lights,
                    "spot light spot:SHIP[,key=value...] on a recorded ship (its id in --list-objects) or "
                    "spot:fixed,x=M,y=M[,...]; keys height, azimuth (from the heading), elevation, angle, "
                    "intensity, range, color=R:G:B (docs/ARCHITECTURE.md, Spot lights); repeat for several")
        ->expected(1)
        ->take_all();
    addOutputOptions();
    addOceanOptions(*app, ocean);
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

ReplayOptions ReplayCommand::options() const {
    ReplayOptions r = replay;
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
    parseSize(size, r.width, r.height);
    if (startOpt->count())
        r.start = start;
    if (endOpt->count())
        r.end = end;
    if (ocioOpt->count())
        r.ocioConfig = ocioConfig;
    if (envOpt->count()) {
        // Replay points the sun at the map's brightest direction (docs/ARCHITECTURE.md, Shading).
        if (ocean.sunElevationDeg || ocean.sunAzimuthDeg || ocean.moonElevationDeg)
            throw UsageError(
                "--sun-elevation/--sun-azimuth/--moon-elevation cannot be combined with --env: the "
                "sun is the environment map's brightest direction");
        r.environment = environment;
    }
    r.writeImages = !noImages;
    r.imageCompression = imageCompression == "small" ? pacifica::capture::Compression::Small
                                                     : pacifica::capture::Compression::Fast;
    r.ocean = toOceanDesc(ocean);
    r.progress = !noProgress;
    if (framesOpt->count())
        r.frames = parseFrameRange(frames);
    r.runKey =
        r.frames || keyWithContents ? runKeyWithContents(runKey, r, ocean.heightMaps, hashFile) : runKey;
    return r;
}

/// ReplayOptions::runKey: the arguments as a JSON array, less what differs between the chunks of one run
/// and leaves the pixels alone: --frames and --cuda-device (with their values) and --no-progress.
std::string replayRunKey(const std::vector<std::string>& args) {
    nlohmann::json kept = nlohmann::json::array();
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "--frames" || a == "--cuda-device")
            ++i;
        else if (a.rfind("--frames=", 0) != 0 && a.rfind("--cuda-device=", 0) != 0 && a != "--no-progress")
            kept.push_back(argumentJson(a));
    }
    return kept.dump();
}

ReplayOptions parseReplayArgs(const std::vector<std::string>& args, const FileHasher& hashFile) {
    CLI::App app{"pacifica"};
    ReplayCommand cmd;
    cmd.add(app);
    std::vector<std::string> reversed = {"replay"};
    reversed.insert(reversed.end(), args.begin(), args.end());
    cmd.runKey = replayRunKey(reversed);
    cmd.keyWithContents = true;
    cmd.hashFile = hashFile;
    std::reverse(reversed.begin(), reversed.end()); // CLI11 takes a vector last argument first
    try {
        app.parse(reversed);
    } catch (const CLI::ParseError& e) {
        throw UsageError(std::string("the replay options after --: ") + e.what());
    }
    if (cmd.listObjects)
        throw UsageError("the replay options after --: --list-objects renders nothing");
    return cmd.options();
}

void CompareCommand::add(CLI::App& parent) {
    CLI::App* tm = parent.add_subcommand("tonemap", "HDR display-transform tools");
    tm->require_subcommand(1);
    app = tm->add_subcommand("compare", "compare every OCIO view and the shipped tonemappers on scene-linear "
                                        "frames: contact sheets, metrics.json, report.md, report.html "
                                        "(docs/TONEMAP.md)");
    app->add_option("inputs", compare.inputs, "scene-linear EXRs, replay output folders, or flight files")
        ->required();
    app->add_option("--out", compare.outDir, "output directory")
        ->required()
        ->check(CLI::Validator(
            [](std::string& v) {
                return v.empty() ? std::string("expects a folder, got ''") : std::string();
            },
            "DIR"));
    app->add_option("--ocio-config", configs, "another OCIO config to compare (repeatable)");
    app->add_option("--lut3d", compare.lut3dSize, "edge of PBR Neutral's 3D LUT")
        ->default_val(33)
        ->check(CLI::Range(2, 129));
    app->add_option("--max-pixels", compare.maxPixels, "refuse larger images")
        ->default_val(50000000)
        ->check(CLI::Range(1LL, 1000000000LL));
    app->add_option("--tile-width", compare.tileWidth, "contact-sheet tile width")
        ->default_val(360)
        ->check(CLI::Range(64, 4096));
    app->add_option("--pair", compare.pair,
                    "the two transforms of the wipe and difference sheets, A,B (parts of their labels)")
        ->default_val(compare.pair)
        ->check(CLI::Validator(
            [](std::string& v) {
                const size_t comma = v.find(',');
                return comma != std::string::npos && comma > 0 && comma + 1 < v.size()
                           ? std::string()
                           : "expected two transforms, A,B, got '" + v + "'";
            },
            "A,B"));
    app->add_flag("--no-gpu", noGpu, "skip the GPU path (no GPU-vs-CPU differences)");
    app->add_option("--frames", compare.framesPerFolder, "frames taken from a replay folder or flight")
        ->default_val(3)
        ->check(CLI::Range(1, 100));
}

TonemapCompareOptions CompareCommand::options() const {
    TonemapCompareOptions o = compare;
    for (const std::string& c : configs)
        o.ocioConfigs.emplace_back(c);
    o.gpu = !noGpu;
    return o;
}

void ConvertCommand::add(CLI::App& parent) {
    app =
        parent.add_subcommand("convert", "write a recording (Tacview ACMI text/zip, IGC) as Tacview ACMI 2.2 "
                                         "text, e.g. an IGC flight for Tacview");
    app->add_option("input", input, "recording to read")->required();
    app->add_option("output", output, "ACMI text file to write (.txt.acmi)")->required();
}

void FarmCommand::engineOptions(CLI::App* a) {
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

void FarmCommand::add(CLI::App& parent) {
    app = parent.add_subcommand("farm", "a replay sharded into chunks on Slurm or a local pool: one summary "
                                        "per recording, resumable (docs/SCALE.md)");
    app->require_subcommand(1);
    runApp = app->add_subcommand("run", "plan and run: RECORDING... --out RUN [options] -- REPLAY OPTIONS");
    runApp->add_option("recordings", recordings, "recordings (ACMI, IGC, flight CSV)")->required();
    runApp->add_option("--out", runDir, "the run's folder (plan.json, a folder per recording)")->required();
    runApp->add_option("--chunk-frames", farm.chunkFrames, "frames per chunk")
        ->default_val(100)
        ->check(CLI::Range(1LL, 1000000000LL));
    runApp->add_flag("--dry-run", farm.dryRun, "print the plan and the chunks' commands, write nothing");
    runApp
        ->add_option("--video", farm.video,
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

void FarmCommand::adjustEngine(FarmEngine& e) const {
    const auto given = [this](const char* name) { return resumeApp->get_option(name)->count() > 0; };
    if (given("--engine"))
        e.name = farm.engine.name;
    if (given("--workers"))
        e.workers = farm.engine.workers;
    if (given("--gpus"))
        e.gpus = farm.engine.gpus;
    if (given("--retries"))
        e.retries = farm.engine.retries;
    if (given("--throttle"))
        e.throttle = farm.engine.throttle;
    if (given("--gpus-per-chunk"))
        e.gpusPerChunk = farm.engine.gpusPerChunk;
    if (given("--partition"))
        e.partition = farm.engine.partition;
    if (given("--wait"))
        e.wait = farm.engine.wait;
}

CommandLine::CommandLine() {
    app.require_subcommand(1);
    replay.add(app);
    compare.add(app);
    convert.add(app);
    farm.add(app);
}

std::optional<int> CommandLine::parse(std::vector<std::string> args, std::ostream& out, std::ostream& err) {
    // `farm run ... -- REPLAY OPTIONS`: what follows -- is the replay's, not the farm's.
    replayArgs.clear();
    if (!args.empty() && args[0] == "farm")
        if (auto dash = std::find(args.begin(), args.end(), "--"); dash != args.end()) {
            replayArgs.assign(dash + 1, args.end());
            args.erase(dash, args.end());
        }
    try {
        std::vector<std::string> reversed(args.rbegin(), args.rend());
        app.parse(reversed);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e, out, err);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e, out, err);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e, out, err);
    } catch (const CLI::ParseError& e) {
        // Same contract as every other bad input: one "pacifica: error:" line, exit status 2.
        err << "pacifica: error: " << e.what() << "\nRun with --help for usage.\n";
        return 2;
    }
    replay.runKey = replayRunKey(args);
    return std::nullopt;
}

} // namespace pacifica::tools
