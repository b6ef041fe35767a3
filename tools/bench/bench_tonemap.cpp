// pacifica-bench-tonemap: what the display transforms of `pacifica tonemap compare` cost per frame on the GPU
// (OCIO's GLSL through color::Tonemapper, LUT textures included) and through OCIO's CPU processor, for the
// six shipped tonemappers (generated OCIO config) and the embedded config's two sRGB views: 8 transforms x
// --frames frames at --size on the GPU, --cpu-frames frames on the CPU. The frame is the test chart
// (tonemap/Metrics.h) stretched to the size, scene-linear up to 2550. Clock: steady_clock wall time around
// each pass followed by glFinish (GL timer queries are wrong on llvmpipe); medians per transform.
// No OIIO, so it runs on the GPU benchmark machine. Writes DIR/tonemap_bench.{json,md}.
//
//   pacifica-bench-tonemap --out DIR [--frames 60] [--cpu-frames 5] [--size 1920x1080]
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
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pacifica::median;
using pacifica::color::ColorPipeline;
namespace tmap = pacifica::tonemap;

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

int main(int argc, char** argv) {
    fs::path outDir;
    int frames = 60, cpuFrames = 5, width = 1920, height = 1080;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--out" && i + 1 < argc)
            outDir = argv[++i];
        else if (a == "--frames" && i + 1 < argc)
            frames = std::atoi(argv[++i]);
        else if (a == "--cpu-frames" && i + 1 < argc)
            cpuFrames = std::atoi(argv[++i]);
        else if (a == "--size" && i + 1 < argc) {
            if (std::sscanf(argv[++i], "%dx%d", &width, &height) != 2)
                width = height = 0;
        } else {
            std::fprintf(stderr, "usage: pacifica-bench-tonemap --out DIR [--frames 60] [--cpu-frames 5] "
                                 "[--size 1920x1080]\n");
            return 2;
        }
    }
    if (outDir.empty() || frames < 1 || cpuFrames < 1 || width < 16 || height < 16 || width > 16384 ||
        height > 16384) {
        std::fprintf(stderr,
                     "pacifica-bench-tonemap: error: --out DIR is required; --frames and --cpu-frames "
                     ">= 1; --size WxH between 16 and 16384\n");
        return 2;
    }
    try {
        fs::create_directories(outDir);
        // The frame: the chart stretched (nearest) to the size.
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

        struct Entry {
            std::string label;
            ColorPipeline pipeline;
        };
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

        auto context = pacifica::gl::createHeadlessContext();
        const std::string renderer = context->info().renderer;
        namespace gl = pacifica::gl;
        gl::Texture scene = gl::Texture::create2D(GL_RGBA32F, width, height);
        glTextureSubImage2D(scene.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba.data());
        gl::Texture target = gl::Texture::create2D(GL_RGBA8, width, height); // a display framebuffer
        gl::Framebuffer fbo = gl::Framebuffer::create();
        fbo.attachColor(0, target);
        fbo.checkComplete("tonemap bench target");

        nlohmann::json rows = nlohmann::json::array();
        double gpuTotal = 0.0, cpuTotal = 0.0;
        for (Entry& e : entries) {
            auto t0 = std::chrono::steady_clock::now();
            pacifica::color::Tonemapper pass(e.pipeline);
            glFinish();
            const double buildMs = msSince(t0);
            for (int w = 0; w < 2; ++w) // warm-up: first use compiles and uploads lazily on some drivers
                pass.run(scene, fbo, width, height);
            glFinish();
            std::vector<double> gpu;
            for (int f = 0; f < frames; ++f) {
                t0 = std::chrono::steady_clock::now();
                pass.run(scene, fbo, width, height);
                glFinish();
                gpu.push_back(msSince(t0));
            }
            std::vector<double> cpu;
            std::vector<float> work(rgba.size());
            for (int f = 0; f < cpuFrames; ++f) {
                std::copy(rgba.begin(), rgba.end(), work.begin());
                t0 = std::chrono::steady_clock::now();
                e.pipeline.applyCpu(work.data(), work.size() / 4);
                cpu.push_back(msSince(t0));
            }
            const double gpuMs = median(gpu), cpuMs = median(cpu);
            gpuTotal += gpuMs * frames;
            cpuTotal += cpuMs * frames;
            rows.push_back({{"transform", e.label},
                            {"gpu_ms_per_frame_median", gpuMs},
                            {"cpu_ms_per_frame_median", cpuMs},
                            {"cpu_over_gpu", cpuMs / gpuMs},
                            {"gpu_pass_build_ms", buildMs}});
            std::fprintf(stderr, "%-62s GPU %8.2f ms  CPU %8.2f ms\n", e.label.c_str(), gpuMs, cpuMs);
        }
        nlohmann::json report = {{"gl_renderer", renderer},
                                 {"clock", "steady_clock wall time around each pass + glFinish; CPU: around "
                                           "OCIO CPUProcessor::apply, one thread"},
                                 {"width", width},
                                 {"height", height},
                                 {"gpu_frames", frames},
                                 {"cpu_frames", cpuFrames},
                                 {"transforms", rows},
                                 {"gpu_total_s_all_transforms", gpuTotal / 1000.0},
                                 {"cpu_total_s_all_transforms_extrapolated", cpuTotal / 1000.0}};
        std::ofstream(outDir / "tonemap_bench.json") << report.dump(2) << "\n";
        std::ofstream md(outDir / "tonemap_bench.md");
        md << "GL_RENDERER " << renderer << ", " << width << "x" << height << ", GPU: median of " << frames
           << " frames, CPU: median of " << cpuFrames << " (steady_clock; glFinish after each GPU pass)\n\n"
           << "| transform | GPU ms/frame | OCIO CPU ms/frame | CPU / GPU |\n|---|---|---|---|\n";
        for (const auto& r : rows) {
            char b[160];
            std::snprintf(b, sizeof b, "| %s | %.2f | %.1f | %.1f |\n",
                          r["transform"].get<std::string>().c_str(),
                          r["gpu_ms_per_frame_median"].get<double>(),
                          r["cpu_ms_per_frame_median"].get<double>(), r["cpu_over_gpu"].get<double>());
            md << b;
        }
        char b[200];
        std::snprintf(b, sizeof b, "\n%zu transforms x %d frames: GPU %.2f s, CPU (extrapolated) %.1f s\n",
                      entries.size(), frames, gpuTotal / 1000.0, cpuTotal / 1000.0);
        md << b;
        std::fputs(b, stderr);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica-bench-tonemap: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
