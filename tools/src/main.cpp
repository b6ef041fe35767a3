// pacifica: the command-line tool. Subcommands:
//   replay FLIGHT --out DIR [--fps N] [--size WxH] [--start S --end S] [--display D --view V]
//          [--ocio-config FILE] [--no-images] [--env FILE] [ocean options: tools/src/OceanOptions.h]
//   tonemap compare INPUT... --out DIR [--ocio-config FILE]... [--lut3d N] [--max-pixels N]
//   convert RECORDING OUT.txt.acmi
// Any failure prints "pacifica: error: ..." naming the file/line/option and exits non-zero, leaving no
// partial output behind.
#include "OceanOptions.h"
#include "Replay.h"
#include "ReplayInput.h"
#include "TonemapCompare.h"
#include "engine/AtomicFile.h"

#include <recording/AcmiWriter.h>
#include <recording/Recording.h>

#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <exception>
#include <string>

int main(int argc, char** argv) {
    std::signal(SIGPIPE, SIG_IGN); // a dying ffmpeg (--video) must give an error, not kill the process
    CLI::App app{"pacifica: Pacifica ocean tools (replay flights into headless EGL captures)"};
    app.require_subcommand(1);

    pacifica::tools::ReplayOptions replay;
    std::string flight, outDir, size = "640x360", ocioConfig, start, end, video;
    bool noImages = false, noProgress = false;
    CLI::App* rp = app.add_subcommand(
        "replay", "render a flight (Tacview ACMI text/zip, IGC, or the CSV of docs/FLIGHT_FORMAT.md) "
                  "to EXR + PNG frames");
    rp->add_option("flight", flight, "flight file: Tacview ACMI (text or zip), IGC, or flight CSV")
        ->required();
    rp->add_option("--out", outDir, "output directory (created if missing)");
    bool listObjects = false;
    rp->add_flag("--list-objects", listObjects,
                 "print the recording's objects (id, type, name, pilot, time span, altitudes) and exit");
    rp->add_option(
          "--rig", replay.rigs,
          "camera rig KIND:OBJECT[,key=value...] (cockpit, chase, orbit, fixed, lookat; size=WxH, fov=DEG, "
          "name=N); repeat for several views; CSV flights: path")
        ->expected(1)
        ->take_all();
    CLI::Option* videoOpt = rp->add_option("--video", video,
                                           "also encode the first view as FILE.mp4 (H.264) or .mov "
                                           "(ProRes) with ffmpeg");
    rp->add_option("--speed", replay.speed, "recording seconds per video second (time-lapse)")
        ->default_val(1.0);
    rp->add_option("--max-frames", replay.maxFrames, "refuse runs with more frames than this")
        ->default_val(100000);
    rp->add_option("--fps", replay.fps, "frames per simulated second")->default_val(10.0);
    rp->add_option("--size", size, "frame size WxH")->default_val("640x360");
    CLI::Option* startOpt = rp->add_option(
        "--start", start, "first frame time: seconds or UTC YYYY-MM-DDTHH:MM:SSZ (default: flight start)");
    CLI::Option* endOpt =
        rp->add_option("--end", end, "last frame time: seconds or UTC timestamp (default: flight end)");
    rp->add_option("--display", replay.display, "OCIO display (default: the config's default)");
    std::vector<std::string> replayViews;
    rp->add_option("--view", replayViews,
                   "OCIO view (default: the display's default); repeat to tonemap the same render several "
                   "ways (frame_NNNNN.<view>.png per extra view)")
        ->expected(1)
        ->take_all();
    CLI::Option* ocioOpt = rp->add_option("--ocio-config", ocioConfig, "OCIO config file (overrides $OCIO)");
    rp->add_flag("--no-images", noImages, "render and read back but write no images (benchmarking)");
    rp->add_flag("--no-progress", noProgress, "no progress line");
    std::string imageCompression = "fast";
    rp->add_option("--image-compression", imageCompression,
                   "zlib level of the lossless EXR (ZIP) and PNG files: fast (1; ~2x faster to encode, "
                   "1.1-1.3x the bytes) or small (6)")
        ->check(CLI::IsMember({"fast", "small"}))
        ->default_val("fast");
    rp->add_flag("--profile", replay.profile,
                 "time every pass (sky, sea, effects, objects, tonemap, readback, encode) into summary.json");
    bool noEvents = false, noObjects = false;
    rp->add_flag("--no-objects", noObjects, "do not draw the recording's aircraft, ships and weapons");
    rp->add_flag("--no-events", noEvents,
                 "ignore the flight file's explosions and ships (the plain ocean, for comparisons)");
    rp->add_option("--fov", replay.fovYDeg, "vertical field of view, degrees")->default_val(60.0f);
    std::string environment;
    CLI::Option* envOpt =
        rp->add_option("--env", environment,
                       "HDR lat-long environment EXR for the sky and reflections (default: procedural)");
    pacifica::tools::OceanOptions oceanOptions;
    pacifica::tools::addOceanOptions(*rp, oceanOptions);

    pacifica::tools::TonemapCompareOptions compare;
    std::vector<std::string> compareConfigs;
    CLI::App* tmApp = app.add_subcommand("tonemap", "HDR display-transform tools");
    tmApp->require_subcommand(1);
    CLI::App* cmp = tmApp->add_subcommand(
        "compare", "compare every OCIO view and the shipped tonemappers on scene-linear frames: contact "
                   "sheets, metrics.json, report.md, report.html (docs/TONEMAP.md)");
    cmp->add_option("inputs", compare.inputs, "scene-linear EXRs, replay output folders, or flight files")
        ->required();
    cmp->add_option("--out", compare.outDir, "output directory")->required();
    cmp->add_option("--ocio-config", compareConfigs, "another OCIO config to compare (repeatable)");
    cmp->add_option("--lut3d", compare.lut3dSize, "edge of PBR Neutral's 3D LUT")->default_val(33);
    cmp->add_option("--max-pixels", compare.maxPixels, "refuse larger images")->default_val(50000000);
    cmp->add_option("--tile-width", compare.tileWidth, "contact-sheet tile width")->default_val(360);
    cmp->add_option("--pair", compare.pair,
                    "the two transforms of the wipe and difference sheets, A,B (parts of their labels)")
        ->default_val(compare.pair);
    bool noGpu = false;
    cmp->add_flag("--no-gpu", noGpu, "skip the GPU path (no GPU-vs-CPU differences)");
    cmp->add_option("--frames", compare.framesPerFolder, "frames taken from a replay folder or flight")
        ->default_val(3)
        ->check(CLI::Range(1, 100));

    std::string convertIn, convertOut;
    CLI::App* cv = app.add_subcommand("convert", "write a recording (Tacview ACMI text/zip, IGC) as Tacview "
                                                 "ACMI 2.2 text, e.g. an IGC flight for Tacview");
    cv->add_option("input", convertIn, "recording to read")->required();
    cv->add_option("output", convertOut, "ACMI text file to write (.txt.acmi)")->required();

    try {
        app.parse(argc, argv);
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

    try {
        if (cv->parsed()) {
            const pacifica::recording::Recording rec = pacifica::recording::readRecording(convertIn);
            // Written beside the target and renamed on success: never a half-written file.
            pacifica::writeFileAtomically(
                convertOut, [&](std::ostream& out) { pacifica::recording::writeAcmi(rec, out); });
            std::fprintf(stderr, "pacifica: wrote %zu objects (%lld samples) to %s\n", rec.objects.size(),
                         rec.samples, convertOut.c_str());
            return 0;
        }
        if (cmp->parsed()) {
            for (const std::string& c : compareConfigs)
                compare.ocioConfigs.emplace_back(c);
            compare.gpu = !noGpu;
            pacifica::tools::runTonemapCompare(compare);
            return 0;
        }
        if (rp->parsed() && listObjects) {
            const pacifica::recording::Recording rec = pacifica::recording::readRecording(flight);
            std::fputs(pacifica::tools::listObjects(rec).c_str(), stdout);
            return 0;
        }
        if (rp->parsed()) {
            replay.flight = flight;
            if (!replayViews.empty()) {
                replay.view = replayViews.front();
                replay.extraViews.assign(replayViews.begin() + 1, replayViews.end());
            }
            if (videoOpt->count())
                replay.video = video;
            replay.outDir = outDir;
            replay.events = !noEvents;
            replay.objects = !noObjects;
            pacifica::tools::parseSize(size, replay.width, replay.height);
            if (startOpt->count())
                replay.start = start;
            if (endOpt->count())
                replay.end = end;
            if (ocioOpt->count())
                replay.ocioConfig = ocioConfig;
            if (envOpt->count()) {
                // Replay points the sun at the map's brightest direction (docs/ARCHITECTURE.md, Shading).
                if (oceanOptions.sunElevationDeg || oceanOptions.sunAzimuthDeg)
                    throw pacifica::tools::UsageError("--sun-elevation/--sun-azimuth cannot be combined with "
                                                      "--env: the sun is the environment map's brightest "
                                                      "direction");
                replay.environment = environment;
            }
            replay.writeImages = !noImages;
            replay.imageCompression = imageCompression == "small" ? pacifica::capture::Compression::Small
                                                                  : pacifica::capture::Compression::Fast;
            replay.ocean = pacifica::tools::toOceanDesc(oceanOptions);
            replay.progress = !noProgress;
            pacifica::tools::runReplay(replay);
        }
    } catch (const pacifica::tools::UsageError& e) {
        std::fprintf(stderr, "pacifica: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
