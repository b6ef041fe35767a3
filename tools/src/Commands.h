// Commands: the `pacifica` command line (CLI11) -- every subcommand's options and their translation into the
// options structs the work functions take (ReplayOptions, TonemapCompareOptions, FarmOptions) -- apart from
// running anything, so that main() only dispatches and the option fuzzer (tests/fuzz) parses exactly what
// the program parses. Subcommands:
//   replay FLIGHT --out DIR [--fps N] [--size WxH] [--start S --end S] [--display D --view V]
//          [--ocio-config FILE] [--no-images] [--env FILE] [--frames I-J] [ocean options: OceanOptions.h]
//   tonemap compare INPUT... --out DIR [--ocio-config FILE]... [--lut3d N] [--max-pixels N]
//   convert RECORDING OUT.txt.acmi
//   farm run RECORDING... --out RUN [--chunk-frames N] [--engine local|slurm] ... -- REPLAY OPTIONS
//   farm resume|status RUN; farm chunk RUN I; farm merge RUN (what the engines' tasks run)
#pragma once

#include "Farm.h"
#include "OceanOptions.h"
#include "Replay.h"
#include "TonemapCompare.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace pacifica::tools {

/// How the run key reads an input's bytes: XXH64 of the file, nullopt when it cannot be read
/// (capture::hashFileBytes). The option fuzzer passes one that reads nothing.
using FileHasher = std::function<std::optional<uint64_t>(const std::filesystem::path&)>;

/// `pacifica replay`: its options as typed, then ReplayOptions (Replay.h) from them.
struct ReplayCommand {
    CLI::App* app = nullptr;
    ReplayOptions replay;
    std::string flight, outDir, size = "640x360", ocioConfig, start, end, video, environment, frames;
    std::string runKey; ///< the command line less --frames, --cuda-device and --no-progress (replayRunKey)
    /// The run key with the program's and the inputs' hashes (runKeyWithContents) even without --frames:
    /// the farm's plan, which must name what its chunks will. A plain run does not read them for nothing.
    bool keyWithContents = false;
    FileHasher hashFile; ///< empty: capture::hashFileBytes
    std::string imageCompression = "fast";
    std::vector<std::string> views;
    bool noImages = false, noProgress = false, listObjects = false, noEvents = false, noObjects = false;
    CLI::Option *videoOpt = nullptr, *startOpt = nullptr, *endOpt = nullptr, *ocioOpt = nullptr,
                *envOpt = nullptr, *framesOpt = nullptr;
    OceanOptions ocean;

    void add(CLI::App& parent);
    /// The options the run takes; reads the --height-map files. Throws UsageError naming the option.
    ReplayOptions options() const;

private:
    void addOutputOptions();
};

/// `pacifica tonemap compare`: every bound is checked while parsing (CLI11 validators), so a bad value is a
/// usage error (exit 2) before anything is read.
struct CompareCommand {
    CLI::App* app = nullptr;
    TonemapCompareOptions compare;
    std::vector<std::string> configs;
    bool noGpu = false;

    void add(CLI::App& parent);
    TonemapCompareOptions options() const;
};

/// `pacifica convert`.
struct ConvertCommand {
    CLI::App* app = nullptr;
    std::string input, output;

    void add(CLI::App& parent);
};

/// `pacifica farm run|resume|status|chunk|merge` (Farm.h); the replay's options follow `--`.
struct FarmCommand {
    CLI::App *app = nullptr, *runApp = nullptr, *resumeApp = nullptr, *statusApp = nullptr,
             *chunkApp = nullptr, *mergeApp = nullptr;
    FarmOptions farm;
    std::vector<std::string> recordings;
    std::string runDir;
    long long chunkIndex = 0;
    int resubmit = 0;

    void add(CLI::App& parent);
    /// `farm resume`: the plan's engine with the options given to resume put over it.
    void adjustEngine(FarmEngine& e) const;

private:
    void engineOptions(CLI::App* a);
};

/// ReplayOptions::runKey: the arguments as a JSON array, less what differs between the chunks of one run
/// and leaves the pixels alone: --frames and --cuda-device (with their values) and --no-progress.
std::string replayRunKey(const std::vector<std::string>& args);

/// A replay command line (after `pacifica replay`, e.g. farm run's after --) parsed as the CLI parses it,
/// with the run key of its contents. Throws UsageError naming the option.
ReplayOptions parseReplayArgs(const std::vector<std::string>& args, const FileHasher& hashFile = {});

/// The whole command line. Holds the CLI11 app the commands' options point into: not copyable or movable.
struct CommandLine {
    CLI::App app{"pacifica: Pacifica ocean tools (replay flights into headless EGL captures)"};
    ReplayCommand replay;
    CompareCommand compare;
    ConvertCommand convert;
    FarmCommand farm;
    std::vector<std::string> replayArgs; ///< `farm run ... -- REPLAY OPTIONS`: what follows --

    CommandLine();
    CommandLine(const CommandLine&) = delete;
    CommandLine& operator=(const CommandLine&) = delete;

    /// Parses the arguments after the program's name. On --help prints the help to `out` and returns 0; on
    /// a bad argument prints "pacifica: error: ..." to `err` and returns 2; std::nullopt when a command runs.
    std::optional<int> parse(std::vector<std::string> args, std::ostream& out, std::ostream& err);
};

} // namespace pacifica::tools
