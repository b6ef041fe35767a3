// pacifica-bench-tonemap: what the display transforms of `pacifica tonemap compare` cost per frame on the GPU
// (OCIO's GLSL through color::Tonemapper, LUT textures included) and through OCIO's CPU processor, for the
// six shipped tonemappers (generated OCIO config) and the embedded config's two sRGB views: 8 transforms x
// --frames frames at --size on the GPU, --cpu-frames frames on the CPU. The frame is the test chart
// (tonemap/Metrics.h) stretched to the size, scene-linear up to 2550. Clock: steady_clock wall time around
// each pass followed by glFinish (GL timer queries are wrong on llvmpipe); medians per transform.
// No OIIO, so it runs on the GPU benchmark machine. Writes DIR/tonemap_bench.{json,md}.
//
//   pacifica-bench-tonemap --out DIR [--frames 60] [--cpu-frames 5] [--size 1920x1080 (16..8192 each)]
#include "BenchCli.h"
#include "BenchMain.h"

#include <engine/Stats.h>
#include <engine/color/ColorPipeline.h>
#include <engine/color/Tonemapper.h>
#include <engine/gl/GlContext.h>
#include <engine/gl/GlObjects.h>
#include <tonemap/ConfigWriter.h>
#include <tonemap/Curves.h>
#include <tonemap/Metrics.h>

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace fs = std::filesystem;
using pacifica::median;
using pacifica::color::ColorPipeline;
namespace tmap = pacifica::tonemap;

namespace {

namespace gl = pacifica::gl;
namespace bench = pacifica::bench;

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

struct Args {
    fs::path outDir;
    int frames = 60, cpuFrames = 5, width = 1920, height = 1080;
};

std::optional<int> parseArgs(int argc, char** argv, Args& a) {
    CLI::App app("GPU (OCIO GLSL) and OCIO CPU cost per frame of the display transforms of `pacifica tonemap "
                 "compare` (docs/TONEMAP.md)",
                 "pacifica-bench-tonemap");
    app.add_option("--out", a.outDir, "report directory (tonemap_bench.json, tonemap_bench.md)")->required();
    app.add_option("--frames", a.frames, "GPU frames per transform")->check(CLI::Range(1, 100000));
    app.add_option("--cpu-frames", a.cpuFrames, "CPU frames per transform")->check(CLI::Range(1, 100000));
    std::string size = "1920x1080";
    app.add_option("--size", size, "frame size WxH")->check(bench::sizeValidator());
    if (const auto code = bench::parseCommandLine(app, argc, argv))
        return code;
    std::tie(a.width, a.height) = *bench::parseSize(size);
    return std::nullopt;
}

/// The frame: the test chart (scene-linear up to 2550) stretched (nearest) to width x height, RGBA.
std::vector<float> chartFrame(int width, int height) {
    const tmap::Chart chart = tmap::testChart(16);
    std::vector<float> rgba(static_cast<size_t>(width) * static_cast<size_t>(height) * 4, 1.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t s =
                (static_cast<size_t>(y * chart.height / height) * static_cast<size_t>(chart.width) +
                 static_cast<size_t>(x * chart.width / width)) *
                3;
            const size_t d =
                (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
            std::copy_n(&chart.rgb[s], 3, &rgba[d]);
        }
    return rgba;
}

struct Entry {
    std::string label;
    ColorPipeline pipeline;
};

/// The shipped tonemappers (a generated OCIO config in DIR/ocio) and the embedded config's sRGB views.
std::vector<Entry> transforms(const fs::path& outDir) {
    std::vector<Entry> entries;
    const tmap::GeneratedConfig g = tmap::writeTonemapConfig(outDir / "ocio", 33);
    const ColorPipeline shipped = ColorPipeline::fromFile(g.path);
    for (const tmap::Tonemapper& t : tmap::tonemappers()) {
        Entry e{"pacifica: " + t.name, shipped};
        e.pipeline.select(g.display, g.views.at(t.id));
        entries.push_back(std::move(e));
    }
    const ColorPipeline embedded = ColorPipeline::createDefault();
    for (const std::string& view : embedded.views("sRGB")) {
        Entry e{"embedded: sRGB / " + view, embedded};
        e.pipeline.select("sRGB", view);
        entries.push_back(std::move(e));
    }
    return entries;
}

/// One transform: its GPU pass built and warmed up, `frames` timed passes (glFinish after each), then
/// `cpuFrames` runs of OCIO's CPU processor; medians.
nlohmann::json measure(Entry& e, const Args& a, const gl::Texture& scene, const gl::Framebuffer& fbo,
                       const std::vector<float>& rgba) {
    auto t0 = std::chrono::steady_clock::now();
    pacifica::color::Tonemapper pass(e.pipeline);
    glFinish();
    const double buildMs = msSince(t0);
    for (int w = 0; w < 2; ++w) // warm-up: first use compiles and uploads lazily on some drivers
        pass.run(scene, fbo, a.width, a.height);
    glFinish();
    std::vector<double> gpu;
    for (int f = 0; f < a.frames; ++f) {
        t0 = std::chrono::steady_clock::now();
        pass.run(scene, fbo, a.width, a.height);
        glFinish();
        gpu.push_back(msSince(t0));
    }
    std::vector<double> cpu;
    std::vector<float> work(rgba.size());
    for (int f = 0; f < a.cpuFrames; ++f) {
        std::copy(rgba.begin(), rgba.end(), work.begin());
        t0 = std::chrono::steady_clock::now();
        e.pipeline.applyCpu(work.data(), work.size() / 4);
        cpu.push_back(msSince(t0));
    }
    const double gpuMs = median(gpu), cpuMs = median(cpu);
    std::fprintf(stderr, "%-62s GPU %8.2f ms  CPU %8.2f ms\n", e.label.c_str(), gpuMs, cpuMs);
    return {{"transform", e.label},
            {"gpu_ms_per_frame_median", gpuMs},
            {"cpu_ms_per_frame_median", cpuMs},
            {"cpu_over_gpu", cpuMs / gpuMs},
            {"gpu_pass_build_ms", buildMs}};
}

std::string markdownReport(const nlohmann::json& report) {
    std::ostringstream md;
    md << "GL_RENDERER " << report["gl_renderer"].get<std::string>() << ", " << report["width"].get<int>()
       << "x" << report["height"].get<int>() << ", GPU: median of " << report["gpu_frames"].get<int>()
       << " frames, CPU: median of " << report["cpu_frames"].get<int>()
       << " (steady_clock; glFinish after each GPU pass)\n\n"
       << "| transform | GPU ms/frame | OCIO CPU ms/frame | CPU / GPU |\n|---|---|---|---|\n";
    for (const auto& r : report["transforms"]) {
        char b[160];
        std::snprintf(b, sizeof b, "| %s | %.2f | %.1f | %.1f |\n", r["transform"].get<std::string>().c_str(),
                      r["gpu_ms_per_frame_median"].get<double>(), r["cpu_ms_per_frame_median"].get<double>(),
                      r["cpu_over_gpu"].get<double>());
        md << b;
    }
    return md.str();
}

} // namespace

int main(int argc, char** argv) {
    Args a;
    if (const auto code = parseArgs(argc, argv, a))
        return *code;
    const auto run = [&](gl::GlContext& context) {
        const std::vector<float> rgba = chartFrame(a.width, a.height);
        std::vector<Entry> entries = transforms(a.outDir);
        gl::Texture scene = gl::Texture::create2D(GL_RGBA32F, a.width, a.height);
        glTextureSubImage2D(scene.id(), 0, 0, 0, a.width, a.height, GL_RGBA, GL_FLOAT, rgba.data());
        gl::Texture target = gl::Texture::create2D(GL_RGBA8, a.width, a.height); // a display framebuffer
        gl::Framebuffer fbo = gl::Framebuffer::create();
        fbo.attachColor(0, target);
        fbo.checkComplete("tonemap bench target");
        nlohmann::json rows = nlohmann::json::array();
        double gpuTotal = 0.0, cpuTotal = 0.0;
        for (Entry& e : entries) {
            rows.push_back(measure(e, a, scene, fbo, rgba));
            gpuTotal += rows.back()["gpu_ms_per_frame_median"].get<double>() * a.frames;
            cpuTotal += rows.back()["cpu_ms_per_frame_median"].get<double>() * a.frames;
        }
        const nlohmann::json report = {{"gl_renderer", context.info().renderer},
                                       {"clock",
                                        "steady_clock wall time around each pass + glFinish; CPU: around "
                                        "OCIO CPUProcessor::apply, one thread"},
                                       {"width", a.width},
                                       {"height", a.height},
                                       {"gpu_frames", a.frames},
                                       {"cpu_frames", a.cpuFrames},
                                       {"transforms", rows},
                                       {"gpu_total_s_all_transforms", gpuTotal / 1000.0},
                                       {"cpu_total_s_all_transforms_extrapolated", cpuTotal / 1000.0}};
        char total[200];
        std::snprintf(total, sizeof total,
                      "\n%zu transforms x %d frames: GPU %.2f s, CPU (extrapolated) %.1f s\n", entries.size(),
                      a.frames, gpuTotal / 1000.0, cpuTotal / 1000.0);
        pacifica::writeFileAtomically(a.outDir / "tonemap_bench.json", report.dump(2) + "\n");
        pacifica::writeFileAtomically(a.outDir / "tonemap_bench.md", markdownReport(report) + total);
        std::fputs(total, stderr);
        return 0;
    };
    return bench::runGlBench("pacifica-bench-tonemap", a.outDir, {}, run, gl::ContextDesc{});
}
