// libFuzzer target: an OCIO config given by path (`--ocio-config FILE` of replay and tonemap compare, $OCIO),
// loaded through the engine's ColorPipeline (engine/color/ColorPipeline.h). The input is written to a file
// FUZZ.ocio in a folder of its own (LUTs a config names are looked up beside it; there are none) and loaded;
// when it loads, up to 4 displays x 4 views are selected, a few pixels are transformed on the CPU and the
// GLSL is generated. Everything may fail with a ColorError naming the file or the field; any other exception,
// a crash, a leak or a hang is a finding. The transformed pixels are not checked: a config may map anything
// to anything.
#include "engine/color/ColorPipeline.h"

#include <OpenColorIO/OpenColorIO.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

/// FUZZ.ocio in a folder made once per process (pid-named, removed at exit).
const std::filesystem::path& configPath() {
    static const struct Folder {
        std::filesystem::path dir, file;
        Folder() {
            dir = std::filesystem::temp_directory_path() / ("pacifica-fuzz-ocio-" + std::to_string(getpid()));
            std::filesystem::create_directories(dir);
            file = dir / "FUZZ.ocio";
        }
        ~Folder() {
            std::error_code ec;
            std::filesystem::remove_all(dir, ec);
        }
    } folder;
    return folder.file;
}

void exercise(pacifica::color::ColorPipeline& pipeline) {
    const std::vector<std::string> displays = pipeline.displays();
    for (size_t d = 0; d < displays.size() && d < 4; ++d) {
        const std::vector<std::string> views = pipeline.views(displays[d]);
        for (size_t v = 0; v < views.size() && v < 4; ++v) {
            pipeline.select(displays[d], views[v]);
            float rgba[] = {0.18f, 0.18f, 0.18f, 1.0f, 16.0f, 0.5f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f};
            pipeline.applyCpu(rgba, 3);
            (void)pipeline.decodeDisplayCpu(rgba, 3);
            (void)pipeline.gpuShader();
        }
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path& file = configPath();
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
        if (!out) {
            std::fprintf(stderr, "fuzz_ocio_config: cannot write %s\n", file.c_str());
            std::abort();
        }
    }
    // OpenColorIO caches files by path, and every input is the same path: each starts from empty caches.
    OCIO_NAMESPACE::ClearAllCaches();
    try {
        pacifica::color::ColorPipeline pipeline = pacifica::color::ColorPipeline::fromFile(file);
        (void)pipeline.validateReport();
        (void)pipeline.configDescription();
        (void)pipeline.linearRec709ColorSpace();
        exercise(pipeline);
    } catch (const pacifica::color::ColorError&) {
    }
    return 0;
}
