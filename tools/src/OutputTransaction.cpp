// OutputTransaction: a replay's output folder as a transaction (OutputTransaction.h).
#include "OutputTransaction.h"

#include "Usage.h"
#include "engine/AtomicFile.h"

#include <cctype>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <sys/file.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace pacifica::tools {

std::string reportText(const nlohmann::json& report) {
    return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}
namespace fs = std::filesystem;

namespace {

constexpr const char* STAGING_PREFIX = ".pacifica-staging-";
constexpr const char* LOCK_SUFFIX = ".lock";

/// ".pacifica-staging-<host>-": this host's staging folders. Their locks are flock()s, which a network file
/// system may keep per host: another host's folder may belong to a live run, so only this host's are judged.
std::string hostPrefix() {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0 || name[0] == '\0')
        std::strcpy(name, "host");
    std::string host;
    for (const char* c = name; *c; ++c)
        host += std::isalnum(static_cast<unsigned char>(*c)) || *c == '.' || *c == '_' ? *c : '_';
    return STAGING_PREFIX + host + "-";
}

} // namespace

void OutputTransaction::checkWritable(const fs::path& dir) {
    std::error_code ec;
    fs::path probe = dir.empty() ? fs::path(".") : dir;
    while (!fs::exists(probe, ec) && probe.has_parent_path() && probe.parent_path() != probe)
        probe = probe.parent_path();
    if (!fs::exists(probe, ec))
        probe = ".";
    const std::string what = probe == dir
                                 ? "'" + dir.string() + "'"
                                 : "'" + probe.string() + "' (where '" + dir.string() + "' would be created)";
    if (!fs::is_directory(probe, ec))
        throw UsageError("--out: " + what + " exists and is not a directory");
    struct statvfs vfs {};
    if (statvfs(probe.c_str(), &vfs) == 0 && (vfs.f_flag & ST_RDONLY) != 0)
        throw UsageError("--out: " + what + " is on a read-only file system");
    if (access(probe.c_str(), W_OK | X_OK) != 0)
        throw UsageError("--out: " + what + " is not writable: " + std::strerror(errno));
}

OutputTransaction::OutputTransaction(fs::path dir, bool shared) : mDir(std::move(dir)) {
    checkWritable(mDir);
    std::error_code ec;
    if (!fs::exists(mDir, ec)) {
        // Remember the outermost directory we create, to remove exactly that on failure.
        fs::path probe = mDir;
        while (!probe.empty() && !fs::exists(probe, ec)) {
            mCreatedRoot = probe;
            probe = probe.parent_path();
        }
        fs::create_directories(mDir, ec);
        if (ec)
            throw UsageError("--out: cannot create directory '" + mDir.string() + "': " + ec.message());
        if (shared)
            mCreatedRoot.clear(); // other processes may be writing into it already
    }
    removeStaleStaging();
    const std::string name = hostPrefix() + std::to_string(getpid());
    mStaging = mDir / name;
    mLock = mDir / (name + LOCK_SUFFIX);
    // The lock first, then the folder: a staging folder without a locked lock file belongs to a dead run.
    // The lock file is locked under another name and renamed into place, so a run cleaning up dead runs'
    // folders at the same moment never finds it unlocked.
    const fs::path unlocked = mDir / (name + ".locking");
    mLockFd = open(unlocked.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (mLockFd < 0 || flock(mLockFd, LOCK_EX | LOCK_NB) != 0 || rename(unlocked.c_str(), mLock.c_str()) != 0)
        throw UsageError("--out: cannot lock '" + mLock.string() + "': " + std::strerror(errno));
    fs::remove_all(mStaging, ec); // a dead run with this pid
    fs::create_directory(mStaging, ec);
    if (ec)
        throw UsageError("--out: cannot write into '" + mDir.string() + "': " + ec.message());
}

void OutputTransaction::removeStaleStaging() {
    std::error_code ec;
    const std::string prefix = hostPrefix();
    for (const fs::directory_entry& e : fs::directory_iterator(mDir, ec)) {
        const std::string n = e.path().filename().string();
        if (n.rfind(prefix, 0) == 0 && n.ends_with(".locking")) { // killed before its lock was in place
            const int fd = open(e.path().c_str(), O_RDWR | O_CLOEXEC);
            if (fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) == 0)
                fs::remove(e.path(), ec);
            if (fd >= 0)
                close(fd);
            continue;
        }
        if (n.rfind(prefix, 0) != 0 || n.size() <= std::strlen(LOCK_SUFFIX) ||
            n.compare(n.size() - std::strlen(LOCK_SUFFIX), std::string::npos, LOCK_SUFFIX) != 0)
            continue;
        const int fd = open(e.path().c_str(), O_RDWR | O_CLOEXEC);
        if (fd < 0)
            continue;
        if (flock(fd, LOCK_EX | LOCK_NB) == 0) { // its run is gone: remove its folder, then the lock
            fs::remove_all(mDir / n.substr(0, n.size() - std::strlen(LOCK_SUFFIX)), ec);
            fs::remove(e.path(), ec);
            ++mStaleRemoved;
        }
        close(fd);
    }
}

OutputTransaction::~OutputTransaction() {
    std::error_code ec;
    fs::remove_all(mStaging, ec);
    if (mLockFd >= 0) {
        fs::remove(mLock, ec);
        close(mLockFd);
    }
    if (!mCommitted && !mCreatedRoot.empty())
        fs::remove_all(mCreatedRoot, ec); // everything under it is ours
}

fs::path OutputTransaction::staged(const std::string& name) {
    mNames.push_back(name);
    return mStaging / name;
}

void OutputTransaction::commit(const nlohmann::json& summary) {
    std::error_code ec;
    for (const std::string& n : mNames) { // check first: never half-commit over something we can't replace
        const fs::path dest = mDir / n;
        if (fs::exists(dest, ec) && !fs::is_regular_file(dest, ec))
            throw std::runtime_error(dest.string() + ": exists and is not a regular file; not replacing it");
    }
    const fs::path old = mStaging / ".replaced";
    fs::create_directory(old);
    std::vector<std::string> moved, replaced;
    try {
        for (const std::string& n : mNames) {
            if (fs::exists(mDir / n, ec)) {
                fs::rename(mDir / n, old / n);
                replaced.push_back(n);
            }
            fs::rename(mStaging / n, mDir / n);
            moved.push_back(n);
        }
        writeFileAtomically(mDir / "summary.json", reportText(summary));
    } catch (...) {
        for (const std::string& n : moved)
            fs::remove(mDir / n, ec);
        for (const std::string& n : replaced)
            fs::rename(old / n, mDir / n, ec);
        throw;
    }
    mCommitted = true;
}

void OutputTransaction::publish(const std::vector<std::string>& names) {
    mCommitted = true; // frames that landed stay, a failure after this point included
    for (const std::string& n : names) {
        fs::rename(mStaging / n, mDir / n);
        std::erase(mNames, n);
    }
}

void OutputTransaction::land(const std::string& name, const std::string& text) {
    mCommitted = true;
    writeFileAtomically(mStaging / name, text); // its temporary, if killed, stays inside the staging folder
    fs::rename(mStaging / name, mDir / name);
}

} // namespace pacifica::tools
