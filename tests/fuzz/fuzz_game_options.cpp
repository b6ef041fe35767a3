// libFuzzer target: pacifica-game's command line (game/Options.cpp). The input is split at newlines into
// arguments after "pacifica-game". Any argument list must end in Options within the documented ranges or in a
// UsageError naming the option: any other exception (a conversion CLI11 lets through, std::out_of_range) or
// an out-of-range value that parses is a finding (abort).
#include "FuzzArguments.h"
#include "Options.h"

#include <ocean/Presets.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace {

void require(bool ok, const char* what) {
    if (!ok) {
        std::fprintf(stderr, "game options: parsed but out of range: %s\n", what);
        std::abort();
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace pacifica;
    std::vector<std::string> args{"pacifica-game"};
    for (std::string& a : fuzz::splitArguments(data, size))
        args.push_back(std::move(a));
    std::vector<char*> argv;
    for (std::string& a : args)
        argv.push_back(a.data());
    argv.push_back(nullptr);
    try {
        const game::Options o = game::parseOptions(static_cast<int>(args.size()), argv.data());
        if (o.help)
            return 0;
        require(o.frames >= 0, "--frames");
        require(std::isfinite(o.fps) && o.fps >= 1.0 && o.fps <= 1000.0, "--fps");
        require(std::isfinite(o.sea.windSpeed) && o.sea.windSpeed >= 2.0 && o.sea.windSpeed <= 25.0,
                "--wind");
        require(std::isfinite(o.wipePosition) && o.wipePosition >= 0.0 && o.wipePosition <= 1.0,
                "--wipe-position");
        require(o.width >= 64 && o.width <= 8192 && o.height >= 64 && o.height <= 8192, "--size");
        for (const auto& [t, file] : o.screenshots)
            require(std::isfinite(t) && t >= 0.0 && !file.empty(), "--screenshot");
        (void)ocean::parseQuality(o.sea.quality); // throws (a finding) if an unknown preset got through
        (void)game::parseSurfaceModelIndex(o.sea.model);
        require(!o.headless || o.frames > 0, "--headless without --frames");
    } catch (const game::UsageError&) {
    }
    return 0;
}
