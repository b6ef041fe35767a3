// OutputTransaction: a replay's output folder as a transaction. Frames are written into a hidden staging
// folder inside DIR and moved into DIR only when the whole run succeeded (summary.json last, atomically), so
// a failed run leaves DIR exactly as it was (files of an earlier run included) and a folder it had to create
// is removed again.
//
// A run killed outright (kill -9, power loss) cannot clean up: its staging folder stays behind with the
// frames it had written, DIR itself holds only whole files of earlier commits. Each staging folder has a lock
// file beside it (DIR/.pacifica-staging-HOST-PID.lock, flock held for the run's life, released by the kernel
// when the process dies), and the next run into DIR on the same host removes every staging folder of that
// host whose lock is free (another host's lock may not show here on a network file system).
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace pacifica::tools {

/// A run's report (summary.json, a chunk's summary, the farm's merged summaries and report.json) as text:
/// indented by 2, with a final newline. A string that is not UTF-8 -- a flight or folder whose Linux name is
/// bytes of another encoding -- is written with U+FFFD for its bad bytes, where nlohmann::json would throw
/// and fail the run after its last frame.
std::string reportText(const nlohmann::json& report);
/// Whether JSON can hold `text` as it is: UTF-8 as nlohmann::json checks it when writing (a Linux argument or
/// file name may be any bytes). Inline: the command line's parser (Commands.cpp) links without this header's
/// .cpp in its fuzzer.
inline bool isUtf8(const std::string& text) {
    try {
        (void)nlohmann::json(text).dump();
        return true;
    } catch (const nlohmann::json::type_error&) {
        return false;
    }
}

class OutputTransaction {
public:
    /// Creates DIR if missing, removes the staging folders of runs into DIR that died, and makes this run's.
    /// Throws UsageError naming DIR when it cannot be written (checkWritable). `shared`: DIR is shared with
    /// other processes writing into it at the same time (the chunks of a sharded run, --frames): it is never
    /// removed, not even when this process created it and fails before anything landed.
    explicit OutputTransaction(std::filesystem::path dir, bool shared = false);
    ~OutputTransaction();
    OutputTransaction(const OutputTransaction&) = delete;
    OutputTransaction& operator=(const OutputTransaction&) = delete;

    /// Where to write a file that will appear as DIR/name on commit.
    std::filesystem::path staged(const std::string& name);
    /// Moves every staged file into DIR, then writes summary.json (atomically) last. Files of an earlier run
    /// that get replaced are kept aside until the end, so a failure part-way puts DIR back as it was.
    void commit(const nlohmann::json& summary);
    /// A chunk of a sharded run (--frames) shares DIR with other chunks and lands frame by frame: publish()
    /// moves these staged files into DIR now, each by one rename (replacing any there).
    void publish(const std::vector<std::string>& names);
    /// Writes `text` into the staging folder, then renames it to DIR/name: a frame's sidecar or a chunk's
    /// summary appears whole or not at all, and a process killed while writing it leaves its temporary in
    /// its own staging folder (removed by the next run), never in DIR.
    void land(const std::string& name, const std::string& text);
    /// Staging folders of dead runs removed when this one started (for the log).
    int staleRemoved() const { return mStaleRemoved; }

    /// Throws UsageError "--out: ..." naming the folder when DIR, or the nearest folder above it that exists
    /// (where DIR would be created), is not a folder, is on a read-only file system or is not writable by
    /// this process: the replay calls it before it makes a GL context or renders anything.
    static void checkWritable(const std::filesystem::path& dir);

private:
    void removeStaleStaging();

    std::filesystem::path mDir, mStaging, mLock, mCreatedRoot;
    std::vector<std::string> mNames;
    int mLockFd = -1;
    int mStaleRemoved = 0;
    bool mCommitted = false;
};

} // namespace pacifica::tools
