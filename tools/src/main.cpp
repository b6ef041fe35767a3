// pacifica: the command-line tool. Its subcommands and their options are in Commands.h; this file runs the
// one that was parsed. Any failure prints "pacifica: error: ..." naming the file/line/option and exits
// non-zero (2 for bad usage), leaving no partial output behind.
#include "Commands.h"
#include "Farm.h"
#include "Replay.h"
#include "ReplayInput.h"
#include "TonemapCompare.h"
#include "engine/AtomicFile.h"

#include <recording/AcmiWriter.h>
#include <recording/Recording.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

namespace tools = pacifica::tools;

int runReplayCommand(const tools::ReplayCommand& cmd) {
    if (cmd.listObjects) {
        const tools::ReplayOptions o = cmd.options();
        const pacifica::recording::Recording rec = pacifica::recording::readRecording(cmd.flight);
        std::fputs(tools::listObjects(rec, tools::replayEarthFrame(rec, o.rigs, cmd.flight), o.ocean).c_str(),
                   stdout);
        return 0;
    }
    tools::runReplay(cmd.options());
    return 0;
}

int runConvertCommand(const tools::ConvertCommand& cmd) {
    const pacifica::recording::Recording rec = pacifica::recording::readRecording(cmd.input);
    // Written beside the target and renamed on success: never a half-written file.
    pacifica::writeFileAtomically(cmd.output,
                                  [&](std::ostream& out) { pacifica::recording::writeAcmi(rec, out); });
    std::fprintf(stderr, "pacifica: wrote %zu objects (%lld samples) to %s\n", rec.objects.size(),
                 rec.samples, cmd.output.c_str());
    return 0;
}

int runFarmCommand(const tools::FarmCommand& cmd, const std::vector<std::string>& replayArgs) {
    if (cmd.runApp->parsed()) {
        tools::FarmOptions farm = cmd.farm;
        farm.recordings.assign(cmd.recordings.begin(), cmd.recordings.end());
        farm.runDir = cmd.runDir;
        farm.replayArgs = replayArgs;
        farm.exe = std::filesystem::read_symlink("/proc/self/exe");
        return tools::farmRun(
            farm, [](const std::vector<std::string>& args) { return tools::parseReplayArgs(args); });
    }
    if (!replayArgs.empty())
        throw tools::UsageError("farm: only `farm run` takes replay options after --");
    if (cmd.resumeApp->parsed())
        return tools::farmResume(cmd.runDir, [&cmd](tools::FarmEngine& e) { cmd.adjustEngine(e); });
    if (cmd.statusApp->parsed())
        return tools::farmStatus(cmd.runDir);
    if (cmd.chunkApp->parsed())
        return tools::farmChunk(cmd.runDir, cmd.chunkIndex);
    return tools::farmMerge(cmd.runDir, cmd.resubmit);
}

} // namespace

int main(int argc, char** argv) {
    std::signal(SIGPIPE, SIG_IGN); // a dying ffmpeg (--video) must give an error, not kill the process
    tools::CommandLine cli;
    if (const std::optional<int> status = cli.parse({argv + 1, argv + argc}, std::cout, std::cerr))
        return *status;
    try {
        if (cli.farm.app->parsed())
            return runFarmCommand(cli.farm, cli.replayArgs);
        if (cli.convert.app->parsed())
            return runConvertCommand(cli.convert);
        if (cli.compare.app->parsed()) {
            tools::runTonemapCompare(cli.compare.options());
            return 0;
        }
        if (cli.replay.app->parsed())
            return runReplayCommand(cli.replay);
    } catch (const tools::UsageError& e) {
        std::fprintf(stderr, "pacifica: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
