// BenchPlot: runs gnuplot on a script a benchmark wrote beside its data (bench_accuracy.cpp,
// bench_soak.cpp). Header-only.
#pragma once

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace pacifica::bench {

/// Runs `gnuplot SCRIPT` in `dir` (fork + chdir + execlp, so no shell quoting is involved); the script
/// writes `png` there. Returns false when gnuplot is not installed; throws when it fails, removing a half
/// written plot.
inline bool runGnuplot(const std::string& dir, const std::string& script, const std::string& png) {
    const pid_t pid = fork();
    if (pid < 0)
        throw std::runtime_error("cannot start gnuplot: fork failed");
    if (pid == 0) {
        if (chdir(dir.c_str()) != 0)
            _exit(126);
        execlp("gnuplot", "gnuplot", script.c_str(), static_cast<char*>(nullptr));
        _exit(errno == ENOENT ? 127 : 126);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid)
        throw std::runtime_error("gnuplot: waitpid failed");
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
        return false;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::filesystem::remove(dir + "/" + png); // gnuplot opens it before it fails: no half plot
        throw std::runtime_error("gnuplot failed on " + dir + "/" + script + " (status " +
                                 std::to_string(status) + ")");
    }
    if (!std::filesystem::exists(dir + "/" + png))
        throw std::runtime_error("gnuplot wrote no " + dir + "/" + png);
    return true;
}

} // namespace pacifica::bench
