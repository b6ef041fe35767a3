// BenchMain: the GL benches' main once their command line is parsed: the output folder made (the named
// stale files removed from it: a plot left by an earlier run must not pass for this one's), a headless GL
// context, then the bench itself. One way to end for all of them: "NAME: no GL context: WHY" and exit 2
// when no context can be made (no GPU device, no EGL driver), "NAME: error: WHY" and exit 1 on any other
// failure, else the bench's own exit code. Header-only.
#pragma once

#include "engine/gl/GlContext.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <memory>

namespace pacifica::bench {

/// Runs `bench(context)` (returning the exit code) as the header says. `desc`: the context's (no debug
/// context by default: its callbacks cost time in the timed frames).
template <class Bench>
int runGlBench(const char* name, const std::filesystem::path& outDir,
               std::initializer_list<const char*> stale, Bench&& bench,
               const gl::ContextDesc& desc = {.debug = false}) {
    try {
        std::filesystem::create_directories(outDir);
        for (const char* file : stale)
            std::filesystem::remove(outDir / file);
        const std::unique_ptr<gl::GlContext> context = gl::createHeadlessContext(desc);
        return bench(*context);
    } catch (const gl::ContextError& e) {
        std::fprintf(stderr, "%s: no GL context: %s\n", name, e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: error: %s\n", name, e.what());
        return 1;
    }
}

} // namespace pacifica::bench
