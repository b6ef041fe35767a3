// libFuzzer target: the image inputs -- `pacifica replay --height-map FILE` and `--env FILE`
// (tools/src/ImageInputs.cpp) and the EXRs `tonemap compare` reads, all through capture::readImage()
// (engine/src/capture/Capture.cpp, OpenImageIO underneath). The first byte picks the file type (OpenImageIO
// chooses its reader by the name's extension, then by the content); the rest is the file. Any input must end
// in an image or an exception naming the file: no crash, leak, hang, or allocation beyond readImage's
// MAX_READ_SAMPLES (run with -rss_limit_mb). The seed corpus holds small valid EXR, PNG and HDR files.
#include "ImageInputs.h"
#include "engine/capture/Capture.h"

#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <unistd.h>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1)
        return 0;
    static const char* const kinds[] = {".exr", ".png", ".hdr", ".tif"};
    static const std::string dir = [] {
        char tmpl[] = "/tmp/pacifica-fuzz-image-XXXXXX";
        return std::string(mkdtemp(tmpl) ? tmpl : "/tmp");
    }();
    const std::string file = dir + "/input" + kinds[data[0] % 4];
    if (FILE* f = std::fopen(file.c_str(), "wb")) {
        std::fwrite(data + 1, 1, size - 1, f);
        std::fclose(f);
    } else {
        return 0;
    }
    try {
        (void)pacifica::capture::readImage(file);
    } catch (const std::exception&) {
    }
    try {
        (void)pacifica::tools::loadHeightMap(file);
    } catch (const std::exception&) {
    }
    try {
        (void)pacifica::tools::loadEnvironment(file);
    } catch (const std::exception&) {
    }
    return 0;
}
