// The shared data directory of the tests: real recordings (data/flights), HDR images (data/hdr), the ACES
// OCIO configs (data/ocio) and the look references, which do not ship with the repository. Its path comes
// from $PACIFICA_SHARED_DIR, which ctest sets from the CMake cache variable PACIFICA_SHARED_DIR (default:
// a directory named `shared` beside the source tree; tests/README.md).
#pragma once

#include <cstdlib>
#include <filesystem>

namespace pacifica::testdata {

/// $PACIFICA_SHARED_DIR, or an empty path when it is unset (the files under it then do not exist, and the
/// tests that read them say which file was missing).
inline std::filesystem::path sharedDir() {
    const char* env = std::getenv("PACIFICA_SHARED_DIR");
    return env && *env ? std::filesystem::path(env) : std::filesystem::path();
}

} // namespace pacifica::testdata
