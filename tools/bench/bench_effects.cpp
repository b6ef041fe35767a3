// pacifica-bench-effects: what the ocean's effects (ocean/Effects.h) cost per active effect of each kind, and
// what the frame without effects costs against the plain ocean (docs/EFFECTS_BENCH.md). Settings, each timed
// as the median (and p90) of N frames of OceanRenderer::render + glFinish with the engine's GpuTimer
// (GL_TIME_ELAPSED on hardware, wall clock around glFinish on llvmpipe), the settings interleaved frame by
// frame (round robin) so that the load of a shared machine changing during the run hits all of them alike:
//   - plain: a registry holding only the OceanComponent, no EffectsSystem at all;
//   - zero-effect: an EffectsSystem exists and update() runs every frame, but there are no effects; its
//     effect counters (passes, draws, uploads) must be 0 in every timed frame;
//   - explosions: 1, 4, 16, 64 grown explosions in view; wakes: 1, 2, 4, 8 ships with built-up trails in
//     view (parallel courses, 10 m/s).
// Per kind it reports the slope of a least-squares line through (count, ms) and (ms(N) - ms(plain)) / N,
// the CPU time of EffectsSystem::update() per frame (steady_clock) and the vertices processed (lastStats()).
// It links no OpenImageIO, so the no-OIIO build runs it on the GPU benchmark machine (NVIDIA H100).
#include "engine/Ecs.h"
#include "engine/Events.h"
#include "engine/Space.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanHost.h"

#include "BenchCli.h"
#include "BenchMain.h"
#include "BenchText.h"

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
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
constexpr int WARMUP_FRAMES = 2; // first use builds shader variants and uploads grid meshes
// The brief's camera: ~100 m up, looking down 20 degrees, heading east (+x); away from the origin so the
// camera-relative float path is exercised as in a game.
constexpr glm::dvec3 CAMERA{2000.0, -1500.0, 100.0};
constexpr double HEADING_DEG = 90.0;
constexpr double PITCH_DEG = -20.0;
// Ships: 10 m/s on parallel courses along +x; their paths are built for 120 s in 0.5 s steps first.
constexpr double SHIP_SPEED = 10.0;
constexpr double HISTORY_SECONDS = 120.0;

enum class Kind { None, Explosion, Wake, Fleet }; // Fleet: wakes and explosions together

const char* kindName(Kind k) {
    switch (k) {
    case Kind::None:
        return "none";
    case Kind::Explosion:
        return "explosion";
    case Kind::Wake:
        return "wake";
    case Kind::Fleet:
        return "fleet";
    }
    return "?";
}

constexpr double NAN_MS = std::numeric_limits<double>::quiet_NaN();

struct Row {
    std::string setting; // plain, zero_effect, explosions, wakes
    Kind kind = Kind::None;
    int count = 0;
    int active = 0, drawn = 0; // of the kind, from lastStats() (minimum over the timed frames)
    double msMedian = 0.0, msP90 = 0.0;
    double updateUsMedian = std::numeric_limits<double>::quiet_NaN(); // EffectsSystem::update(), CPU
    double renderCpuMsMedian = 0.0; // steady_clock around the render() call alone (CPU side, no glFinish)
    long long vertices = 0;         // all vertices of the frame (max over the timed frames)
    long long fxVertices = 0;       // secondary-grid vertices, both kinds
    int fxPasses = 0, fxDraws = 0, fxUploads = 0; // both kinds and the field, max over the timed frames
    int fieldTiles = 0;                           // tiles of the effects field evaluated (max)
    int passes = 0, draws = 0, uploads = 0;       // frame totals, max over the timed frames
    int programsBuilt = 0;                        // summed over the timed frames (must be 0: warm)
    // Medians of the per-pass times (OceanPassTimes) of a second renderer drawing the same frames with
    // setPassTiming(): compute holds the effects field's pass, sea the base grid, effects the secondary
    // grids.
    double computeMs = NAN_MS, seaMs = NAN_MS, effectsMs = NAN_MS, shadeMs = NAN_MS;
    std::vector<double> samples; // ms of each timed frame, one per round (round order)
};

double quantile(std::vector<double> v, double q) {
    if (v.empty())
        return std::numeric_limits<double>::quiet_NaN();
    std::sort(v.begin(), v.end());
    // Nearest rank: the median of an odd count is the middle sample.
    const size_t i = std::min(v.size() - 1, static_cast<size_t>(std::ceil(q * double(v.size())) - 1.0));
    return v[q == 0.5 ? v.size() / 2 : i];
}

std::string fixed(double v, int decimals) {
    if (std::isnan(v))
        return "–";
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << v;
    return s.str();
}

// Halton radical inverse: well-spread points whose first N are spread for every N (so 1, 4, 16 and 64
// explosions all cover the view instead of piling up in one corner).
double halton(int i, int base) {
    double f = 1.0, r = 0.0;
    for (; i > 0; i /= base) {
        f /= base;
        r += f * (i % base);
    }
    return r;
}

// Explosion i: 180..600 m ahead of the camera, within +-55% of the depth sideways (the view's half width on
// the sea is ~1.0 of the depth at 640x360 and 60 degrees vertical fov), spawned 3..5 s before T0 so the ring
// has grown (front ~20-30 m out), strengths 1..2. `origin`: sim time of the setting's first frame.
ocean::SpawnExplosion explosionSpawn(int i, double origin) {
    const double depth = 180.0 + 420.0 * halton(i + 1, 2);
    const double side = (2.0 * halton(i + 1, 3) - 1.0) * 0.55 * depth;
    return {glm::dvec2(CAMERA) + glm::dvec2(depth, side), origin - 3.0 - (i % 3), 1.0 + 0.5 * (i % 3)};
}

// Ship i's lane: centre lane first, then alternating sides 90 m apart, so the first N are centred in view.
// At the setting's first frame (sinceOrigin = 0) the ships are 450..590 m ahead; their 1200 m of path runs
// back past the camera.
glm::dvec2 shipPosition(int i, double sinceOrigin) {
    const double lane = 90.0 * ((i + 1) / 2) * (i % 2 == 1 ? 1.0 : -1.0);
    const double ahead = 450.0 + 20.0 * i + SHIP_SPEED * sinceOrigin;
    return glm::dvec2(CAMERA) + glm::dvec2(ahead, lane);
}

ocean::OceanFrame makeFrame(const gl::FrameTargets& targets, double time) {
    Pose pose;
    pose.position = CAMERA;
    pose.headingDeg = HEADING_DEG;
    pose.pitchDeg = PITCH_DEG;
    return ocean::makeOceanFrame(pose, static_cast<float>(FOV_Y_DEG * std::numbers::pi / 180.0),
                                 targets.width(), targets.height(), time, targets.sceneFramebuffer().id(),
                                 0.5f);
}

// One setting: its own registry, events, effects system, renderer and sim clock, so the settings can be
// timed interleaved (round robin, one frame each) and a shared machine's drift hits all of them alike.
struct Scene {
    Row row;
    ecs::Registry registry;
    ecs::EventQueue events;
    std::unique_ptr<ocean::EffectsSystem> fx;         // null: the plain ocean
    std::unique_ptr<ocean::EffectsTimeline> timeline; // moves the ships, dispatches, updates fx
    std::unique_ptr<ocean::OceanRenderer> renderer;   // one per scene: its cache is keyed by entity
    std::unique_ptr<ocean::OceanRenderer> profiled;   // the same frames with per-pass timing
    double origin = T0, time = T0;                    // sim time of the first frame, of the next frame
    std::vector<double> ms, updateUs, renderCpuMs, computeMs, seaMs, effectsMs, shadeMs;

    Scene(std::string setting, Kind kind, int count, bool withSystem) : row{std::move(setting), kind, count} {
        row.active = row.drawn = std::numeric_limits<int>::max();
        registry.emplace<ocean::OceanComponent>(registry.create(), ocean::makeOcean({}));
        if (withSystem) {
            fx = std::make_unique<ocean::EffectsSystem>(registry, events);
            timeline = std::make_unique<ocean::EffectsTimeline>(registry, events, *fx);
        }
        renderer = std::make_unique<ocean::OceanRenderer>();
    }

    // One frame: the effects step (ships moved, events dispatched, fx->update(); timed on the CPU), then
    // render + glFinish inside the GPU timer. Untimed frames warm up (shader variants, grid meshes).
    void frame(gl::GpuTimer& timer, const gl::FrameTargets& targets, bool timed) {
        if (timeline) {
            const auto u0 = std::chrono::steady_clock::now();
            timeline->step(time, CAMERA);
            const auto u1 = std::chrono::steady_clock::now();
            if (timed)
                updateUs.push_back(std::chrono::duration<double, std::micro>(u1 - u0).count());
        }
        const ocean::OceanFrame f = makeFrame(targets, time);
        time += FRAME_DT;
        glFinish(); // nothing of an earlier scene's frame may run inside this one's span
        if (timed)
            timer.begin();
        const auto r0 = std::chrono::steady_clock::now();
        render(*renderer, registry, f);
        const auto r1 = std::chrono::steady_clock::now();
        if (timed)
            timer.end();
        glFinish();
        if (!profiled) {
            profiled = std::make_unique<ocean::OceanRenderer>();
            profiled->setPassTiming(ocean::passClock(timer.clock()));
        }
        render(*profiled, registry, f); // outside the timed span
        glFinish();
        if (!timed)
            return;
        timer.drain(); // the span just ended is the newest sample (the frame has finished: no stall)
        ms.push_back(timer.samples().back());
        if (const ocean::OceanPassTimes& p = profiled->lastStats().passTimes; p.measured) {
            computeMs.push_back(p.computeMs);
            seaMs.push_back(p.seaMs);
            effectsMs.push_back(p.effectsMs);
            shadeMs.push_back(p.shadeMs + p.skyMs);
        }
        renderCpuMs.push_back(std::chrono::duration<double, std::milli>(r1 - r0).count());
        const ocean::OceanStats& s = renderer->lastStats();
        const bool wakes = row.kind == Kind::Wake || row.kind == Kind::Fleet;
        const bool explosions = row.kind == Kind::Explosion || row.kind == Kind::Fleet;
        row.active =
            std::min(row.active, (wakes ? s.wakes.active : 0) + (explosions ? s.explosions.active : 0));
        row.drawn = std::min(row.drawn, (wakes ? s.wakes.drawn : 0) + (explosions ? s.explosions.drawn : 0));
        row.vertices = std::max(row.vertices, s.vertices);
        row.fxVertices = std::max(row.fxVertices, s.explosions.vertices + s.wakes.vertices);
        row.fxPasses = std::max(row.fxPasses, s.explosions.passes + s.wakes.passes + s.effectField.passes);
        row.fxDraws = std::max(row.fxDraws, s.explosions.draws + s.wakes.draws);
        row.fxUploads =
            std::max(row.fxUploads, s.explosions.uploads + s.wakes.uploads + s.effectField.uploads);
        row.fieldTiles = std::max(row.fieldTiles, s.effectField.tiles);
        row.passes = std::max(row.passes, s.passes);
        row.draws = std::max(row.draws, s.draws);
        row.uploads = std::max(row.uploads, s.uploads);
        row.programsBuilt += s.programsBuilt;
    }

    Row finish() {
        row.samples = ms;
        row.msMedian = quantile(ms, 0.5);
        row.msP90 = quantile(ms, 0.9);
        row.renderCpuMsMedian = quantile(renderCpuMs, 0.5);
        if (!updateUs.empty())
            row.updateUsMedian = quantile(updateUs, 0.5);
        if (!seaMs.empty()) {
            row.computeMs = quantile(computeMs, 0.5);
            row.seaMs = quantile(seaMs, 0.5);
            row.effectsMs = quantile(effectsMs, 0.5);
            row.shadeMs = quantile(shadeMs, 0.5);
        }
        std::fprintf(stderr,
                     "[%s] %s x%d: %.3f ms (p90 %.3f), update %.1f us, active %d drawn %d, fx vertices %lld, "
                     "fx passes %d draws %d uploads %d, field tiles %d\n",
                     row.setting.c_str(), kindName(row.kind), row.count, row.msMedian, row.msP90,
                     row.updateUsMedian, row.active, row.drawn, row.fxVertices, row.fxPasses, row.fxDraws,
                     row.fxUploads, row.fieldTiles);
        return row;
    }
};

/// A secondary grid for every effect in view (EffectGridDesc minAngularSize and minAmplitudePixels 0, no
/// limit), as before the effects field: the difference to the default row is what the grids' geometry costs.
void everyGrid(Scene& scene) {
    scene.registry.view<ocean::OceanComponent>().each([](ecs::Entity, ocean::OceanComponent& oc) {
        oc.desc.effectGrids.minAngularSize = oc.desc.effectGrids.minAmplitudePixels = 0.0;
        oc.desc.effectGrids.maxExplosionGrids = oc.desc.effectGrids.maxWakeGrids = 4096;
    });
}

std::unique_ptr<Scene> explosionScene(int n, bool grids = false) {
    auto scene =
        std::make_unique<Scene>(grids ? "explosions_every_grid" : "explosions", Kind::Explosion, n, true);
    if (grids)
        everyGrid(*scene);
    for (int i = 0; i < n; ++i)
        scene->events.enqueue(explosionSpawn(i, scene->origin));
    return scene;
}

// Ships with trails, their paths recorded for 120 s of sim time in 0.5 s steps before the first frame
// (update() only: the renderer never sees that earlier time).
void addShips(Scene& scene, int n) {
    const double origin = scene.origin;
    for (int i = 0; i < n; ++i)
        scene.timeline->addShip(shipPosition(i, -HISTORY_SECONDS), 60.0,
                                [i, origin](double t) { return shipPosition(i, t - origin); });
    scene.timeline->warmUp(origin - HISTORY_SECONDS, origin, CAMERA);
}

/// EffectFieldDesc::viewCull off: every tile an effect touches is evaluated, the trails behind the camera's
/// view too (what the cull saves; the image is the same).
void noViewCull(Scene& scene) {
    scene.registry.view<ocean::OceanComponent>().each(
        [](ecs::Entity, ocean::OceanComponent& oc) { oc.desc.effectField.viewCull = false; });
}

std::unique_ptr<Scene> wakeScene(int n, bool grids = false, bool viewCull = true) {
    auto scene = std::make_unique<Scene>(grids      ? "wakes_every_grid"
                                         : viewCull ? "wakes"
                                                    : "wakes_no_view_cull",
                                         Kind::Wake, n, true);
    if (grids)
        everyGrid(*scene);
    if (!viewCull)
        noViewCull(*scene);
    addShips(*scene, n);
    return scene;
}

/// The fleet goal's scene: n ships with trails and n explosions at once (count = both kinds together).
std::unique_ptr<Scene> fleetScene(int n, bool viewCull = true) {
    auto scene = std::make_unique<Scene>(viewCull ? "fleet" : "fleet_no_view_cull", Kind::Fleet, 2 * n, true);
    if (!viewCull)
        noViewCull(*scene);
    for (int i = 0; i < n; ++i)
        scene->events.enqueue(explosionSpawn(i, scene->origin));
    addShips(*scene, n);
    return scene;
}

struct Fit {
    double slope = std::numeric_limits<double>::quiet_NaN(); // ms per effect
    double intercept = std::numeric_limits<double>::quiet_NaN();
};

// Ordinary least squares y = a + b x.
Fit leastSquares(const std::vector<double>& x, const std::vector<double>& y) {
    const size_t n = x.size();
    if (n < 2)
        return {};
    double mx = 0.0, my = 0.0;
    for (size_t i = 0; i < n; ++i) {
        mx += x[i];
        my += y[i];
    }
    mx /= double(n);
    my /= double(n);
    double sxy = 0.0, sxx = 0.0;
    for (size_t i = 0; i < n; ++i) {
        sxy += (x[i] - mx) * (y[i] - my);
        sxx += (x[i] - mx) * (x[i] - mx);
    }
    if (sxx <= 0.0)
        return {};
    Fit f;
    f.slope = sxy / sxx;
    f.intercept = my - f.slope * mx;
    return f;
}

struct KindSummary {
    Kind kind = Kind::None;
    std::vector<int> counts;
    Fit ms;                                                             // render ms against count
    Fit updateUs;                                                       // update() us against count
    double usPerEffectAtMax = std::numeric_limits<double>::quiet_NaN(); // (ms(Nmax) - ms(plain)) / Nmax
    long long verticesPerEffect = 0;
};

KindSummary summarise(const std::vector<Row>& rows, Kind kind, double plainMs) {
    KindSummary k;
    k.kind = kind;
    std::vector<double> x, y, u;
    const Row* largest = nullptr;
    for (const Row& r : rows)
        if (r.kind == kind && r.setting == (kind == Kind::Explosion ? "explosions" : "wakes")) {
            k.counts.push_back(r.count);
            x.push_back(r.count);
            y.push_back(r.msMedian);
            u.push_back(r.updateUsMedian);
            if (!largest || r.count > largest->count)
                largest = &r;
        }
    k.ms = leastSquares(x, y);
    k.updateUs = leastSquares(x, u);
    if (largest && largest->count > 0) {
        k.usPerEffectAtMax = 1000.0 * (largest->msMedian - plainMs) / largest->count;
        k.verticesPerEffect = largest->fxVertices / std::max(1, largest->drawn);
    }
    return k;
}

const Row& findRow(const std::vector<Row>& rows, const std::string& setting) {
    for (const Row& r : rows)
        if (r.setting == setting)
            return r;
    throw std::logic_error("findRow(): no row " + setting);
}

std::string loadAverage() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    if (!(in >> a >> b >> c))
        return "unknown";
    return a + " " + b + " " + c;
}

// effects.csv (one row per setting), effects.md (the tables docs/EFFECTS_BENCH.md quotes) and effects.json
// (the per-kind summary, for scripts).
/// What the reports say of the run besides its rows: the plain and zero-effect frames, the paired ratio
/// (zero-effect / plain frame by frame within a round, adjacent in time, which cancels load that changes
/// between rounds; its spread p10..p90 shows the noise the ratio of medians carries) and each kind's fit.
struct RunSummary {
    const Row& plain;
    const Row& zero;
    double plainMs = 0.0, pairedMedian = 0.0, pairedP10 = 0.0, pairedP90 = 0.0;
    KindSummary kinds[2];
    std::string renderer, clock, load, commandLine;
    int width = 0, height = 0, frames = 0;
};

RunSummary summariseRun(const std::vector<Row>& rows, const gl::ContextInfo& info, const gl::GpuTimer& timer,
                        int width, int height, int frames, const std::string& commandLine) {
    const Row& plain = findRow(rows, "plain");
    const Row& zero = findRow(rows, "zero_effect");
    std::vector<double> paired;
    for (size_t i = 0; i < std::min(zero.samples.size(), plain.samples.size()); ++i)
        paired.push_back(zero.samples[i] / plain.samples[i]);
    return RunSummary{
        plain,
        zero,
        plain.msMedian,
        quantile(paired, 0.5),
        quantile(paired, 0.1),
        quantile(paired, 0.9),
        {summarise(rows, Kind::Explosion, plain.msMedian), summarise(rows, Kind::Wake, plain.msMedian)},
        info.renderer,
        timer.clockName(),
        loadAverage(),
        commandLine,
        width,
        height,
        frames};
}

double perEffectUs(const Row& r, double plainMs) {
    return r.count > 0 ? 1000.0 * (r.msMedian - plainMs) / r.count : std::numeric_limits<double>::quiet_NaN();
}

std::string effectsCsv(const std::vector<Row>& rows, const RunSummary& s) {
    std::ostringstream csv;
    csv << "setting,kind,count,active,drawn,ms_median,ms_p90,us_per_effect_vs_plain,update_us_median,"
           "render_cpu_ms_median,vertices,fx_vertices,fx_passes,fx_draws,fx_uploads,passes,draws,uploads,"
           "programs_built,field_tiles,compute_ms,sea_ms,effects_ms,shade_ms,clock,renderer\n";
    for (const Row& r : rows)
        csv << r.setting << ',' << kindName(r.kind) << ',' << r.count << ',' << r.active << ',' << r.drawn
            << ',' << num(r.msMedian) << ',' << num(r.msP90) << ',' << num(perEffectUs(r, s.plainMs)) << ','
            << num(r.updateUsMedian) << ',' << num(r.renderCpuMsMedian) << ',' << r.vertices << ','
            << r.fxVertices << ',' << r.fxPasses << ',' << r.fxDraws << ',' << r.fxUploads << ',' << r.passes
            << ',' << r.draws << ',' << r.uploads << ',' << r.programsBuilt << ',' << r.fieldTiles << ','
            << num(r.computeMs) << ',' << num(r.seaMs) << ',' << num(r.effectsMs) << ',' << num(r.shadeMs)
            << ',' << csvQuote(s.clock) << ',' << csvQuote(s.renderer) << '\n';
    return csv.str();
}

void settingsTable(std::ostringstream& md, const std::vector<Row>& rows, const RunSummary& s) {
    md << "# Pacifica effects benchmark\n\n"
       << "- GL_RENDERER: " << s.renderer << "\n- clock: " << s.clock << "\n- date: " << utcNow()
       << "\n- command: `" << s.commandLine << "`\n- size: " << s.width << "x" << s.height << ", " << s.frames
       << " timed frames per setting (+" << WARMUP_FRAMES
       << " warm-up), settings interleaved frame by frame; ms = median (p90) of render + glFinish\n"
       << "- camera: (" << CAMERA.x << ", " << CAMERA.y << ", " << CAMERA.z << ") m, heading " << HEADING_DEG
       << " deg, pitch " << PITCH_DEG << " deg, " << FOV_Y_DEG << " deg vertical fov; default OceanDesc\n"
       << "- load average at the end: " << s.load << "\n\n"
       << "| setting | kind | count | active | drawn | ms median | ms p90 | µs/effect vs plain | update µs | "
          "render CPU ms | vertices | fx vertices | fx passes | fx draws | fx uploads | field tiles |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Row& r : rows)
        md << "| " << r.setting << " | " << kindName(r.kind) << " | " << r.count << " | " << r.active << " | "
           << r.drawn << " | " << fixed(r.msMedian, 3) << " | " << fixed(r.msP90, 3) << " | "
           << fixed(perEffectUs(r, s.plainMs), 1) << " | " << fixed(r.updateUsMedian, 1) << " | "
           << fixed(r.renderCpuMsMedian, 3) << " | " << r.vertices << " | " << r.fxVertices << " | "
           << r.fxPasses << " | " << r.fxDraws << " | " << r.fxUploads << " | " << r.fieldTiles << " |\n";
}

void perEffectTable(std::ostringstream& md, const RunSummary& s) {
    md << "\n## Per effect\n\nplain = " << fixed(s.plainMs, 3)
       << " ms. Slope and intercept: least squares through (count, ms median) of the kind's settings.\n\n"
       << "| kind | counts | µs per effect (slope) | intercept ms | fixed cost ms (intercept − plain) "
       << "| µs per effect at max count ((ms(N) − plain) / N) | update() µs per effect (slope) "
       << "| vertices per effect |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    for (const KindSummary& k : s.kinds) {
        std::string counts;
        for (int c : k.counts)
            counts += (counts.empty() ? "" : ", ") + std::to_string(c);
        md << "| " << kindName(k.kind) << " | " << counts << " | " << fixed(1000.0 * k.ms.slope, 1) << " | "
           << fixed(k.ms.intercept, 3) << " | " << fixed(k.ms.intercept - s.plainMs, 3) << " | "
           << fixed(k.usPerEffectAtMax, 1) << " | " << fixed(k.updateUs.slope, 2) << " | "
           << k.verticesPerEffect << " |\n";
    }
}

void zeroEffectTable(std::ostringstream& md, const RunSummary& s) {
    const Row& zero = s.zero;
    md << "\n## Zero-effect frame\n\n"
       << "| zero-effect ms | plain ms | ratio of medians | paired ratio median (p10–p90) | Δ ms | update() "
          "µs "
       << "| fx passes | fx draws | fx uploads | fx vertices |\n|---|---|---|---|---|---|---|---|---|---|\n"
       << "| " << fixed(zero.msMedian, 3) << " | " << fixed(s.plainMs, 3) << " | "
       << fixed(zero.msMedian / s.plainMs, 3) << " | " << fixed(s.pairedMedian, 3) << " ("
       << fixed(s.pairedP10, 3) << "–" << fixed(s.pairedP90, 3) << ") | "
       << fixed(zero.msMedian - s.plainMs, 3) << " | " << fixed(zero.updateUsMedian, 2) << " | "
       << zero.fxPasses << " | " << zero.fxDraws << " | " << zero.fxUploads << " | " << zero.fxVertices
       << " |\n\n"
       << "fx counters are the maximum over the timed frames (both kinds summed), so 0 means no effect work "
          "in "
          "any of them.\n";
}

std::string effectsJson(const RunSummary& s) {
    nlohmann::json j;
    j["renderer"] = s.renderer;
    j["clock"] = s.clock;
    j["size"] = {s.width, s.height};
    j["frames"] = s.frames;
    j["command"] = s.commandLine;
    j["load_average"] = s.load;
    j["plain_ms"] = s.plainMs;
    const Row& zero = s.zero;
    j["zero_effect"] = {{"ms", zero.msMedian},
                        {"ratio", zero.msMedian / s.plainMs},
                        {"update_us", zero.updateUsMedian},
                        {"fx_passes", zero.fxPasses},
                        {"fx_draws", zero.fxDraws},
                        {"fx_uploads", zero.fxUploads}};
    auto jnum = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    for (const KindSummary& k : s.kinds)
        j["kinds"][kindName(k.kind)] = {{"counts", k.counts},
                                        {"us_per_effect_slope", jnum(1000.0 * k.ms.slope)},
                                        {"intercept_ms", jnum(k.ms.intercept)},
                                        {"us_per_effect_at_max", jnum(k.usPerEffectAtMax)},
                                        {"update_us_per_effect_slope", jnum(k.updateUs.slope)},
                                        {"vertices_per_effect", k.verticesPerEffect}};
    return j.dump(2) + "\n";
}

void writeReports(const std::string& outDir, const std::vector<Row>& rows, const gl::ContextInfo& info,
                  const gl::GpuTimer& timer, int width, int height, int frames,
                  const std::string& commandLine) {
    const RunSummary s = summariseRun(rows, info, timer, width, height, frames, commandLine);
    std::ostringstream md;
    settingsTable(md, rows, s);
    perEffectTable(md, s);
    zeroEffectTable(md, s);
    writeFileAtomically(outDir + "/effects.csv", effectsCsv(rows, s));
    writeFileAtomically(outDir + "/effects.md", md.str());
    writeFileAtomically(outDir + "/effects.json", effectsJson(s));
    const KindSummary* kinds = s.kinds;
    std::cout << "wrote " << outDir << "/effects.csv, effects.md, effects.json (" << s.renderer << ", "
              << s.clock << ")\n"
              << "explosion: " << fixed(1000.0 * kinds[0].ms.slope, 1) << " us/effect (slope), "
              << fixed(kinds[0].usPerEffectAtMax, 1) << " us/effect at " << kinds[0].counts.back()
              << "; wake: " << fixed(1000.0 * kinds[1].ms.slope, 1) << " us/effect (slope), "
              << fixed(kinds[1].usPerEffectAtMax, 1) << " us/effect at " << kinds[1].counts.back()
              << "; zero-effect/plain " << fixed(s.zero.msMedian / s.plainMs, 3) << " (paired "
              << fixed(s.pairedMedian, 3) << ", p10-p90 " << fixed(s.pairedP10, 3) << "-"
              << fixed(s.pairedP90, 3) << ")\n";
}

struct Args {
    std::string outDir = "effects";
    bool quick = false;
    std::optional<std::pair<int, int>> size;
    std::optional<int> frames;
    std::string commandLine;
};

std::optional<int> parseArgs(int argc, char** argv, Args& a) {
    CLI::App app("Cost per active effect of each kind and the zero-effect frame against the plain ocean "
                 "(docs/EFFECTS_BENCH.md).",
                 "pacifica-bench-effects");
    app.add_option("--out", a.outDir,
                   "output directory for effects.csv, effects.md, effects.json (default effects)");
    std::string size;
    app.add_option("--size", size, "render size WxH (default 640x360; --quick: 160x90)")
        ->check(bench::sizeValidator());
    app.add_option("--frames", a.frames,
                   "timed frames per setting, median and p90 reported (default 15; --quick: 3)")
        ->check(CLI::Range(1, 10000));
    app.add_flag("--quick", a.quick,
                 "few settings (plain, zero-effect, 1 and 4 explosions, 1 and 2 wakes): the test");
    if (const auto code = bench::parseCommandLine(app, argc, argv))
        return code;
    if (!size.empty())
        a.size = parseSize(size);
    a.commandLine = bench::commandLine(argc, argv);
    return std::nullopt;
}

} // namespace

// ---- The grid density knob: error and cost ---------------------------------------------------------------

/// Interpolation error of a field over an effect grid (the unit disc of EffectsGpu.cpp, rings at
/// (i / rings)^exponent, scaled to `radius`): at each triangle's centroid and edge midpoints, |f - the
/// linear interpolation of f at the triangle's corners| (what the rasterised mesh shows between vertices),
/// area-weighted RMS and the maximum.
struct MeshError {
    double rms = 0.0, max = 0.0;
};
template <class F>
MeshError meshError(double radius, int rings, int segments, double exponent, F field) {
    std::vector<glm::dvec2> v{glm::dvec2(0.0)};
    for (int i = 1; i <= rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double a = 2.0 * std::numbers::pi * j / segments;
            v.push_back(radius * std::pow(double(i) / rings, exponent) *
                        glm::dvec2(std::cos(a), std::sin(a)));
        }
    std::vector<double> fv(v.size());
    for (size_t i = 0; i < v.size(); ++i)
        fv[i] = field(v[i]);
    auto at = [segments](int ring, int j) { return size_t(1 + (ring - 1) * segments + (j % segments)); };
    double sumSq = 0.0, sumArea = 0.0;
    MeshError e;
    auto triangle = [&](size_t a, size_t b, size_t c) {
        const glm::dvec2 ab = v[b] - v[a], ac = v[c] - v[a];
        const double area = 0.5 * std::abs(ab.x * ac.y - ab.y * ac.x);
        const glm::dvec3 bary[4] = {{1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
        for (const glm::dvec3& w : bary) {
            const glm::dvec2 p = w.x * v[a] + w.y * v[b] + w.z * v[c];
            const double err = std::abs(field(p) - (w.x * fv[a] + w.y * fv[b] + w.z * fv[c]));
            sumSq += area * err * err / 4.0;
            e.max = std::max(e.max, err);
        }
        sumArea += area;
    };
    for (int j = 0; j < segments; ++j)
        triangle(0, at(1, j), at(1, j + 1));
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    e.rms = std::sqrt(sumSq / std::max(sumArea, 1e-30));
    return e;
}

struct GridRow {
    std::string kind;
    int count = 0, rings = 0, segments = 0;
    double exponent = 0.0;
    double msMedian = 0.0;
    long long fxVertices = 0;
    double rmsRel = 0.0, maxRel = 0.0, amplitude = 0.0, radius = 0.0;
};

/// Times `count` explosions (or wakes) at each grid density, round robin, and measures each density's mesh
/// interpolation error of the field of the scene's first effect (relative to its amplitude).
/// The mesh error of one setting's first effect against its continuous field (relative to its amplitude).
void gridError(Scene& sc, GridRow& r) {
    const double t = sc.time;
    if (r.kind == "wake") {
        sc.registry.view<ocean::Ship, ocean::ShipTrail>().each(
            [&](ecs::Entity, ocean::Ship& ship, ocean::ShipTrail& trail) {
                if (r.radius > 0.0)
                    return;
                const ocean::WakeState ws = ocean::wakeState(ship, trail, t);
                r.radius = ws.radius;
                r.amplitude = ws.peak;
                const MeshError e = meshError(ws.radius, r.rings, r.segments, r.exponent,
                                              [&](const glm::dvec2& q) { return ocean::wakeWave(ws, q).x; });
                r.rmsRel = e.rms / ws.peak;
                r.maxRel = e.max / ws.peak;
            });
        return;
    }
    sc.registry.view<ocean::Explosion>().each([&](ecs::Entity, ocean::Explosion& ex) {
        if (r.radius > 0.0)
            return;
        const ocean::ExplosionState es = ocean::explosionState(ex, t);
        r.radius = es.radius;
        r.amplitude = es.amplitude;
        const MeshError e = meshError(es.radius, r.rings, r.segments, r.exponent, [&](const glm::dvec2& q) {
            return ocean::explosionWave(ex.params, es, q).x;
        });
        r.rmsRel = e.rms / es.amplitude;
        r.maxRel = e.max / es.amplitude;
    });
}

struct Density {
    const char* kind;
    int rings, segments;
    double exponent;
};

/// A scene of `explosions` explosions or one wake, its secondary grids at density d.
std::unique_ptr<Scene> densityScene(const Density& d, int explosions) {
    const bool isWake = std::string(d.kind) == "wake";
    std::unique_ptr<Scene> sc = isWake ? wakeScene(1) : explosionScene(explosions);
    sc->row.setting =
        std::string(d.kind) + "_grid_" + std::to_string(d.rings) + "x" + std::to_string(d.segments);
    sc->registry.view<ocean::OceanComponent>().each([&](ecs::Entity, ocean::OceanComponent& oc) {
        ocean::EffectGridDesc& g = oc.desc.effectGrids;
        if (isWake) {
            g.wakeRings = d.rings;
            g.wakeSegments = d.segments;
            g.wakeExponent = d.exponent;
        } else {
            g.explosionRings = d.rings;
            g.explosionSegments = d.segments;
            g.explosionExponent = d.exponent;
        }
    });
    return sc;
}

/// The grid density knob (OceanDesc::effectGrids): each density's frame time (round robin after the warm-up)
/// and its mesh error.
std::vector<GridRow> gridKnob(gl::GpuTimer& timer, const gl::FrameTargets& targets, int frames, bool quick) {
    std::vector<Density> densities = {{"explosion", 24, 48, 1.5},  {"explosion", 48, 96, 1.5},
                                      {"explosion", 96, 192, 1.5}, {"wake", 48, 96, 2.0},
                                      {"wake", 96, 192, 2.0},      {"wake", 192, 384, 2.0}};
    if (quick)
        densities = {{"explosion", 24, 48, 1.5}, {"explosion", 48, 96, 1.5}, {"wake", 48, 96, 2.0}};
    const int explosions = quick ? 4 : 16;
    std::vector<std::unique_ptr<Scene>> scenes;
    std::vector<GridRow> rows;
    for (const Density& d : densities) {
        scenes.push_back(densityScene(d, explosions));
        GridRow r;
        r.kind = d.kind;
        r.count = std::string(d.kind) == "wake" ? 1 : explosions;
        r.rings = d.rings;
        r.segments = d.segments;
        r.exponent = d.exponent;
        rows.push_back(r);
    }
    for (auto& scene : scenes)
        for (int i = 0; i < WARMUP_FRAMES; ++i)
            scene->frame(timer, targets, false);
    for (int f = 0; f < frames; ++f)
        for (size_t k = 0; k < scenes.size(); ++k)
            scenes[(k + size_t(f)) % scenes.size()]->frame(timer, targets, true);
    for (size_t i = 0; i < scenes.size(); ++i) {
        GridRow& r = rows[i];
        r.msMedian = quantile(scenes[i]->ms, 0.5);
        const ocean::OceanStats& st = scenes[i]->renderer->lastStats();
        r.fxVertices = st.explosions.vertices + st.wakes.vertices;
        gridError(*scenes[i], r);
        std::fprintf(stderr, "[grid] %s %dx%d: %.3f ms, mesh error rms %.3g max %.3g of the amplitude\n",
                     r.kind.c_str(), r.rings, r.segments, r.msMedian, r.rmsRel, r.maxRel);
    }
    return rows;
}

void writeGridReport(const std::string& outDir, const std::vector<GridRow>& rows, const gl::ContextInfo& info,
                     const gl::GpuTimer& timer, int width, int height, int frames) {
    std::ostringstream csv, md; // written whole (writeFileAtomically), as the other reports
    csv << "kind,count,rings,segments,exponent,radius_m,amplitude_m,mesh_rms_rel,mesh_max_rel,ms_median,"
           "fx_vertices,clock,renderer\n";
    for (const GridRow& r : rows)
        csv << r.kind << ',' << r.count << ',' << r.rings << ',' << r.segments << ',' << num(r.exponent)
            << ',' << num(r.radius) << ',' << num(r.amplitude) << ',' << num(r.rmsRel) << ',' << num(r.maxRel)
            << ',' << num(r.msMedian) << ',' << r.fxVertices << ',' << csvQuote(timer.clockName()) << ','
            << csvQuote(info.renderer) << '\n';
    md << "# Effect grid density: error against cost\n\n- GL_RENDERER: " << info.renderer
       << "\n- clock: " << timer.clockName() << "\n- size: " << width << "x" << height << ", " << frames
       << " timed frames per setting, round robin; ms = median of render + glFinish\n"
       << "- error: the mesh's linear interpolation of the effect's height between its vertices against the "
          "analytic field (explosionWave / wakeWave) at triangle centroids and edge midpoints, area-weighted "
          "RMS and max, relative to the effect's amplitude (A(tau) / the wake's peak)\n\n"
       << "| kind | count | grid (rings x segments, exponent) | radius m | mesh rms / A | mesh max / A | ms "
          "| fx "
          "vertices |\n|---|---|---|---|---|---|---|---|\n";
    for (const GridRow& r : rows)
        md << "| " << r.kind << " | " << r.count << " | " << r.rings << " x " << r.segments << ", "
           << num(r.exponent) << " | " << fixed(r.radius, 0) << " | " << num(r.rmsRel, 3) << " | "
           << num(r.maxRel, 3) << " | " << fixed(r.msMedian, 3) << " | " << r.fxVertices << " |\n";
    writeFileAtomically(outDir + "/effects_grid.csv", csv.str());
    writeFileAtomically(outDir + "/effects_grid.md", md.str());
}

int main(int argc, char** argv) {
    Args args;
    if (const auto code = parseArgs(argc, argv, args))
        return *code;
    const bool quick = args.quick;
    const std::string& outDir = args.outDir;
    const std::string& commandLine = args.commandLine;
    const auto [width, height] = args.size.value_or(quick ? std::pair{160, 90} : std::pair{640, 360});
    const int frames = args.frames.value_or(quick ? 3 : 15);
    const std::vector<int> explosionCounts = quick ? std::vector{1, 4} : std::vector{1, 4, 16, 64, 256, 1024};
    const std::vector<int> wakeCounts = quick ? std::vector{1, 2} : std::vector{1, 2, 8, 64, 256};
    return bench::runGlBench("pacifica-bench-effects", outDir, {}, [&](gl::GlContext& context) {
        const gl::ContextInfo info = context.info();
        gl::GpuTimer timer(info);
        std::fprintf(stderr,
                     "pacifica-bench-effects: GL_RENDERER %s; clock: %s; %dx%d, %d frames per setting\n",
                     info.renderer.c_str(), timer.clockName(), width, height, frames);
        gl::FrameTargets targets(width, height);
        // a. plain ocean (no EffectsSystem); b. zero effects (the system exists and runs, nothing to do);
        // c. explosions; d. wakes.
        std::vector<std::unique_ptr<Scene>> scenes;
        scenes.push_back(std::make_unique<Scene>("plain", Kind::None, 0, false));
        scenes.push_back(std::make_unique<Scene>("zero_effect", Kind::None, 0, true));
        for (int n : explosionCounts)
            scenes.push_back(explosionScene(n));
        for (int n : wakeCounts)
            scenes.push_back(wakeScene(n));
        // e. the same with a secondary grid for every effect (as before the field): what the grids cost.
        scenes.push_back(explosionScene(quick ? 4 : 64, true));
        scenes.push_back(wakeScene(quick ? 2 : 8, true));
        scenes.push_back(fleetScene(quick ? 2 : 64)); // the fleet goal: 64 wakes + 64 explosions
        // f. the field evaluated without the view cull (EffectFieldDesc::viewCull): what the cull saves.
        scenes.push_back(wakeScene(1, false, false));
        if (!quick)
            scenes.push_back(fleetScene(64, false));
        for (auto& scene : scenes)
            for (int i = 0; i < WARMUP_FRAMES; ++i)
                scene->frame(timer, targets, false);
        // Round robin, one frame per scene per round, the starting scene rotating from round to round.
        for (int f = 0; f < frames; ++f)
            for (size_t k = 0; k < scenes.size(); ++k)
                scenes[(k + size_t(f)) % scenes.size()]->frame(timer, targets, true);
        std::vector<Row> rows;
        for (auto& scene : scenes)
            rows.push_back(scene->finish());

        writeReports(outDir, rows, info, timer, width, height, frames, commandLine);
        scenes.clear();
        // The grid density knob (OceanDesc::effectGrids): its error and its cost.
        writeGridReport(outDir, gridKnob(timer, targets, frames, quick), info, timer, width, height, frames);
        return 0;
    });
}
