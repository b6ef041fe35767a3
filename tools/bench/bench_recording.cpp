// pacifica-bench-recording: how fast the Tacview ACMI reader parses, and how much memory it holds, on a
// generated recording shaped like a busy DCS export (~97% of its objects are shells,
// flares and chaff that live a few seconds; aircraft with 9-field transforms and extra properties at 10 Hz;
// ships at 1 Hz; removals and events). The text file and a zip of it are parsed in a fresh child process each
// (fork + exec of this program), so the peak resident memory (getrusage ru_maxrss) belongs to one parse
// alone; the baseline RSS of the child before parsing is subtracted. Throughput is the decoded text size over
// the wall time (steady_clock) of readRecording(), median of --runs. Writes DIR/recording_bench.{json,md}.
//
//   pacifica-bench-recording --out DIR [--mb 200] [--runs 3] [--keep]
#include "BenchCli.h"

#include <engine/Stats.h>
#include <recording/Recording.h>

#include <nlohmann/json.hpp>
#include <zip.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using pacifica::median;
using pacifica::recording::ObjectSample;
using pacifica::recording::Recording;

namespace {

/// Writes a synthetic ACMI recording of at least `bytes` bytes. Deterministic (fixed LCG).
/// The generated recording's writer: 40 aircraft every frame, 6 ships every second, shells that live ~3 s,
/// a message every minute, from a fixed-seed LCG (the same bytes every run).
struct BusyRecording {
    static constexpr int AIRCRAFT = 40, SHIPS = 6;
    struct Shell {
        uint64_t id;
        double lon, lat, alt, dies;
    };
    std::ofstream out;
    uint64_t state = 12345, nextId = 0x10000, written = 0;
    std::vector<double> lon, lat, alt, hdg;
    std::vector<Shell> shells;
    char line[512];

    explicit BusyRecording(const fs::path& file)
        : out(file, std::ios::binary), lon(AIRCRAFT), lat(AIRCRAFT), alt(AIRCRAFT), hdg(AIRCRAFT) {
        out << "\xEF\xBB\xBF"
            << "FileType=text/acmi/tacview\nFileVersion=2.2\n"
            << "0,ReferenceTime=2024-06-01T10:00:00Z\n0,ReferenceLongitude=36\n0,ReferenceLatitude=44\n"
            << "0,Title=Generated busy recording\\, for the parser benchmark\n";
        for (int i = 0; i < AIRCRAFT; ++i) {
            lon[i] = 0.5 + rnd();
            lat[i] = 0.5 + rnd();
            alt[i] = 500 + 8000 * rnd();
            hdg[i] = 360 * rnd();
        }
    }
    double rnd() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return static_cast<double>(state >> 11) / 9007199254740992.0;
    }
    void emit(int n) {
        out.write(line, n);
        written += static_cast<uint64_t>(n);
    }
    void aircraft(long frame) {
        for (int i = 0; i < AIRCRAFT; ++i) {
            hdg[i] += (rnd() - 0.5) * 2.0;
            lon[i] += 0.00003 * std::sin(hdg[i] * M_PI / 180.0);
            lat[i] += 0.00002 * std::cos(hdg[i] * M_PI / 180.0);
            alt[i] += (rnd() - 0.5) * 4.0;
            int n = 0;
            if (frame == 0)
                n = std::snprintf(
                    line, sizeof line,
                    "%x,T=%.7f|%.7f|%.2f|%.1f|%.1f|%.1f|%.2f|%.2f|%.1f,Type=Air+FixedWing,Name=F-%d,"
                    "Pilot=Pilot %d,Coalition=Allies,Color=Blue\n",
                    0x100 + i, lon[i], lat[i], alt[i], (rnd() - 0.5) * 60, (rnd() - 0.5) * 20, hdg[i],
                    1000 * rnd(), 1000 * rnd(), hdg[i], i, i);
            else
                n = std::snprintf(line, sizeof line,
                                  "%x,T=%.7f|%.7f|%.2f|%.1f|%.1f|%.1f|%.2f|%.2f|%.1f,IAS=%.1f,AOA=%.1f\n",
                                  0x100 + i, lon[i], lat[i], alt[i], (rnd() - 0.5) * 60, (rnd() - 0.5) * 20,
                                  hdg[i], 1000 * rnd(), 1000 * rnd(), hdg[i], 150 + 100 * rnd(), 10 * rnd());
            emit(n);
        }
    }
    void ships(long frame, double t) {
        for (int s = 0; s < SHIPS; ++s)
            emit(std::snprintf(line, sizeof line, "%x,T=%.7f|%.7f||||%.1f%s\n", 0x200 + s, 0.8 + 0.0001 * t,
                               0.8 + 0.01 * s, 120.0, frame == 0 ? ",Type=Sea+Watercraft+Warship" : ""));
    }
    /// A few new shells per frame, each living ~3 s with 3-field updates, then removed.
    void shellLines(double t) {
        for (int k = 0; k < 4; ++k) {
            const int a = static_cast<int>(rnd() * AIRCRAFT);
            shells.push_back({nextId++, lon[a], lat[a], alt[a], t + 2.0 + 2.0 * rnd()});
            const Shell& s = shells.back();
            emit(std::snprintf(line, sizeof line, "%llx,T=%.7f|%.7f|%.1f,Type=Projectile+Shell\n",
                               static_cast<unsigned long long>(s.id), s.lon, s.lat, s.alt));
        }
        for (size_t k = 0; k < shells.size();) {
            Shell& s = shells[k];
            if (t >= s.dies) {
                emit(std::snprintf(line, sizeof line, "-%llx\n", static_cast<unsigned long long>(s.id)));
                s = shells.back();
                shells.pop_back();
                continue;
            }
            s.lon += 0.0001;
            s.alt -= 20.0;
            emit(std::snprintf(line, sizeof line, "%llx,T=%.7f||%.1f\n",
                               static_cast<unsigned long long>(s.id), s.lon, s.alt));
            ++k;
        }
    }
};

uint64_t generate(const fs::path& file, uint64_t bytes) {
    BusyRecording g(file);
    for (long frame = 0; g.written < bytes; ++frame) {
        const double t = frame * 0.1;
        g.emit(std::snprintf(g.line, sizeof g.line, "#%.2f\n", t));
        g.aircraft(frame);
        if (frame % 10 == 0)
            g.ships(frame, t);
        g.shellLines(t);
        if (frame % 600 == 0)
            g.emit(std::snprintf(g.line, sizeof g.line, "0,Event=Message|%x|Generated event at %.1f s\n",
                                 0x100, t));
    }
    return g.written;
}

void zipFile(const fs::path& text, const fs::path& zipped) {
    int err = 0;
    zip_t* za = zip_open(zipped.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    if (!za)
        throw std::runtime_error("cannot create " + zipped.string());
    zip_source_t* src = zip_source_file(za, text.c_str(), 0, -1);
    if (!src || zip_file_add(za, text.filename().c_str(), src, ZIP_FL_OVERWRITE) < 0 || zip_close(za) != 0)
        throw std::runtime_error("cannot write " + zipped.string());
}

long rssKb() {
    std::ifstream in("/proc/self/status");
    std::string key;
    while (in >> key) {
        if (key == "VmRSS:") {
            long kb = 0;
            in >> kb;
            return kb;
        }
        std::getline(in, key);
    }
    return 0;
}

struct Measure {
    double seconds = 0.0;
    long peakKb = 0, baseKb = 0;
    uint64_t bytes = 0;
    long long samples = 0, objects = 0;
    bool ok = false;
};

/// The child's side: parses `file` in this fresh process and writes its figures to `fd`.
int parseChild(const char* file, int fd) {
    Measure m;
    m.baseKb = rssKb();
    const auto t0 = std::chrono::steady_clock::now();
    try {
        const Recording r = pacifica::recording::readRecording(file);
        m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        m.bytes = r.bytes;
        m.samples = r.samples;
        m.objects = static_cast<long long>(r.objects.size());
        m.ok = true;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "parse failed: %s\n", e.what());
    }
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    m.peakKb = ru.ru_maxrss;
    if (write(fd, &m, sizeof m) != static_cast<ssize_t>(sizeof m))
        return 3;
    return m.ok ? 0 : 2;
}

/// Parses `file` in a child process that re-executes this program (a fresh process, as a user's replay is:
/// a forked child would inherit the generator's heap and malloc state), reporting through a pipe.
Measure parseInChild(const fs::path& file) {
    int fd[2];
    if (pipe(fd) != 0)
        throw std::runtime_error("pipe failed");
    const pid_t pid = fork();
    if (pid == 0) {
        close(fd[0]);
        const std::string fdText = std::to_string(fd[1]);
        execl("/proc/self/exe", "pacifica-bench-recording", "--parse-child", file.c_str(), fdText.c_str(),
              static_cast<char*>(nullptr));
        _exit(127);
    }
    close(fd[1]);
    Measure m;
    const ssize_t got = read(fd[0], &m, sizeof m);
    close(fd[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (got != static_cast<ssize_t>(sizeof m) || !m.ok)
        throw std::runtime_error("parsing " + file.string() + " failed in the child");
    return m;
}

struct Args {
    fs::path outDir;
    double mb = 200.0;
    int runs = 3;
    bool keep = false;
};

std::optional<int> parseArgs(int argc, char** argv, Args& a) {
    CLI::App app("ACMI parse throughput (MB/s) and peak memory on a generated busy recording, text and zip "
                 "(docs/RECORDINGS.md)",
                 "pacifica-bench-recording");
    app.add_option("--out", a.outDir, "report directory (recording_bench.json, recording_bench.md)")
        ->required();
    app.add_option("--mb", a.mb, "size of the generated text ACMI, MB")->check(CLI::Range(0.001, 100000.0));
    app.add_option("--runs", a.runs, "parses per file (median)")->check(CLI::Range(1, 1000));
    app.add_flag("--keep", a.keep, "keep the generated recordings");
    return pacifica::bench::parseCommandLine(app, argc, argv);
}

/// One file parsed `runs` times, each in a fresh child: its JSON row; its Markdown row appended to `md`.
nlohmann::json measureFile(const fs::path& f, int runs, std::string& md) {
    std::vector<double> secs;
    Measure m;
    for (int r = 0; r < runs; ++r) {
        m = parseInChild(f);
        secs.push_back(m.seconds);
    }
    const double s = median(secs);
    const double decodedMb = static_cast<double>(m.bytes) / 1e6;
    const double tracksMb = static_cast<double>(m.samples) * sizeof(ObjectSample) / 1e6;
    const double peakMb = static_cast<double>(m.peakKb - m.baseKb) / 1024.0;
    const double fileMb = static_cast<double>(fs::file_size(f)) / 1e6;
    char row[512];
    std::snprintf(row, sizeof row, "| %s | %.1f | %.1f | %lld | %lld | %.1f | %.3f | %.1f | %.1f | %.2f |\n",
                  f.filename().string().c_str(), fileMb, decodedMb, m.objects, m.samples, tracksMb, s,
                  decodedMb / s, peakMb, peakMb / tracksMb);
    md += row;
    std::printf("%s", row);
    return {{"input", f.filename().string()},
            {"file_mb", fileMb},
            {"decoded_mb", decodedMb},
            {"objects", m.objects},
            {"samples", m.samples},
            {"tracks_kept_mb", tracksMb},
            {"parse_s_median", s},
            {"mb_per_s", decodedMb / s},
            {"peak_rss_above_baseline_mb", peakMb},
            {"peak_over_tracks", peakMb / tracksMb}};
}

} // namespace

int main(int argc, char** argv) {
    if (argc == 4 && std::string(argv[1]) == "--parse-child") // internal: one parse in a child process
        return parseChild(argv[2], std::atoi(argv[3]));
    Args a;
    if (const auto code = parseArgs(argc, argv, a))
        return *code;
    try {
        fs::create_directories(a.outDir);
        const fs::path text = a.outDir / "generated.txt.acmi", zipped = a.outDir / "generated.zip.acmi";
        std::printf("generating %.0f MB ACMI ...\n", a.mb);
        const uint64_t bytes = generate(text, static_cast<uint64_t>(a.mb * 1e6));
        zipFile(text, zipped);
        nlohmann::json results = nlohmann::json::array();
        std::string md =
            "| input | file MB | decoded MB | objects | samples | tracks kept MB | parse s (median of " +
            std::to_string(a.runs) +
            ") | MB/s | peak RSS MB (above baseline) | peak / tracks |\n"
            "|---|---|---|---|---|---|---|---|---|---|\n";
        for (const fs::path& f : {text, zipped})
            results.push_back(measureFile(f, a.runs, md));
        nlohmann::json summary = {{"generated_bytes", bytes},
                                  {"clock", "steady_clock around readRecording(), one process per parse"},
                                  {"memory", "ru_maxrss of the parsing child minus its VmRSS before parsing"},
                                  {"tracks_kept", "samples x sizeof(ObjectSample) (40 bytes)"},
                                  {"results", results}};
        pacifica::writeFileAtomically(a.outDir / "recording_bench.json", summary.dump(2) + "\n");
        pacifica::writeFileAtomically(a.outDir / "recording_bench.md", md);
        if (!a.keep) {
            fs::remove(text);
            fs::remove(zipped);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica-bench-recording: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
