// libFuzzer target: the `pacifica` command line (tools/src/Commands.h) -- replay, tonemap compare, convert
// and farm, with farm run's replay options after `--`. The input is split at newlines into the arguments
// after "pacifica". Every argument list must end in help (0), a usage error (2) or options that the run's
// own checks accept and that lie within every documented range; a replay's ocean must be one the renderer
// accepts (its lighting and grid). Any other exception, or an out-of-range value that parses, is a finding
// (abort). Files are not read: --height-map lists are left to fuzz_image (the readers behind them), and the
// run key's file hashes are replaced by the path's length (the key's shape is what is parsed here). A wind
// that passes --sea-state's or --beaufort's range check is not applied: applySeaState builds the surface to
// fit foam and slopes (0.2-0.7 s in a Release build, seconds under ASan), which tests/unit/test_sea_state.cpp
// covers; the fuzzer stops there, after the range checks.
#include "Commands.h"
#include "FuzzArguments.h"

#include <ocean/Lighting.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

void require(bool ok, const char* what) {
    if (!ok) {
        std::fprintf(stderr, "pacifica options: parsed but out of range: %s\n", what);
        std::abort();
    }
}

std::optional<uint64_t> pathLength(const std::filesystem::path& p) {
    return p.string().size();
}

void checkReplay(const pacifica::tools::ReplayOptions& r) {
    using namespace pacifica;
    try {
        tools::checkReplayOptions(r);
    } catch (const tools::UsageError&) {
        return;
    }
    require(r.width >= 16 && r.width <= 8192 && r.height >= 16 && r.height <= 8192, "--size");
    require(std::isfinite(r.fps) && r.fps > 0.0 && r.fps <= 1000.0, "--fps");
    require(std::isfinite(r.speed) && r.speed > 0.0 && r.speed <= 1e6, "--speed");
    require(std::isfinite(r.fovYDeg) && r.fovYDeg >= 1.0f && r.fovYDeg <= 170.0f, "--fov");
    require(r.maxFrames >= 1, "--max-frames");
    require(r.eglDevice >= -1 && r.eglDevice <= 15, "--egl-device");
    require(!r.frames || (r.frames->first >= 0 && r.frames->first <= r.frames->last), "--frames");
    require(!r.runKey.empty(), "the run key");
    // What the renderer checks first (ocean/src/OceanRenderer.cpp buildOcean): a throw here is a finding.
    ocean::validateLighting(r.ocean.lighting);
}

/// The ocean options this fuzzer turns into a description (above: no files, no sea-state fit).
bool cheapOcean(const pacifica::tools::OceanOptions& o) {
    const bool windFit =
        (o.seaState && std::isfinite(*o.seaState) && *o.seaState >= 1.0 && *o.seaState <= 30.0) ||
        (o.beaufort && *o.beaufort >= 1 && *o.beaufort <= 11);
    return o.heightMaps.empty() && !(windFit && !(o.seaState && o.beaufort));
}

void checkCompare(const pacifica::tools::TonemapCompareOptions& o) {
    require(!o.inputs.empty() && !o.outDir.empty(), "inputs and --out");
    require(o.lut3dSize >= 2 && o.lut3dSize <= 129, "--lut3d");
    require(o.tileWidth >= 64 && o.tileWidth <= 4096, "--tile-width");
    require(o.maxPixels >= 1, "--max-pixels");
    require(o.framesPerFolder >= 1 && o.framesPerFolder <= 100, "--frames");
    const size_t comma = o.pair.find(',');
    require(comma != std::string::npos && comma > 0 && comma + 1 < o.pair.size(), "--pair");
}

void checkFarm(const pacifica::tools::CommandLine& cli) {
    using namespace pacifica;
    const tools::FarmCommand& f = cli.farm;
    require(f.farm.chunkFrames >= 1, "--chunk-frames");
    require(f.farm.engine.workers >= 1 && f.farm.engine.workers <= 256, "--workers");
    require(f.farm.engine.retries >= 0 && f.farm.engine.retries <= 100, "--retries");
    require(f.farm.engine.name == "local" || f.farm.engine.name == "slurm", "--engine");
    if (!f.runApp->parsed() || cli.replayArgs.empty())
        return;
    // What farm run does with the replay's options per recording (Farm.cpp makePlan): FLIGHT OPTIONS --out
    // DIR, parsed as the CLI parses them -- when farm run lets them through (no --out, --frames or --video of
    // their own) and they ask for nothing costly (cheapOcean).
    for (const std::string& a : cli.replayArgs)
        for (const char* own : {"--out", "--frames", "--video"})
            if (a.rfind(own, 0) == 0)
                return;
    std::vector<std::string> args = {"flight"};
    args.insert(args.end(), cli.replayArgs.begin(), cli.replayArgs.end());
    args.insert(args.end(), {"--out", "out"});
    tools::CommandLine replay;
    std::vector<std::string> asCommand = {"replay"};
    asCommand.insert(asCommand.end(), args.begin(), args.end());
    std::ostringstream out, err;
    if (replay.parse(asCommand, out, err) || !cheapOcean(replay.replay.ocean))
        return;
    checkReplay(tools::parseReplayArgs(args, pathLength));
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pacifica;
    const std::vector<std::string> args = fuzz::splitArguments(data, size);
    try {
        tools::CommandLine cli;
        std::ostringstream out, err;
        if (const std::optional<int> status = cli.parse(args, out, err)) {
            require(*status == 0 || *status == 2, "the exit status of help or a usage error");
            return 0;
        }
        if (cli.replay.app->parsed() && cheapOcean(cli.replay.ocean)) {
            cli.replay.hashFile = pathLength;
            checkReplay(cli.replay.options());
        } else if (cli.compare.app->parsed()) {
            checkCompare(cli.compare.options());
        } else if (cli.farm.app->parsed()) {
            checkFarm(cli);
        }
    } catch (const tools::UsageError&) {
    }
    return 0;
}
