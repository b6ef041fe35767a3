// pacifica-bench-frame: what a whole ocean frame costs per quality preset and screen size, and where the
// time goes (docs/PERFORMANCE.md). For each setting it renders the same view (the performance issue's:
// 20 m above the sea, 60 degree vertical field of view, looking toward the horizon) with two renderers:
//   - timed: OceanRenderer::render inside the engine's GpuTimer (GL_TIME_ELAPSED on hardware, wall clock
//     around glFinish on llvmpipe): the frame time, nothing added;
//   - profiled: the same with OceanRenderer::setPassTiming (GL_TIMESTAMP between passes on hardware, a
//     glFinish between passes on llvmpipe): the per-pass split (compute, sky, sea, effects).
// Settings: the presets low, medium, high, each preset with the other shading path
// (OceanDesc::computeShading), and the high preset with one knob changed at a time (sky off, vertex filter,
// lighting octaves, displaced octaves, grid density, culling) — the cost of each feature is the difference to
// high. Settings are interleaved frame by frame (round robin) so a shared machine's load hits them alike;
// figures are medians (and p90) over the timed frames. No OpenImageIO: it runs on the NVIDIA H100 benchmark
// machine too.
#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "ocean/Lighting.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanHost.h"
#include "ocean/Presets.h"
#include "ocean/SeaState.h"

#include "BenchCli.h"
#include "BenchMain.h"
#include "BenchText.h"

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

using namespace pacifica;

namespace {

using bench::csvQuote;
using bench::num;
using bench::parseSize;
using bench::utcNow;

constexpr double T0 = 100.0;            // simulation time of the first frame, s
constexpr double FRAME_DT = 1.0 / 60.0; // simulation time between frames, s
constexpr double FOV_Y_DEG = 60.0;
constexpr int WARMUP_FRAMES = 2; // first use compiles shaders, uploads the grid, JITs on llvmpipe
// The performance issue's view: 20 m up, toward the horizon (pitch -3 degrees), away from the origin so the
// camera-relative float path is exercised as in a game.
constexpr glm::dvec3 CAMERA{2000.0, -1500.0, 20.0};
constexpr double HEADING_DEG = 70.0, PITCH_DEG = -3.0;

double quantile(std::vector<double> v, double q) {
    if (v.empty())
        return 0.0;
    std::sort(v.begin(), v.end());
    const double pos = q * static_cast<double>(v.size() - 1);
    const size_t i = static_cast<size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v[i];
}

struct Setting {
    std::string name, knob;
    ocean::OceanDesc desc;
    // The view: the benchmark's standard view, unless a row names another.
    glm::dvec3 camera = CAMERA;
    double headingDeg = HEADING_DEG, pitchDeg = PITCH_DEG;
    /// Asynchronous GPU height queries queued before every timed frame (OceanRenderer::queueHeights), the
    /// previous frames' answers taken after it: the cost of the query pass.
    size_t gpuQueries = 0;
    std::vector<ocean::SpotLight> spots; ///< SpotLight components in the scene
};

/// Adds one row of the high preset changed by `change`.
using AddHighRow = std::function<void(const std::string&, const std::string&,
                                      const std::function<void(ocean::OceanDesc&)>&)>;

/// The FFT sea's rows: its cascades and their variants (docs/LOOK.md, "The FFT sea").
void fftSettings(const AddHighRow& high) {
    auto fft = [&](const std::string& name, const std::string& knob,
                   const std::function<void(ocean::OceanDesc&)>& change) {
        high(name, knob, [change](ocean::OceanDesc& d) {
            d.model = ocean::SurfaceKind::Fft;
            change(d);
        });
    };
    fft("high/fft", "FFT sea: 4 cascades (256^2, 3 x 128^2), 2 draws each, living whitecaps",
        [](ocean::OceanDesc&) {});
    fft("high/fft-sea-state-9", "the FFT sea under applySeaState at U10 = 9 m/s", [](ocean::OceanDesc& d) {
        d = ocean::applySeaState(d, {9.0, d.fft.windDirectionDeg});
    });
    fft("high/fft-sea-state-16", "the FFT sea under applySeaState at U10 = 16 m/s: ~5 % whitecaps",
        [](ocean::OceanDesc& d) {
            d = ocean::applySeaState(d, {16.0, d.fft.windDirectionDeg});
        });
    fft("high/fft-no-mix", "FFT cascades with one draw each (FftDesc::aperiodic off)",
        [](ocean::OceanDesc& d) { d.fft.aperiodic = false; });
    fft("high/fft-detail-64", "FFT cascades 1-3 of 64^2 (FftDesc::detailSize 128 -> 64)",
        [](ocean::OceanDesc& d) { d.fft.detailSize = 64; });
    fft("high/fft-128-64", "FFT cascade 0 of 128^2, cascades 1-3 of 64^2", [](ocean::OceanDesc& d) {
        d.fft.size = 128;
        d.fft.detailSize = 64;
    });
    fft("high/fft-one-tile", "one 500 m FFT tile, no mix (the FFT sea before its cascades)",
        [](ocean::OceanDesc& d) {
            d.fft.cascades = 1;
            d.fft.aperiodic = false;
            d.fft.tileSize = 500.0;
        });
}

/// Adds a setting: the high preset with one change.
using AddHighRow = std::function<void(const std::string&, const std::string&,
                                      const std::function<void(ocean::OceanDesc&)>&)>;

/// The high preset's geometry knobs: sky pass, vertex filters, octaves, grid, culling, hidden rings, and
/// the view from 3 km where the inner rings out to 3.5 km are off screen (what leaving them out saves where a
/// flight sim spends its time).
void geometrySettings(const AddHighRow& high, std::vector<Setting>& out) {
    using ocean::Quality;
    high("high/no-sky", "sky pass off", [](ocean::OceanDesc& d) { d.drawSky = false; });
    high("high/vertex-nearest", "vertex filter nearest (1 fetch/octave/slice)",
         [](ocean::OceanDesc& d) { d.octaves.vertexFilter = ocean::VertexFilter::Nearest; });
    high("high/vertex-bilinear", "vertex filter bilinear (4 fetches)",
         [](ocean::OceanDesc& d) { d.octaves.vertexFilter = ocean::VertexFilter::Bilinear; });
    high("high/vertex-packed4tap", "vertex filter packed 4-tap (1 fetch, listing 18-2)",
         [](ocean::OceanDesc& d) { d.octaves.vertexFilter = ocean::VertexFilter::Packed4Tap; });
    high("high/lighting-3", "lighting octaves 5 -> 3 (fragment fetches)",
         [](ocean::OceanDesc& d) { d.octaves.octaves.resize(3); });
    high("high/displaced-1", "displaced octaves 3 -> 1 (vertex fetches)",
         [](ocean::OceanDesc& d) { d.octaves.displacedOctaves = 1; });
    high("high/grid-128x256", "grid 256x512 -> 128x256 (vertices, triangles)", [](ocean::OceanDesc& d) {
        d.grid.rings = 128;
        d.grid.segments = 256;
    });
    high("high/no-cull", "per-vertex frustum test off", [](ocean::OceanDesc& d) { d.cullVertices = false; });
    high("high/draw-hidden-rings", "inner rings outside the frustum drawn (OceanDesc::skipHiddenRings off)",
         [](ocean::OceanDesc& d) { d.skipHiddenRings = false; });
    // From altitude (3 km, 10 degrees down) the inner rings out to 3.5 km are off screen: what leaving them
    // out saves where a flight sim spends its time.
    for (bool skip : {true, false}) {
        Setting s{skip ? "high/3km" : "high/3km-draw-hidden-rings",
                  skip ? "the view from 3 km, 10 deg down" : "the view from 3 km, inner rings drawn",
                  ocean::oceanPreset(Quality::High)};
        s.desc.skipHiddenRings = skip;
        s.camera = {2000.0, -1500.0, 3000.0};
        s.pitchDeg = -10.0;
        out.push_back(s);
    }
}

/// Look knobs: what each addition costs in the frame.
void lookSettings(const AddHighRow& high) {
    high("high/glitter-blinn-phong",
         "the Blinn-Phong lobe instead of Cox-Munk glitter (LightingDesc::glitter)",
         [](ocean::OceanDesc& d) { d.lighting.glitter = ocean::LightingDesc::Glitter::BlinnPhong; });
    high("high/sky-gradient", "the gradient sky instead of the physical clear sky (LightingDesc::sky)",
         [](ocean::OceanDesc& d) { d.lighting.sky = ocean::LightingDesc::Sky::Gradient; });
    // The near sea: a sea state gives the octave sea its detail octaves (down to 16 cm) carrying 80 % of
    // Cox & Munk's slopes (ocean/SeaState.h), 7 lighting octaves instead of 5.
    high("high/sea-state-9", "applySeaState at U10 = 9 m/s: detail octaves and resolved glints",
         [](ocean::OceanDesc& d) {
             d = ocean::applySeaState(d, {9.0, d.octaves.windDirectionDeg});
         });
    high("high/sea-state-9-no-octave-mix",
         "the near sea without the lighting octaves' aperiodic mix (HeightOctavesDesc::aperiodic off)",
         [](ocean::OceanDesc& d) {
             d.octaves.aperiodic = false;
             d = ocean::applySeaState(d, {9.0, d.octaves.windDirectionDeg});
         });
    // Whitecaps: a strong sea (~5 % foam, Monahan) with and without its foam (ocean.frag foamCover).
    high("high/sea-state-16", "applySeaState at U10 = 16 m/s: ~5 % whitecaps", [](ocean::OceanDesc& d) {
        d = ocean::applySeaState(d, {16.0, d.octaves.windDirectionDeg});
    });
    high("high/sea-state-16-no-foam", "the 16 m/s sea without foam (LightingDesc::foamIntensity 0)",
         [](ocean::OceanDesc& d) {
             d = ocean::applySeaState(d, {16.0, d.octaves.windDirectionDeg});
             d.lighting.foamIntensity = 0.0f;
         });
    high("high/no-octave-mix", "the high preset without the lighting octaves' aperiodic mix",
         [](ocean::OceanDesc& d) { d.octaves.aperiodic = false; });
}

/// The other surface models with and without their living whitecaps.
void modelSettings(const AddHighRow& high) {
    high("high/gerstner", "Gerstner sum (8 waves) with its living whitecaps",
         [](ocean::OceanDesc& d) { d.model = ocean::SurfaceKind::Gerstner; });
    high("high/gerstner-no-foam-memory",
         "Gerstner sum without living whitecaps (GerstnerDesc::foamMemory off)", [](ocean::OceanDesc& d) {
             d.model = ocean::SurfaceKind::Gerstner;
             d.gerstner.foamMemory = false;
         });
    high("high/fft-no-foam-memory", "FFT sea without living whitecaps (FftDesc::foamMemory off)",
         [](ocean::OceanDesc& d) {
             d.model = ocean::SurfaceKind::Fft;
             d.fft.foamMemory = false;
         });
}

/// Each preset with the other shading path (OceanDesc::computeShading), and compute shading by tiles
/// (OceanDesc::shadeTiles): the other side of Auto on this renderer, each preset.
void shadingSettings(std::vector<Setting>& out) {
    using ocean::Quality;
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High}) {
        ocean::OceanDesc d = ocean::oceanPreset(q);
        d.computeShading = !d.computeShading;
        out.push_back(
            {std::string(ocean::toString(q)) + (d.computeShading ? "/compute-shading" : "/forward-shading"),
             d.computeShading ? "lit in one compute pass (OceanDesc::computeShading)"
                              : "lit in the grids' fragment stage",
             d});
    }
    // Compute shading by tiles (OceanDesc::shadeTiles): the other side of Auto on this renderer, each preset,
    // and from 3 km up (more sky, and sea beyond the grid).
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High}) {
        for (auto tiles : {ocean::OceanDesc::ShadeTiles::Off, ocean::OceanDesc::ShadeTiles::On}) {
            Setting s{std::string(ocean::toString(q)) +
                          (tiles == ocean::OceanDesc::ShadeTiles::On ? "/shade-tiles" : "/shade-untiled"),
                      tiles == ocean::OceanDesc::ShadeTiles::On
                          ? "compute shading sorted into tiles (OceanDesc::shadeTiles On)"
                          : "compute shading in one program (OceanDesc::shadeTiles Off)",
                      ocean::oceanPreset(q)};
            s.desc.shadeTiles = tiles;
            out.push_back(s);
        }
    }
}

/// Spot lights (Lighting.h SpotLight) in a foggy night's fog (1e-3/m, ~4 km visibility): eight ships'
/// searchlights 150..780 m ahead, 15 m up, four sweeping the sea and four raised into the fog; their beams
/// with 4, 8 (the default) and 16 points (LightingDesc::spotScatterSamples) and none; and the same fog
/// without lamps. The rows' differences are the lamps' cost on the sea and their beams'.
void spotSettings(std::vector<Setting>& out) {
    const double heading = HEADING_DEG * std::numbers::pi / 180.0;
    const glm::dvec2 ahead(std::sin(heading), std::cos(heading)), right(ahead.y, -ahead.x);
    std::vector<ocean::SpotLight> lamps;
    for (int i = 0; i < ocean::MAX_SPOT_LIGHTS; ++i) {
        ocean::SpotLight s;
        const double along = 150.0 + 90.0 * i, side = (i % 2 ? 1.0 : -1.0) * (40.0 + 15.0 * i);
        s.position = glm::dvec3(glm::dvec2(CAMERA) + ahead * along + right * side, 15.0);
        const double yaw = (i % 4 - 1.5) * 0.35,
                     elevation = (i % 2 ? -12.0 : 15.0) * std::numbers::pi / 180.0;
        const glm::dvec2 h = ahead * std::cos(yaw) + right * std::sin(yaw);
        s.direction = glm::dvec3(h * std::cos(elevation), std::sin(elevation));
        s.frustumDeg = 6.0;
        s.range = 3000.0;
        lamps.push_back(s);
    }
    auto row = [&](const std::string& name, const std::string& knob, int samples, bool withLamps) {
        Setting st{name, knob, ocean::oceanPreset(ocean::Quality::High)};
        st.desc.lighting.fogDensity = 1e-3f;
        st.desc.lighting.spotScatterSamples = samples;
        if (withLamps)
            st.spots = lamps;
        out.push_back(st);
    };
    row("high/fog-1e-3", "the high preset in a 1e-3/m fog (the spot rows' baseline)", 8, false);
    row("high/spots-8-no-beams", "8 spot lights on the sea, no beams (LightingDesc::spotScatterSamples 0)", 0,
        true);
    row("high/spots-8-beams-4", "8 spot lights with their beams in the fog, 4 points per beam", 4, true);
    row("high/spots-8", "8 spot lights with their beams in the fog, 8 points per beam (the default)", 8,
        true);
    row("high/spots-8-beams-16", "8 spot lights with their beams in the fog, 16 points per beam", 16, true);
}

std::vector<Setting> settings(bool quick) {
    using ocean::Quality;
    std::vector<Setting> out;
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High})
        out.push_back({ocean::toString(q), "preset", ocean::oceanPreset(q)});
    if (quick)
        return out;
    const AddHighRow high = [&](const std::string& name, const std::string& knob,
                                const std::function<void(ocean::OceanDesc&)>& change) {
        ocean::OceanDesc d = ocean::oceanPreset(Quality::High);
        change(d);
        out.push_back({name, knob, d});
    };
    geometrySettings(high, out);
    lookSettings(high);
    fftSettings(high);
    modelSettings(high);
    shadingSettings(out);
    spotSettings(out);
    for (const auto& [name, model] :
         {std::pair{"high/gpu-queries-100k", ocean::SurfaceKind::Octaves},
          std::pair{"high/gerstner-gpu-queries-100k", ocean::SurfaceKind::Gerstner},
          std::pair{"high/fft-gpu-queries-100k", ocean::SurfaceKind::Fft}}) {
        ocean::OceanDesc d = ocean::oceanPreset(Quality::High);
        d.model = model;
        Setting s{name, "100 000 asynchronous GPU height queries a frame (OceanRenderer::queueHeights)", d};
        s.gpuQueries = 100000;
        out.push_back(s);
    }
    return out;
}

struct Scene {
    Setting setting;
    ecs::Registry registry;
    ocean::OceanRenderer timed, profiled;
    // Its own timer: on hardware results arrive frames later, and one timer shared by the round robin
    // would hand a scene another scene's span.
    gl::GpuTimer timer;
    std::vector<double> compute, sky, sea, effects, shade;
    size_t warmupSpans = 0; // the timer's first spans belong to the warm-up frames
    ocean::OceanStats stats;
    ecs::Entity entity;
    std::vector<glm::dvec2> queryPoints; // Setting::gpuQueries points within 2 km of the camera
    std::vector<double> queryHeights;
    std::vector<std::uint64_t> tickets; // queued, not yet taken

    Scene(Setting s, gl::GpuTimer::Clock clock) : setting(std::move(s)), timer(clock) {
        entity = registry.create();
        registry.emplace<ocean::OceanComponent>(entity, ocean::makeOcean(setting.desc));
        for (const ocean::SpotLight& spot : setting.spots)
            registry.emplace<ocean::SpotLight>(registry.create(), spot);
        profiled.setPassTiming(ocean::passClock(clock));
        // A square grid over +-2 km around the camera, row by row (neighbours in the buffer are neighbours on
        // the sea, as a fleet's hull points are).
        const auto side = static_cast<size_t>(std::ceil(std::sqrt(static_cast<double>(setting.gpuQueries))));
        for (size_t i = 0; i < setting.gpuQueries; ++i) {
            const glm::dvec2 cell(static_cast<double>(i % side), static_cast<double>(i / side));
            queryPoints.push_back(glm::dvec2(setting.camera) + (cell + 0.5) * (4000.0 / side) - 2000.0);
        }
        queryHeights.resize(queryPoints.size());
    }

    /// Takes every answer ready (no wait), then queues this frame's points.
    void queueQueries() {
        if (queryPoints.empty())
            return;
        std::erase_if(tickets, [&](std::uint64_t t) {
            bool ready = false;
            const ocean::Status s = timed.takeHeights(t, queryHeights, ready);
            return !s || ready; // taken, or dropped from the ring
        });
        std::uint64_t ticket = 0;
        if (const ocean::Status s = timed.queueHeights(ocean::oceanId(entity), queryPoints, ticket); !s)
            throw std::runtime_error("bench: queueHeights: " + s.message);
        tickets.push_back(ticket);
    }

    ocean::OceanFrame frameAt(double t, const gl::FrameTargets& targets) const {
        Pose pose;
        pose.position = setting.camera;
        pose.headingDeg = setting.headingDeg;
        pose.pitchDeg = setting.pitchDeg;
        return ocean::makeOceanFrame(pose, static_cast<float>(FOV_Y_DEG * std::numbers::pi / 180.0),
                                     targets.width(), targets.height(), t, targets.sceneFramebuffer().id());
    }

    void frame(const gl::FrameTargets& targets, double t, bool record) {
        const ocean::OceanFrame f = frameAt(t, targets);
        if (!record)
            ++warmupSpans;
        queueQueries();
        timer.begin();
        render(timed, registry, f);
        timer.end();
        stats = timed.lastStats();
        render(profiled, registry, f);
        const ocean::OceanPassTimes& p = profiled.lastStats().passTimes;
        if (record && p.measured) {
            compute.push_back(p.computeMs);
            sky.push_back(p.skyMs);
            sea.push_back(p.seaMs);
            effects.push_back(p.effectsMs);
            shade.push_back(p.shadeMs);
        }
    }
};

struct Row {
    std::string setting, knob;
    int width = 0, height = 0;
    double ms = 0, p90 = 0, compute = 0, sky = 0, sea = 0, effects = 0, shade = 0;
    long long vertices = 0;
    int passes = 0, draws = 0, samples = 0;
    bool shadeTiled = false; // lit by tiles (OceanDesc::shadeTiles)
};

struct Args {
    std::string outDir;
    std::vector<std::pair<int, int>> sizes;
    std::optional<int> frames;
    bool quick = false;
    std::vector<std::string> only; // just these settings
    std::string commandLine;
};

std::optional<int> parseArgs(int argc, char** argv, Args& a) {
    CLI::App app(
        "Frame time per quality preset and size, and the per-pass split (docs/PERFORMANCE.md). Default "
        "sizes: 640x360 and 1280x720 on a software renderer, 1920x1080 on hardware; default frames 15 "
        "(llvmpipe) / 120 (hardware).",
        "pacifica-bench-frame");
    app.add_option("--out", a.outDir, "report directory (frame.csv, frame.md, frame.json)")->required();
    std::vector<std::string> sizes;
    app.add_option("--size", sizes, "frame size WxH (repeat for several)")->check(bench::sizeValidator());
    app.add_option("--frames", a.frames, "timed frames per setting")->check(CLI::Range(1, 10000));
    app.add_flag("--quick", a.quick, "the presets at 160x90, 3 frames");
    app.add_option("--only", a.only, "just the named settings (rows of a full run: low, high/no-sky, ...)")
        ->delimiter(',');
    if (const auto code = bench::parseCommandLine(app, argc, argv))
        return code;
    for (const std::string& s : sizes)
        a.sizes.push_back(*parseSize(s));
    a.commandLine = bench::commandLine(argc, argv);
    return std::nullopt;
}

/// The scene's timed frames as a report row.
Row rowOf(Scene& scene, int width, int height) {
    scene.timer.drain(); // every span in order, the warm-up frames' first
    const std::vector<double>& all = scene.timer.samples();
    const std::vector<double> ms(all.begin() + static_cast<long>(std::min(scene.warmupSpans, all.size())),
                                 all.end());
    Row r;
    r.setting = scene.setting.name;
    r.knob = scene.setting.knob;
    r.width = width;
    r.height = height;
    r.ms = quantile(ms, 0.5);
    r.p90 = quantile(ms, 0.9);
    r.compute = quantile(scene.compute, 0.5);
    r.sky = quantile(scene.sky, 0.5);
    r.sea = quantile(scene.sea, 0.5);
    r.effects = quantile(scene.effects, 0.5);
    r.shade = quantile(scene.shade, 0.5);
    r.vertices = scene.stats.vertices;
    r.passes = scene.stats.passes;
    r.draws = scene.stats.draws;
    r.shadeTiled = scene.stats.shadeTiled;
    r.samples = static_cast<int>(ms.size());
    if (r.samples == 0 || !(r.ms > 0.0))
        throw std::runtime_error("setting " + r.setting + ": no frame time measured");
    return r;
}

/// What the reports say of the run besides its rows.
struct RunInfo {
    std::string renderer, clock, passClock, date, commandLine;
    int frames = 0;
};

/// Every selected setting at one size: warm-up frames, then round robin (the starting scene rotating from
/// round to round) so a shared machine's load hits them alike. Appends one row per setting.
void runSize(const Args& a, int width, int height, gl::GpuTimer& timer, RunInfo& info,
             std::vector<Row>& rows) {
    std::fprintf(stderr, "pacifica-bench-frame: GL_RENDERER %s; clock: %s; %dx%d, %d frames per setting\n",
                 info.renderer.c_str(), timer.clockName(), width, height, info.frames);
    gl::FrameTargets targets(width, height);
    std::vector<std::unique_ptr<Scene>> scenes;
    for (Setting& s : settings(a.quick))
        if (a.only.empty() || std::find(a.only.begin(), a.only.end(), s.name) != a.only.end())
            scenes.push_back(std::make_unique<Scene>(std::move(s), timer.clock()));
    if (scenes.empty())
        throw CLI::ValidationError("--only",
                                   "names no setting (the names are the rows of a full run, e.g. low, "
                                   "high/no-sky)");
    info.passClock = scenes.front()->profiled.passTimingClock();
    double t = T0;
    for (int i = 0; i < WARMUP_FRAMES; ++i, t += FRAME_DT)
        for (auto& scene : scenes)
            scene->frame(targets, t, false);
    for (int f = 0; f < info.frames; ++f, t += FRAME_DT)
        for (size_t k = 0; k < scenes.size(); ++k)
            scenes[(k + static_cast<size_t>(f)) % scenes.size()]->frame(targets, t, true);
    for (auto& scene : scenes) {
        const Row r = rowOf(*scene, width, height);
        rows.push_back(r);
        std::fprintf(stderr,
                     "  %-22s %8.3f ms (p90 %8.3f)  sky %7.3f  sea %8.3f  shade %7.3f  compute %6.3f\n",
                     r.setting.c_str(), r.ms, r.p90, r.sky, r.sea, r.shade, r.compute);
    }
}

std::string csvReport(const std::vector<Row>& rows, const RunInfo& info) {
    std::ostringstream csv;
    csv << "setting,knob,width,height,ms_median,ms_p90,samples,compute_ms,sky_ms,sea_ms,effects_ms,"
           "shade_ms,vertices,passes,draws,shade_tiled,clock,pass_clock,renderer\n";
    for (const Row& r : rows)
        csv << r.setting << "," << csvQuote(r.knob) << "," << r.width << "," << r.height << "," << num(r.ms)
            << "," << num(r.p90) << "," << r.samples << "," << num(r.compute) << "," << num(r.sky) << ","
            << num(r.sea) << "," << num(r.effects) << "," << num(r.shade) << "," << r.vertices << ","
            << r.passes << "," << r.draws << "," << (r.shadeTiled ? 1 : 0) << "," << csvQuote(info.clock)
            << "," << csvQuote(info.passClock) << "," << csvQuote(info.renderer) << "\n";
    return csv.str();
}

std::string markdownReport(const std::vector<Row>& rows, const RunInfo& info) {
    std::ostringstream md;
    md << "# Ocean frame cost per preset (pacifica-bench-frame)\n\n"
       << "- GL_RENDERER: " << info.renderer << "\n- frame clock: " << info.clock
       << "\n- pass clock: " << info.passClock << " (a separate renderer, same frames)\n- date: " << info.date
       << "\n- command: `" << info.commandLine << "`\n- view: 20 m up, pitch " << PITCH_DEG
       << " deg (rows high/3km*: 3 km up, pitch -10 deg), vertical fov " << FOV_Y_DEG
       << " deg; median (p90) of " << info.frames << " frames per setting, round robin\n\n"
       << "| setting | size | ms median | p90 | sky | sea | shade | compute | vertices | vs high |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows) {
        double high = 0.0;
        for (const Row& h : rows)
            if (h.setting == "high" && h.width == r.width && h.height == r.height)
                high = h.ms;
        md << "| " << r.setting << " | " << r.width << "x" << r.height << " | " << num(r.ms, 4) << " | "
           << num(r.p90, 4) << " | " << num(r.sky, 3) << " | " << num(r.sea, 4) << " | " << num(r.shade, 3)
           << " | " << num(r.compute, 3) << " | " << r.vertices << " | "
           << (high > 0 ? num(r.ms / high, 3) : "-") << " |\n";
    }
    return md.str();
}

std::string jsonReport(const std::vector<Row>& rows, const RunInfo& info) {
    nlohmann::json js;
    js["renderer"] = info.renderer;
    js["clock"] = info.clock;
    js["pass_clock"] = info.passClock;
    js["date"] = info.date;
    js["command"] = info.commandLine;
    js["frames"] = info.frames;
    for (const Row& r : rows)
        js["rows"].push_back({{"setting", r.setting},
                              {"knob", r.knob},
                              {"width", r.width},
                              {"height", r.height},
                              {"ms_median", r.ms},
                              {"ms_p90", r.p90},
                              {"samples", r.samples},
                              {"compute_ms", r.compute},
                              {"sky_ms", r.sky},
                              {"sea_ms", r.sea},
                              {"effects_ms", r.effects},
                              {"shade_ms", r.shade},
                              {"vertices", r.vertices},
                              {"passes", r.passes},
                              {"draws", r.draws},
                              {"shade_tiled", r.shadeTiled}});
    return js.dump(2) + "\n";
}

} // namespace

int main(int argc, char** argv) {
    Args a;
    if (const auto code = parseArgs(argc, argv, a))
        return *code;
    return bench::runGlBench("pacifica-bench-frame", a.outDir, {}, [&](gl::GlContext& context) {
        const gl::ContextInfo& gl = context.info();
        gl::GpuTimer timer(gl);
        std::vector<std::pair<int, int>> sizes = a.sizes;
        if (sizes.empty())
            sizes = a.quick ? std::vector<std::pair<int, int>>{{160, 90}}
                            : (gl.software ? std::vector<std::pair<int, int>>{{640, 360}, {1280, 720}}
                                           : std::vector<std::pair<int, int>>{{1920, 1080}});
        RunInfo info{
            gl.renderer, timer.clockName(), "",
            utcNow(),    a.commandLine,     a.frames.value_or(a.quick ? 3 : (gl.software ? 15 : 120))};
        std::vector<Row> rows;
        try {
            for (const auto& [width, height] : sizes)
                runSize(a, width, height, timer, info, rows);
        } catch (const CLI::ValidationError& e) { // --only names no setting: a usage error
            std::fprintf(stderr, "pacifica-bench-frame: error: %s\n", e.what());
            return 2;
        }
        const std::filesystem::path dir(a.outDir);
        writeFileAtomically(dir / "frame.csv", csvReport(rows, info));
        writeFileAtomically(dir / "frame.md", markdownReport(rows, info));
        writeFileAtomically(dir / "frame.json", jsonReport(rows, info));
        return 0;
    });
}
