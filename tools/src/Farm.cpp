// Farm: a replay run sharded into chunks and run by Slurm or a local pool (Farm.h, docs/SCALE.md).
#include "Farm.h"

#include "ChunkFrames.h"
#include "OutputTransaction.h"
#include "VideoWriter.h"
#include "engine/AtomicFile.h"
#include "engine/Log.h"
#include "engine/Stats.h"
#include "engine/gl/GlContext.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <optional>
#include <spawn.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

extern char** environ;

namespace pacifica::tools {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Chunk {
    long long index = 0;
    size_t recording = 0;
    long long first = 0, last = 0;
};

struct PlannedRecording {
    fs::path path;
    std::string name; ///< folder under RUN
    long long frames = 0;
    std::string error; ///< non-empty: quarantined (it could not be read or planned)
    /// ReplayOptions::runKey of its chunks: a chunk summary naming another (a stale run's, other options)
    /// is not this run's. Empty in plans written before it was kept: not checked.
    std::string runKey;
};

struct Plan {
    fs::path runDir, exe;
    std::vector<std::string> replayArgs;
    long long chunkFrames = 0;
    FarmEngine engine;
    std::vector<PlannedRecording> recordings;
    std::vector<Chunk> chunks;
    std::string video;     ///< FarmOptions::video
    double videoFps = 0.0; ///< the replay's --fps: the video's frame rate, as a one-process --video
    fs::path out(const Chunk& c) const { return runDir / recordings[c.recording].name; }
};

std::string fiveDigits(long long v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%05lld", v);
    return buf;
}

fs::path planPath(const fs::path& runDir) {
    return runDir / "plan.json";
}

fs::path chunkLog(const Plan& p, long long index) {
    return p.runDir / "logs" / ("chunk-" + fiveDigits(index) + ".log");
}

json engineJson(const FarmEngine& e) {
    return {{"name", e.name},           {"workers", e.workers},   {"gpus", e.gpus},
            {"retries", e.retries},     {"throttle", e.throttle}, {"gpus_per_chunk", e.gpusPerChunk},
            {"partition", e.partition}, {"wait", e.wait}};
}

FarmEngine engineFrom(const json& j) {
    FarmEngine e;
    e.name = j.at("name").get<std::string>();
    e.workers = j.at("workers").get<int>();
    e.gpus = j.at("gpus").get<int>();
    e.retries = j.at("retries").get<int>();
    e.throttle = j.at("throttle").get<int>();
    e.gpusPerChunk = j.at("gpus_per_chunk").get<int>();
    e.partition = j.at("partition").get<std::string>();
    e.wait = j.at("wait").get<bool>();
    return e;
}

json planJson(const Plan& p) {
    json recs = json::array(), chunks = json::array();
    for (const PlannedRecording& r : p.recordings) {
        json j = {{"path", r.path.string()}, {"name", r.name}, {"frames", r.frames}, {"run_key", r.runKey}};
        if (!r.error.empty())
            j["quarantined"] = r.error;
        recs.push_back(std::move(j));
    }
    for (const Chunk& c : p.chunks)
        chunks.push_back(
            {{"index", c.index}, {"recording", c.recording}, {"first", c.first}, {"last", c.last}});
    return {{"version", 1},
            {"exe", p.exe.string()},
            {"replay_args", p.replayArgs},
            {"chunk_frames", p.chunkFrames},
            {"video", p.video},
            {"video_fps", p.videoFps},
            {"engine", engineJson(p.engine)},
            {"recordings", std::move(recs)},
            {"chunks", std::move(chunks)}};
}

Plan loadPlan(const fs::path& runDir) {
    std::ifstream in(planPath(runDir));
    if (!in)
        throw UsageError(planPath(runDir).string() + ": no plan (is '" + runDir.string() +
                         "' a farm run folder? `pacifica farm run` makes one)");
    try {
        const json j = json::parse(in);
        Plan p;
        p.runDir = runDir;
        p.exe = j.at("exe").get<std::string>();
        p.replayArgs = j.at("replay_args").get<std::vector<std::string>>();
        p.chunkFrames = j.at("chunk_frames").get<long long>();
        p.engine = engineFrom(j.at("engine"));
        p.video = j.value("video", std::string());
        p.videoFps = j.value("video_fps", 0.0);
        for (const json& r : j.at("recordings"))
            p.recordings.push_back({r.at("path").get<std::string>(), r.at("name").get<std::string>(),
                                    r.at("frames").get<long long>(), r.value("quarantined", std::string()),
                                    r.value("run_key", std::string())});
        for (const json& c : j.at("chunks")) {
            const Chunk ch{c.at("index").get<long long>(), c.at("recording").get<size_t>(),
                           c.at("first").get<long long>(), c.at("last").get<long long>()};
            if (ch.recording >= p.recordings.size() || ch.index != static_cast<long long>(p.chunks.size()))
                throw std::runtime_error("chunk " + std::to_string(ch.index) + " is out of order");
            p.chunks.push_back(ch);
        }
        return p;
    } catch (const std::exception& e) {
        throw UsageError(planPath(runDir).string() + ": not a valid plan: " + e.what());
    }
}

/// The replay command line of a chunk, after the program's name.
std::vector<std::string> chunkArgs(const Plan& p, const Chunk& c) {
    std::vector<std::string> a = {"replay", p.recordings[c.recording].path.string()};
    a.insert(a.end(), p.replayArgs.begin(), p.replayArgs.end());
    a.insert(a.end(), {"--out", p.out(c).string(), "--frames",
                       std::to_string(c.first) + "-" + std::to_string(c.last), "--no-progress"});
    return a;
}

/// The chunk's summary when it finished: every frame of its range rendered or kept, by this run's options.
std::optional<json> finishedChunk(const Plan& p, const Chunk& c) {
    std::ifstream in(p.out(c) / chunkSummaryName({c.first, c.last}));
    if (!in)
        return std::nullopt;
    json s = json::parse(in, nullptr, false);
    if (s.is_discarded() || !s.contains("chunk") || !s["chunk"].is_object())
        return std::nullopt;
    const json& ch = s["chunk"];
    const std::string& key = p.recordings[c.recording].runKey;
    if ((!key.empty() && ch.value("run_key", std::string()) != key) || ch.value("first", -1LL) != c.first ||
        ch.value("last", -1LL) != c.last ||
        ch.value("rendered", 0LL) + ch.value("kept", 0LL) != c.last - c.first + 1)
        return std::nullopt;
    return s;
}

std::vector<long long> unfinished(const Plan& p) {
    std::vector<long long> out;
    for (const Chunk& c : p.chunks)
        if (!finishedChunk(p, c))
            out.push_back(c.index);
    return out;
}

/// Why a chunk failed, from its log: the replay's last "pacifica: error:" line and the pool's last word on
/// the attempt ("farm: attempt N killed by signal 9").
std::string failureOf(const Plan& p, long long index) {
    std::ifstream in(chunkLog(p, index));
    std::string line, error, attempt;
    while (std::getline(in, line))
        if (line.rfind("pacifica: error:", 0) == 0)
            error = line;
        else if (line.rfind("farm: ", 0) == 0)
            attempt = line;
    if (error.empty() && attempt.empty())
        return "did not finish (no error in " + chunkLog(p, index).string() + ")";
    return error.empty() ? attempt : attempt.empty() ? error : error + " (" + attempt + ")";
}

std::string recordingName(const fs::path& path, const std::vector<PlannedRecording>& taken) {
    std::string stem = path.filename().string();
    stem = stem.substr(0, stem.find('.'));
    if (stem.empty() || stem[0] == '.' || stem == "logs" || stem == "slurm")
        stem = "recording-" + stem;
    std::string name = stem;
    for (int n = 2;; ++n) {
        bool used = false;
        for (const PlannedRecording& r : taken)
            used = used || r.name == name;
        if (!used)
            return name;
        name = stem + "-" + std::to_string(n);
    }
}

/// Reads and counts every recording; a recording that cannot be is quarantined with its error. Bad replay
/// options (the same for every recording) are a UsageError.
Plan makePlan(const FarmOptions& o, const ReplayParser& parseReplay) {
    Plan p{o.runDir, o.exe, o.replayArgs, o.chunkFrames, o.engine, {}, {}, o.video, 0.0};
    for (const fs::path& path : o.recordings) {
        PlannedRecording r{
            fs::weakly_canonical(fs::absolute(path)), recordingName(path, p.recordings), 0, {}, {}};
        std::vector<std::string> args = {r.path.string()};
        args.insert(args.end(), o.replayArgs.begin(), o.replayArgs.end());
        args.insert(args.end(), {"--out", (o.runDir / r.name).string()});
        const ReplayOptions ro = parseReplay(args); // throws on bad options: nothing is planned
        r.runKey = ro.runKey; // what its chunks' command lines give (the same recording, options and --out)
        if (!o.video.empty() && !ro.writeImages)
            throw UsageError(
                "farm run --video: the video is encoded from the chunks' PNGs, which --no-images "
                "does not write");
        p.videoFps = ro.fps;
        try {
            r.frames = replayFrameCount(ro);
        } catch (const std::exception& e) {
            r.error = e.what();
            logWarning("farm: quarantined " + path.string() + ": " + r.error);
        }
        for (long long f = 0; r.error.empty() && f < r.frames; f += o.chunkFrames)
            p.chunks.push_back({static_cast<long long>(p.chunks.size()), p.recordings.size(), f,
                                std::min(f + o.chunkFrames, r.frames) - 1});
        p.recordings.push_back(std::move(r));
    }
    return p;
}

std::string shellQuote(const std::string& s) {
    std::string q = "'";
    for (char ch : s)
        q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
}

std::string joinIndices(const std::vector<long long>& v) {
    std::string s;
    for (long long i : v)
        s += (s.empty() ? "" : ",") + std::to_string(i);
    return s;
}

// ---- the local pool ----

/// Starts `exe farm chunk RUN I` with its output appended to the chunk's log (and CUDA_VISIBLE_DEVICES set
/// to `gpu` when >= 0).
pid_t spawnChunk(const Plan& p, long long index, int attempt, int gpu) {
    const fs::path log = chunkLog(p, index);
    {
        std::ofstream head(log, std::ios::app);
        head << "== attempt " << attempt << (gpu >= 0 ? " on GPU " + std::to_string(gpu) : std::string())
             << "\n";
    }
    const std::vector<std::string> args = {p.exe.string(), "farm", "chunk", p.runDir.string(),
                                           std::to_string(index)};
    std::vector<char*> argv;
    for (const std::string& a : args)
        argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e)
        if (gpu < 0 || std::strncmp(*e, "CUDA_VISIBLE_DEVICES=", 21) != 0)
            env.emplace_back(*e);
    if (gpu >= 0)
        env.push_back("CUDA_VISIBLE_DEVICES=" + std::to_string(gpu));
    std::vector<char*> envp;
    for (std::string& e : env)
        envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, p.exe.c_str(), &fa, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0)
        throw std::runtime_error("farm: cannot start " + p.exe.string() + ": " + std::strerror(rc));
    return pid;
}

std::string exitText(int status) {
    if (WIFEXITED(status))
        return "exit " + std::to_string(WEXITSTATUS(status));
    if (WIFSIGNALED(status))
        return std::string("killed by signal ") + std::to_string(WTERMSIG(status)) + " (" +
               strsignal(WTERMSIG(status)) + ")";
    return "ended (status " + std::to_string(status) + ")";
}

/// Runs the chunks `indices` in a pool of engine.workers processes; a chunk that fails (non-zero exit, a
/// signal, or an unfinished summary) runs again until it has run 1 + retries times.
void runLocal(const Plan& p, const std::vector<long long>& indices) {
    std::deque<long long> queue(indices.begin(), indices.end());
    std::map<pid_t, std::pair<long long, int>> running; // pid -> (chunk, worker slot)
    std::map<long long, int> attempts;
    std::vector<bool> slotBusy(static_cast<size_t>(std::max(1, p.engine.workers)), false);
    size_t done = 0;
    while (!queue.empty() || !running.empty()) {
        for (size_t s = 0; s < slotBusy.size() && !queue.empty(); ++s) {
            if (slotBusy[s])
                continue;
            const long long i = queue.front();
            queue.pop_front();
            const int gpu = p.engine.gpus > 0 ? static_cast<int>(s) % p.engine.gpus : -1;
            running[spawnChunk(p, i, ++attempts[i], gpu)] = {i, static_cast<int>(s)};
            slotBusy[s] = true;
        }
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0)
            throw std::runtime_error(std::string("farm: waitpid: ") + std::strerror(errno));
        const auto [i, slot] = running.at(pid);
        running.erase(pid);
        slotBusy[static_cast<size_t>(slot)] = false;
        const Chunk& c = p.chunks[static_cast<size_t>(i)];
        const std::string what = p.recordings[c.recording].name + " frames " + std::to_string(c.first) + "-" +
                                 std::to_string(c.last);
        if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && finishedChunk(p, c)) {
            logInfo("farm: chunk " + std::to_string(i) + " (" + what + ") done, " + std::to_string(++done) +
                    "/" + std::to_string(indices.size()));
            continue;
        }
        const std::string why = "farm: attempt " + std::to_string(attempts[i]) + " " + exitText(status);
        std::ofstream(chunkLog(p, i), std::ios::app) << why << "\n";
        const bool again = attempts[i] <= p.engine.retries;
        logWarning("farm: chunk " + std::to_string(i) + " (" + what + "): " + exitText(status) +
                   (again ? "; running it again" : "; giving up (" + chunkLog(p, i).string() + ")"));
        if (again)
            queue.push_back(i);
    }
}

// ---- Slurm ----

/// Runs a command, returns its stdout (its stderr goes to ours); throws naming it when it fails.
std::string capture(const std::string& command) {
    FILE* f = popen(command.c_str(), "r");
    if (!f)
        throw std::runtime_error("farm: cannot run " + command);
    std::string out;
    char buf[512];
    while (size_t n = std::fread(buf, 1, sizeof buf, f))
        out.append(buf, n);
    const int status = pclose(f);
    if (status != 0)
        throw std::runtime_error("farm: `" + command + "` failed (" + exitText(status) + "): " + out);
    return out;
}

/// Submits the chunks `indices` as a job array and a merge job after it (afterany) that submits the
/// unfinished ones again while `rounds` > 0. Returns the two job ids.
std::pair<std::string, std::string> submitSlurm(const Plan& p, const std::vector<long long>& indices,
                                                int rounds) {
    const fs::path dir = p.runDir / "slurm";
    fs::create_directories(dir);
    writeFileAtomically(dir / "chunk.sh", "#!/bin/sh\nexec " + shellQuote(p.exe.string()) + " farm chunk " +
                                              shellQuote(p.runDir.string()) + " \"$SLURM_ARRAY_TASK_ID\"\n");
    writeFileAtomically(dir / "merge.sh", "#!/bin/sh\nexec " + shellQuote(p.exe.string()) + " farm merge " +
                                              shellQuote(p.runDir.string()) + " --resubmit \"$1\"\n");
    std::string common = "sbatch --parsable --open-mode=append";
    if (!p.engine.partition.empty())
        common += " --partition=" + shellQuote(p.engine.partition);
    std::string array = common + " --job-name=pacifica-chunks --array=" + joinIndices(indices);
    if (p.engine.throttle > 0)
        array += "%" + std::to_string(p.engine.throttle);
    if (p.engine.gpusPerChunk > 0)
        array += " --gres=gpu:" + std::to_string(p.engine.gpusPerChunk);
    array += " --output=" + shellQuote((p.runDir / "logs" / "chunk-%5a.log").string()) + " " +
             shellQuote((dir / "chunk.sh").string());
    auto jobId = [](const std::string& out) { // --parsable: "ID" or "ID;CLUSTER"
        const std::string id = out.substr(0, out.find_first_of(";\n"));
        if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
            throw std::runtime_error("farm: sbatch printed no job id: '" + out + "'");
        return id;
    };
    const std::string arrayId = jobId(capture(array));
    const std::string mergeId =
        jobId(capture(common + " --job-name=pacifica-merge --dependency=afterany:" + arrayId +
                      " --output=" + shellQuote((p.runDir / "logs" / "merge.log").string()) + " " +
                      shellQuote((dir / "merge.sh").string()) + " " + std::to_string(rounds)));
    std::ofstream(dir / "jobs.log", std::ios::app)
        << "array " << arrayId << " chunks " << joinIndices(indices) << " merge " << mergeId << " rounds "
        << rounds << "\n";
    logInfo("farm: submitted chunks " + joinIndices(indices) + " as Slurm job array " + arrayId +
            ", merge job " + mergeId);
    return {arrayId, mergeId};
}

/// Waits for the merge's RUN/report.json; 0 when it says every recording is whole.
int waitForReport(const Plan& p) {
    const auto t0 = std::chrono::steady_clock::now();
    const fs::path report = p.runDir / "report.json";
    while (!fs::exists(report)) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >
            p.engine.waitTimeoutS)
            throw std::runtime_error("farm: no report.json after " + std::to_string(p.engine.waitTimeoutS) +
                                     " s; `pacifica farm status " + p.runDir.string() + "`");
        std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    std::ifstream in(report);
    const json r = json::parse(in, nullptr, false);
    return !r.is_discarded() && r.value("whole", false) && r.value("videos_ok", true) ? 0 : 1;
}

// ---- the merge ----

/// One summary.json for a recording whose chunks all finished: the schema of a one-process run's, its frames
/// in order, plus "chunks" (range, host, GPU, wall time of each).
json mergedSummary(const std::vector<json>& parts) {
    json s = parts.front();
    s.erase("chunk");
    json chunks = json::array();
    double totalS = 0.0;
    std::vector<double> wallMedians, gpuMedians;
    for (size_t vi = 0; vi < s["views"].size(); ++vi)
        s["views"][vi]["frames"] = json::array();
    for (const json& part : parts) {
        for (size_t vi = 0; vi < s["views"].size(); ++vi)
            for (const json& f : part["views"][vi]["frames"])
                s["views"][vi]["frames"].push_back(f);
        json c = part["chunk"];
        c["total_s"] = part["timings"].value("total_s", 0.0);
        c["time_to_first_frame_s"] = part["timings"].value("time_to_first_frame_s", 0.0);
        c["frame_wall_ms_median"] = part["timings"].value("frame_wall_ms_median", 0.0);
        totalS += c["total_s"].get<double>();
        wallMedians.push_back(part["timings"].value("frame_wall_ms_median", 0.0));
        gpuMedians.push_back(part["timings"].value("gpu_ms_median", 0.0));
        chunks.push_back(std::move(c));
    }
    s["frames"] = s["views"][0]["frames"];
    s["chunks"] = std::move(chunks);
    s["timings"]["total_s"] = totalS;
    s["timings"]["frames_per_second_overall"] =
        static_cast<double>(s["frames"].size()) / std::max(totalS, 1e-9);
    s["timings"]["frame_wall_ms_median"] = median(wallMedians);
    s["timings"]["gpu_ms_median"] = median(gpuMedians);
    s["timings"]["merged"] = "total_s: the chunks' total_s summed; medians: of the chunks' medians";
    return s;
}

/// FarmOptions::video for a whole recording: one video per view from its frames' PNGs, in frame order, each
/// encoded once (ffmpeg decodes the PNGs); a video newer than all its frames is kept. Records the videos, or
/// the error, in the report's entry `rj`; returns false when one could not be made (the frames stay).
bool encodeVideos(const Plan& p, const PlannedRecording& rec, const json& merged, json& rj) {
    json videos = json::array();
    try {
        std::vector<std::string> taken;
        for (const json& view : merged.at("views")) {
            std::string slug = fileSlug(view.at("name").get<std::string>());
            if (slug.empty())
                slug = "view";
            if (std::find(taken.begin(), taken.end(), slug) != taken.end()) // "a b" and "a-b"
                slug += "-" + std::to_string(taken.size());
            taken.push_back(slug);
            const fs::path target = p.runDir / rec.name / (slug + "." + p.video);
            std::vector<fs::path> pngs;
            for (const json& f : view.at("frames"))
                pngs.push_back(p.runDir / rec.name / f.at("png").get<std::string>());
            json entry = {{"view", view.at("name")}, {"file", target.string()}, {"frames", pngs.size()}};
            // Up to date (a resume that rendered nothing): newer than every frame, so it is left alone.
            std::error_code ec;
            const auto made = fs::last_write_time(target, ec);
            bool current = !ec;
            for (const fs::path& png : pngs)
                current = current && fs::last_write_time(png, ec) <= made && !ec;
            if (current) {
                videos.push_back(std::move(entry));
                continue;
            }
            VideoWriter video(target, view.at("size").at(0).get<int>(), view.at("size").at(1).get<int>(),
                              p.videoFps, VideoWriter::Input::Png);
            for (const fs::path& png : pngs)
                video.addPng(png);
            video.finish();
            videos.push_back(std::move(entry));
            logInfo("farm: " + std::to_string(video.frames()) + " frames -> " + target.string());
        }
    } catch (const std::exception& e) {
        rj["video_error"] = e.what();
        logError("farm: " + rec.name + ": no video: " + e.what());
        return false;
    }
    rj["videos"] = std::move(videos);
    return true;
}

/// RUN/<recording>/summary.json for every whole recording, and RUN/report.json. Returns whether all are.
bool writeMerged(const Plan& p) {
    json recs = json::array(), failed = json::array();
    bool whole = true, videosFailed = false;
    for (size_t r = 0; r < p.recordings.size(); ++r) {
        const PlannedRecording& rec = p.recordings[r];
        json j = {{"name", rec.name}, {"path", rec.path.string()}, {"frames", rec.frames}};
        if (!rec.error.empty()) {
            j["state"] = "quarantined";
            j["error"] = rec.error;
            whole = false;
            recs.push_back(std::move(j));
            continue;
        }
        std::vector<json> parts;
        json missing = json::array();
        for (const Chunk& c : p.chunks) {
            if (c.recording != r)
                continue;
            if (std::optional<json> s = finishedChunk(p, c)) {
                parts.push_back(std::move(*s));
                continue;
            }
            missing.push_back({c.first, c.last});
            failed.push_back({{"chunk", c.index},
                              {"recording", rec.name},
                              {"frames", {c.first, c.last}},
                              {"error", failureOf(p, c.index)},
                              {"log", chunkLog(p, c.index).string()}});
        }
        j["state"] = missing.empty() ? "whole" : "incomplete";
        j["missing_frames"] = std::move(missing);
        if (j["state"] == "whole") {
            const json merged = mergedSummary(parts);
            writeFileAtomically(p.runDir / rec.name / "summary.json", reportText(merged));
            if (!p.video.empty() && !encodeVideos(p, rec, merged, j))
                videosFailed = true;
        }
        whole = whole && j["state"] == "whole";
        recs.push_back(std::move(j));
    }
    size_t wholeCount = 0, quarantined = 0;
    for (const json& r : recs) {
        wholeCount += r["state"] == "whole" ? 1 : 0;
        quarantined += r["state"] == "quarantined" ? 1 : 0;
    }
    logInfo("farm: " + std::to_string(wholeCount) + " of " + std::to_string(recs.size()) +
            " recording(s) whole, " + std::to_string(quarantined) + " quarantined, " +
            std::to_string(failed.size()) + " chunk(s) failed -> " + (p.runDir / "report.json").string());
    writeFileAtomically(p.runDir / "report.json", reportText(json{{"whole", whole},
                                                                  {"videos_ok", !videosFailed},
                                                                  {"engine", p.engine.name},
                                                                  {"recordings", std::move(recs)},
                                                                  {"failed_chunks", std::move(failed)}}));
    return whole && !videosFailed;
}

int finishRun(const Plan& p, const std::vector<long long>& indices) {
    if (p.engine.name == "slurm") {
        fs::remove(p.runDir / "report.json");
        submitSlurm(p, indices, p.engine.retries);
        return p.engine.wait ? waitForReport(p) : 0;
    }
    runLocal(p, indices);
    return writeMerged(p) ? 0 : 1;
}

void checkEngine(const FarmEngine& e) {
    if (e.name != "local" && e.name != "slurm")
        throw UsageError("--engine must be 'local' or 'slurm', got '" + e.name + "'");
    if (e.workers < 1 || e.workers > 256)
        throw UsageError("--workers must be in [1, 256], got " + std::to_string(e.workers));
    if (e.retries < 0 || e.retries > 100)
        throw UsageError("--retries must be in [0, 100], got " + std::to_string(e.retries));
}

void printPlan(const Plan& p) {
    for (const PlannedRecording& r : p.recordings)
        std::printf("%s: %s\n", r.path.c_str(),
                    r.error.empty()
                        ? (std::to_string(r.frames) + " frames -> " + (p.runDir / r.name).string()).c_str()
                        : ("quarantined: " + r.error).c_str());
    for (const Chunk& c : p.chunks) {
        std::string line = "chunk " + std::to_string(c.index) + ":";
        for (const std::string& a : chunkArgs(p, c))
            line += " " + shellQuote(a);
        std::printf("%s\n", line.c_str());
    }
    std::printf("%zu chunks on the %s engine\n", p.chunks.size(), p.engine.name.c_str());
}

/// plan.json keeps every path to run the chunks with it, so each must be UTF-8 (JSON's text).
void requireUtf8(const fs::path& path, const char* what) {
    if (!isUtf8(path.string()))
        throw UsageError(std::string("farm run: ") + what + " '" + path.string() +
                         "' is not UTF-8, and plan.json (JSON) cannot hold it: rename it");
}

} // namespace

int farmRun(const FarmOptions& o, const ReplayParser& parseReplay) {
    checkEngine(o.engine);
    requireUtf8(o.runDir, "--out");
    for (const fs::path& r : o.recordings)
        requireUtf8(r, "the recording");
    for (const std::string& a : o.replayArgs)
        requireUtf8(a, "the replay option");
    if (o.recordings.empty())
        throw UsageError("farm run: no recording given");
    if (o.chunkFrames < 1)
        throw UsageError("--chunk-frames must be >= 1, got " + std::to_string(o.chunkFrames));
    if (fs::exists(planPath(o.runDir)))
        throw UsageError("--out: '" + o.runDir.string() +
                         "' already holds a run (plan.json): `pacifica farm resume " + o.runDir.string() +
                         "` or `pacifica farm status " + o.runDir.string() + "`");
    for (const std::string& a : o.replayArgs)
        if (a == "--out" || a.rfind("--out=", 0) == 0 || a == "--frames" || a.rfind("--frames=", 0) == 0 ||
            a == "--video" || a.rfind("--video=", 0) == 0)
            throw UsageError("farm run: the replay options after -- must not set " +
                             a.substr(0, a.find('=')) + " (the farm sets --out and --frames per chunk)");
    FarmOptions abs = o;
    abs.runDir = fs::weakly_canonical(fs::absolute(o.runDir));
    Plan p = makePlan(abs, parseReplay);
    if (o.dryRun) {
        printPlan(p);
        return 0;
    }
    fs::create_directories(p.runDir / "logs");
    for (const PlannedRecording& r : p.recordings) // made here, so no chunk takes it for its own
        if (r.error.empty())
            fs::create_directories(p.runDir / r.name);
    writeFileAtomically(planPath(p.runDir), planJson(p).dump(2) + "\n");
    std::vector<long long> all;
    for (const Chunk& c : p.chunks)
        all.push_back(c.index);
    if (all.empty()) {
        writeMerged(p);
        logWarning("farm: nothing to render: every recording was quarantined (report.json)");
        return 1;
    }
    return finishRun(p, all);
}

int farmResume(const fs::path& runDir, const std::function<void(FarmEngine&)>& adjust) {
    Plan p = loadPlan(fs::weakly_canonical(fs::absolute(runDir)));
    adjust(p.engine);
    checkEngine(p.engine);
    writeFileAtomically(planPath(p.runDir), planJson(p).dump(2) + "\n");
    const std::vector<long long> todo = unfinished(p);
    if (todo.empty()) {
        logInfo("farm: nothing to render: every chunk of " + p.runDir.string() + " is done");
        return writeMerged(p) ? 0 : 1;
    }
    logInfo("farm: " + std::to_string(todo.size()) + " of " + std::to_string(p.chunks.size()) +
            " chunks to run");
    return finishRun(p, todo);
}

int farmStatus(const fs::path& runDir) {
    const Plan p = loadPlan(fs::weakly_canonical(fs::absolute(runDir)));
    std::map<size_t, std::pair<long long, long long>> done; // recording -> (chunks done, frames done)
    for (const Chunk& c : p.chunks)
        if (finishedChunk(p, c)) {
            done[c.recording].first += 1;
            done[c.recording].second += c.last - c.first + 1;
        }
    for (size_t r = 0; r < p.recordings.size(); ++r) {
        const PlannedRecording& rec = p.recordings[r];
        if (!rec.error.empty()) {
            std::printf("%s: quarantined: %s\n", rec.name.c_str(), rec.error.c_str());
            continue;
        }
        long long chunks = 0;
        for (const Chunk& c : p.chunks)
            chunks += c.recording == r ? 1 : 0;
        std::printf("%s: %lld/%lld chunks, %lld/%lld frames done\n", rec.name.c_str(), done[r].first, chunks,
                    done[r].second, rec.frames);
    }
    for (long long i : unfinished(p))
        if (fs::exists(chunkLog(p, i)))
            std::printf("chunk %lld: %s\n", i, failureOf(p, i).c_str());
    return 0;
}

int farmChunk(const fs::path& runDir, long long index) {
    const Plan p = loadPlan(fs::weakly_canonical(fs::absolute(runDir)));
    if (index < 0 || index >= static_cast<long long>(p.chunks.size()))
        throw UsageError("farm chunk: no chunk " + std::to_string(index) + " in " +
                         planPath(runDir).string() + " (0-" + std::to_string(p.chunks.size() - 1) + ")");
    std::vector<std::string> args = chunkArgs(p, p.chunks[static_cast<size_t>(index)]);
    const std::string cuda = visibleCudaDevice();
    bool hasDevice = false; // a device named in the replay's options wins over the engine's
    for (const std::string& a : p.replayArgs)
        hasDevice = hasDevice || a.rfind("--egl-device", 0) == 0 || a.rfind("--cuda-device", 0) == 0;
    if (!cuda.empty() && !hasDevice)
        args.insert(args.end(), {"--cuda-device", cuda});
    std::vector<char*> argv = {const_cast<char*>(p.exe.c_str())};
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(nullptr);
    execv(p.exe.c_str(), argv.data());
    throw std::runtime_error("farm chunk: cannot run " + p.exe.string() + ": " + std::strerror(errno));
}

int farmMerge(const fs::path& runDir, int resubmitRounds) {
    const Plan p = loadPlan(fs::weakly_canonical(fs::absolute(runDir)));
    const std::vector<long long> todo = unfinished(p);
    if (p.engine.name == "slurm" && !todo.empty() && resubmitRounds > 0) {
        logWarning("farm: chunks " + joinIndices(todo) + " did not finish; submitting them again (" +
                   std::to_string(resubmitRounds) + " round(s) left)");
        submitSlurm(p, todo, resubmitRounds - 1);
        return 0;
    }
    return writeMerged(p) ? 0 : 1;
}

} // namespace pacifica::tools
