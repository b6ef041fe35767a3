// Farm: `pacifica farm`, a replay run sharded into chunks (`pacifica replay ... --frames I-J`, Replay.h) and
// run by an engine -- Slurm (a job array, a merge job depending on it) or a local pool of processes. The
// plan (recordings x frame chunks) is written to RUN/plan.json first; every chunk is the same command
// whichever engine runs it; a merge writes one summary.json per recording and RUN/report.json. docs/SCALE.md.
#pragma once

#include "Replay.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace pacifica::tools {

/// Parses a replay command line (the arguments that follow `pacifica replay`) into options, as the CLI does.
using ReplayParser = std::function<ReplayOptions(const std::vector<std::string>& args)>;

/// How a run's chunks are executed (plan.json keeps them; `farm resume` may change them).
struct FarmEngine {
    std::string name = "local"; ///< "local" (a pool of processes here) or "slurm" (sbatch)
    int workers = 1;            ///< local: chunks at once
    int gpus = 0;               ///< local: worker slot s renders on GPU s % gpus (CUDA_VISIBLE_DEVICES)
    int retries = 2;            ///< a failing chunk runs at most 1 + retries times, then the run reports it
    int throttle = 0;           ///< slurm: array tasks at once (sbatch --array=...%N); 0: Slurm decides
    int gpusPerChunk = 0;       ///< slurm: --gres=gpu:N for every chunk
    std::string partition;      ///< slurm: --partition (empty: the default)
    bool wait = false;          ///< slurm: wait until the merge has written RUN/report.json
    double waitTimeoutS = 86400.0;
};

struct FarmOptions {
    std::vector<std::filesystem::path> recordings;
    std::filesystem::path runDir;
    /// The replay's options for every recording: what follows `--` (no flight, --out or --frames).
    std::vector<std::string> replayArgs;
    long long chunkFrames = 100;
    FarmEngine engine;
    /// "mp4" or "mov": after the merge, a video per view of each whole recording, RUN/<name>/<view>.<ext>,
    /// encoded once from the PNGs the chunks wrote (VideoWriter's codecs); "" for none.
    std::string video;
    bool dryRun = false;       ///< print the plan, write nothing
    std::filesystem::path exe; ///< this program, run by every chunk
};

/// `farm run`: plans (each recording read and its frames counted; one that cannot be is quarantined with its
/// error), writes RUN/plan.json, runs the chunks on the engine and merges. Returns the exit status: 0 when
/// every recording rendered whole, 1 otherwise (RUN/report.json says what failed and why). Throws
/// UsageError for bad options (nothing written).
int farmRun(const FarmOptions& options, const ReplayParser& parseReplay);
/// `farm resume RUN`: the plan's chunks that are not done, run again (a chunk keeps its landed frames),
/// then the merge. `adjust` changes the plan's engine (the options given to resume), saved in the plan.
int farmResume(const std::filesystem::path& runDir, const std::function<void(FarmEngine&)>& adjust);
/// `farm status RUN`: chunks and frames done per recording, failures from the last merge. Returns 0.
int farmStatus(const std::filesystem::path& runDir);
/// `farm chunk RUN I`: runs chunk I's replay command in this process's place (exec). With
/// CUDA_VISIBLE_DEVICES set (Slurm's GRES, the local pool's --gpus) the replay renders on its first GPU
/// (--cuda-device visibleCudaDevice()). Returns only on failure.
int farmChunk(const std::filesystem::path& runDir, long long index);
/// `farm merge RUN`: with Slurm and `resubmitRounds` > 0, chunks that did not finish are submitted again
/// (their indices) with another merge after them; otherwise writes RUN/<recording>/summary.json for every
/// whole recording and RUN/report.json. Returns 0 when every recording is whole (or a resubmission went out).
int farmMerge(const std::filesystem::path& runDir, int resubmitRounds);

} // namespace pacifica::tools
