// AtomicFile: temporary beside the target, flush, rename (POSIX rename replaces the target atomically).
#include "engine/AtomicFile.h"

#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace pacifica {
namespace fs = std::filesystem;

void writeFileAtomically(const fs::path& path, const std::function<void(std::ostream&)>& write) {
    // Hidden and named by the process, so two writers of the same target never share a temporary.
    const fs::path tmp =
        path.parent_path() / ("." + path.filename().string() + ".tmp-" + std::to_string(getpid()));
    auto fail = [&](const std::string& reason) {
        std::error_code ec;
        fs::remove(tmp, ec);
        return std::runtime_error(path.string() + ": cannot write: " + reason);
    };
    try {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out)
            throw fail("cannot create " + tmp.string());
        write(out);
        out.flush();
        if (!out)
            throw fail("write failed (disk full?)");
        out.close();
        if (!out)
            throw fail("close failed");
    } catch (...) { // the writer's own exception or ours: no temporary left either way
        std::error_code ec;
        fs::remove(tmp, ec);
        throw;
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec)
        throw fail("cannot rename into place: " + ec.message());
}

void writeFileAtomically(const fs::path& path, std::string_view text) {
    writeFileAtomically(
        path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

} // namespace pacifica
