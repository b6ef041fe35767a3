// Replay implementation: validate everything first, then render frame by frame; on any failure remove
// what this run wrote. summary.json is written last and atomically.
#include "Replay.h"

#include "ChunkFrames.h"
#include "FlightPath.h"
#include "ImageInputs.h"
#include "OutputTransaction.h"
#include "ReplayInput.h"
#include "ReplayLights.h"
#include "VideoWriter.h"
#include "WorkerQueue.h"
#include "engine/AtomicFile.h"
#include "engine/Ecs.h"
#include "engine/Log.h"
#include "engine/Space.h"
#include "engine/Stats.h"
#include "engine/capture/Capture.h"
#include "engine/color/ColorPipeline.h"
#include "engine/color/Tonemapper.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "engine/gl/ObjectRenderer.h"
#include "engine/gl/PassTimer.h"
#include "ocean/Buoyancy.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanHost.h"
#include "ocean/SeaQuery.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <unistd.h>
#include <vector>

namespace pacifica::tools {
namespace fs = std::filesystem;

namespace {

std::string shortNumber(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

using Clock = std::chrono::steady_clock;

/// An environment variable's value, null when unset (summary.json).
nlohmann::json environment(const char* name) {
    const char* v = std::getenv(name);
    return v ? nlohmann::json(v) : nlohmann::json(nullptr);
}

double msBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

/// The frames of a run: frame k is at start + k * speed / fps, from the index (never accumulated), the last
/// one clamped to end.
struct FramePlan {
    double start = 0.0, end = 0.0;
    double step = 0.0; ///< recording seconds per frame
    long long count = 0;
    double timeOf(long long k) const { return std::min(end, start + static_cast<double>(k) * step); }
};

FramePlan planFrames(const ReplayOptions& o, const ReplayInput& input) {
    FramePlan p;
    p.start = o.start ? parseTimeArgument(*o.start, input.referenceUnix, "--start") : input.startTime;
    p.end = o.end ? parseTimeArgument(*o.end, input.referenceUnix, "--end") : input.endTime;
    if (!std::isfinite(p.start) || p.start < input.startTime || p.start > input.endTime)
        throw UsageError("--start " + std::to_string(p.start) + " is outside the flight [" +
                         std::to_string(input.startTime) + ", " + std::to_string(input.endTime) + "]");
    if (!std::isfinite(p.end) || p.end < p.start || p.end > input.endTime)
        throw UsageError("--end " + std::to_string(p.end) + " must be within [--start, " +
                         std::to_string(input.endTime) + "]");
    p.step = o.speed / o.fps;
    const double count = std::floor((p.end - p.start) / p.step + 1e-9) + 1.0;
    if (count > static_cast<double>(o.maxFrames))
        throw UsageError("the run would render " + std::to_string(static_cast<long long>(count)) +
                         " frames (" + shortNumber(p.end - p.start) + " s at --fps " + shortNumber(o.fps) +
                         ", --speed " + shortNumber(o.speed) + "), more than --max-frames " +
                         std::to_string(o.maxFrames) +
                         "; shorten --start/--end, lower --fps, raise --speed, or "
                         "allow it with --max-frames");
    p.count = static_cast<long long>(count);
    if (o.frames && o.frames->last >= p.count)
        throw UsageError("--frames " + std::to_string(o.frames->first) + "-" +
                         std::to_string(o.frames->last) + ": the run has " + std::to_string(p.count) +
                         " frames (0-" + std::to_string(p.count - 1) + ")");
    return p;
}

/// The ocean to render: the options' description with --env's map, whose brightest region becomes the sun
/// (unless it is below the horizon). `environmentJson`: summary.json's entry, null for the procedural sky.
ocean::OceanDesc oceanWithEnvironment(const ReplayOptions& o, nlohmann::json& environmentJson) {
    ocean::OceanDesc d = o.ocean;
    environmentJson = nullptr;
    if (o.environment) {
        d.lighting.environment = loadEnvironment(*o.environment);
        const glm::dvec3 sun = ocean::environmentBrightestDirection(*d.lighting.environment);
        if (sun.z > 0.0) // a sun below the horizon would leave the sea unlit: keep the default then
            d.lighting.sunDirection = sun;
        environmentJson = {
            {"file", o.environment->string()},
            {"width", d.lighting.environment->width},
            {"height", d.lighting.environment->height},
            {"sun_direction",
             {d.lighting.sunDirection.x, d.lighting.sunDirection.y, d.lighting.sunDirection.z}}};
    }
    if (o.exposureEv != 0.0) // pre-exposure: the frame (and the EXR) holds radiance x 2^EV
        d.lighting = ocean::exposed(d.lighting, o.exposureEv);
    return d;
}

/// The OCIO pipeline of the run. The renderer's frames are linear Rec.709: a config whose scene_linear role
/// is another space (ACEScg in the ACES studio and CG configs) is entered through its linear Rec.709 colour
/// space when it has one.
color::ColorPipeline replayColour(const ReplayOptions& o) {
    color::ColorPipeline colour = color::ColorPipeline::fromEnvironmentOr(o.ocioConfig);
    if (const std::string rec709 = colour.linearRec709ColorSpace(); !rec709.empty())
        colour.setInput(rec709);
    else
        std::fprintf(stderr,
                     "pacifica: warning: the OCIO config has no linear Rec.709 colour space; frames enter it "
                     "as its scene_linear role\n");
    colour.select(o.display, o.view);
    return colour;
}

/// An extra view: one more tonemap pass over the same rendered scene (no scene pass is repeated).
struct ExtraView {
    std::string view, suffix;
    std::unique_ptr<color::Tonemapper> pass;
};

std::vector<ExtraView> makeExtraViews(const ReplayOptions& o, const color::ColorPipeline& colour) {
    std::vector<ExtraView> extraViews;
    for (const std::string& v : o.extraViews) {
        color::ColorPipeline other = colour;
        other.select(colour.selectedDisplay(), v); // an unknown view: ColorError listing the valid ones
        const std::string suffix = fileSlug(v);
        for (const ExtraView& e : extraViews)
            if (e.suffix == suffix)
                throw std::runtime_error("--view '" + v + "' is given twice");
        extraViews.push_back({v, suffix, std::make_unique<color::Tonemapper>(other)});
    }
    return extraViews;
}

/// The flight's events on the effects timeline (Effects.h): ships follow their tracks, explosions are
/// spawned when the clock passes them. The wakes are built from the ships' paths before the first frame
/// (0.5 s steps from the earliest ship sample, at most 600 s: older wakes have faded), so a ship that sailed
/// before --start has a wake.
void scheduleEvents(ocean::EffectsTimeline& timeline, const ReplayInput& input, double start) {
    for (size_t i = 0; i < input.ships.size(); ++i) {
        const ShipTrack* track = &input.ships[i];
        timeline.addShip(track->positionAt(track->startTime()), input.shipLengths[i],
                         [track](double t) { return track->positionAt(t); });
    }
    std::vector<ocean::SpawnExplosion> spawns;
    for (const ExplosionEvent& x : input.explosions)
        spawns.push_back({{x.x, x.y}, x.time, x.strength});
    timeline.scheduleExplosions(std::move(spawns));
    double warm = start;
    for (const ShipTrack& track : input.ships)
        warm = std::min(warm, track.startTime());
    timeline.warmUp(std::max(warm, start - 600.0), start, input.views.front().camera(start).position);
}

/// Image encoding (EXR ZIP + PNG) on a worker thread while the next frame renders; at most two frames wait
/// (WorkerQueue.h). Each frame's EXR hash comes back through a future and is filled into its JSON entry.
class ImageWriter {
public:
    explicit ImageWriter(bool enabled) {
        if (enabled)
            mEncoder.emplace(2);
    }
    /// Frame `frame` of view `view`: its EXR (whose hash goes into viewFrames[view][frame]) and PNG.
    void frame(size_t view, size_t frame, long long k, fs::path exr, fs::path png, int w, int h,
               const std::vector<float>& scene, const std::vector<float>& display,
               const capture::Metadata& meta, capture::Compression c) {
        mPending.push_back({view, frame, k, mEncoder->submit([=, sceneCopy = scene, displayCopy = display] {
                                const uint64_t hash =
                                    capture::writeExrHalf(exr, w, h, 4, sceneCopy.data(), meta, c);
                                capture::writePng8(png, w, h, 4, displayCopy.data(), c);
                                return hash;
                            })});
    }
    /// An extra view's PNG (no hash).
    void png(size_t view, long long k, fs::path path, int w, int h, const std::vector<float>& display,
             capture::Compression c) {
        mPending.push_back({view, std::string::npos, k, mEncoder->submit([=, displayCopy = display] {
                                capture::writePng8(path, w, h, 4, displayCopy.data(), c);
                                return uint64_t{0};
                            })});
    }
    /// Fills the hashes of the finished images (all of them with `wait`); rethrows a failed write as soon
    /// as it is seen.
    void collect(bool wait, std::vector<nlohmann::json>& viewFrames) {
        while (!mPending.empty() && (wait || mPending.front().hash.wait_for(std::chrono::seconds(0)) ==
                                                 std::future_status::ready)) {
            Pending p = std::move(mPending.front());
            mPending.pop_front();
            const uint64_t h = p.hash.get();
            if (p.frame != std::string::npos)
                viewFrames[p.view][p.frame]["exr_pixel_hash"] = hex64(h);
        }
    }

    /// The run's frame index of the oldest image still being written (every image of earlier frames is
    /// on disk); LLONG_MAX when none is.
    long long oldestPending() const {
        return mPending.empty() ? std::numeric_limits<long long>::max() : mPending.front().k;
    }

private:
    struct Pending {
        size_t view, frame; // viewFrames[view][frame]; frame == npos: an extra view's PNG (no hash)
        long long k;        // the run's frame index
        std::future<uint64_t> hash;
    };
    std::deque<Pending> mPending;
    std::optional<WorkerQueue<uint64_t>> mEncoder;
};

/// What one view of one frame cost and did (OceanStats, EffectCounters): absent effects show zeros.
nlohmann::json countersJson(const ocean::OceanStats& st, const ocean::EffectCounters& fx, int objectsDrawn,
                            size_t tonemapPasses) {
    auto kindJson = [](const ocean::EffectKindStats& ks) {
        return nlohmann::json{{"active", ks.active}, {"drawn", ks.drawn},     {"passes", ks.passes},
                              {"draws", ks.draws},   {"uploads", ks.uploads}, {"vertices", ks.vertices}};
    };
    return {{"passes", st.passes},
            {"draws", st.draws},
            {"uploads", st.uploads},
            {"vertices", st.vertices},
            {"programs_built", st.programsBuilt},
            {"compute_shaded", st.computeShaded},
            {"shade_tiled", st.shadeTiled},
            {"explosions", kindJson(st.explosions)},
            {"wakes", kindJson(st.wakes)},
            {"effect_field",
             {{"passes", st.effectField.passes},
              {"tiles", st.effectField.tiles},
              {"cleared", st.effectField.cleared},
              {"texels", st.effectField.texels},
              {"uploads", st.effectField.uploads}}},
            {"explosions_spawned", fx.spawned},
            {"effects_ended", fx.ended},
            {"explosions_dropped", fx.droppedExplosions},
            {"wakes_dropped", fx.droppedWakes},
            {"events_rejected", fx.rejected},
            {"spots", st.spots},
            {"spots_dropped", st.spotsDropped},
            {"spots_rejected", st.spotsRejected},
            {"objects_drawn", objectsDrawn},
            {"tonemap_passes", tonemapPasses}};
}

nlohmann::json poseJson(const Pose& pose) {
    return {{"x_m", pose.position.x},         {"y_m", pose.position.y},     {"z_m", pose.position.z},
            {"heading_deg", pose.headingDeg}, {"pitch_deg", pose.pitchDeg}, {"roll_deg", pose.rollDeg}};
}

/// The objects alive at t, posed once per frame and drawn by every view (by id: a view may hide one).
using AliveObjects = std::vector<std::pair<uint64_t, DrawnObject>>;

/// One run of `pacifica replay`. The members are built in declaration order: everything that can fail
/// without touching the output directory first (colour, GL, scene, extra views), then the output
/// transaction, the video and the image writer (declared after the transaction: it finishes its jobs
/// before the staging directory goes). renderFrame() advances the simulation once per frame; every view
/// renders that same state.
class ReplayRun {
public:
    ReplayRun(const ReplayOptions& o, const ReplayInput& input, const FramePlan& plan, Clock::time_point t0);
    void renderFrame(long long k);
    /// Waits for every image (or the first failure), finishes the video, writes summary.json last.
    void finish();
    const ReplayRunInfo& info() const { return mInfo; }

private:
    // --profile: the replay's own GPU passes, timed with the ocean's clock.
    enum ReplayPass { PassObjects, PassTonemap, ReplayPassCount };
    struct ViewTimes {
        Clock::time_point readStart, readEnd, encodeEnd;
        double extraTonemapMs = 0.0; // extra views: their tonemap + readback, timed on the CPU
    };
    int drawView(size_t vi, const ocean::OceanFrame& frame, const AliveObjects& alive);
    nlohmann::json renderView(long long k, size_t vi, double t, const AliveObjects& alive);
    capture::Metadata frameMetadata(long long k, double t, const Pose& pose, const ReplayView& view) const;
    nlohmann::json extraViewPasses(size_t vi, long long k, const std::string& name, ViewTimes& times);
    nlohmann::json passJson(const ViewTimes& times);
    void progress(long long k, double t, Clock::time_point now) const;
    void floatShips(double t, AliveObjects& alive);
    void placeLights(double t);
    AliveObjects advance(double t);
    std::string frameBase(size_t vi, long long k) const;
    bool keepFrame(long long k);
    void landFrames();
    nlohmann::json summary(double totalSeconds) const;
    nlohmann::json chunkJson() const;

    const ReplayOptions& o;
    const ReplayInput& input;
    const FramePlan plan;
    const Clock::time_point t0;
    const bool writeImages; // --video without --out: the video only
    nlohmann::json environmentJson;
    const ocean::OceanDesc oceanDesc;
    const std::string environmentName;
    color::ColorPipeline colour;
    std::unique_ptr<gl::GlContext> context;
    ecs::Registry registry; // the ocean entity, then the ships
    const ecs::Entity oceanEntity;
    ocean::OceanRenderer renderer;
    std::vector<std::unique_ptr<gl::FrameTargets>> targets; // one set per view
    color::Tonemapper tonemapper;
    std::vector<ExtraView> extraViews;
    gl::GpuTimer gpuTimer;
    std::unique_ptr<gl::PassTimer> passTimer;
    std::map<std::string, std::vector<double>> passSamples; // per pass name, one value per view frame
    std::vector<ReplayObject> objects;
    std::unique_ptr<ObjectRenderer> objectRenderer;
    ecs::EventQueue events;
    ocean::EffectsSystem effects;
    ocean::EffectsTimeline timeline;
    std::optional<OutputTransaction> out;
    std::unique_ptr<VideoWriter> video;
    ImageWriter images;
    std::vector<nlohmann::json> viewFrames;
    std::vector<float> scene, display;
    std::vector<double> frameWallMs;
    const std::vector<ReplayLight> lights;  // --light
    std::vector<ecs::Entity> lightEntities; // their SpotLight components at the frame's time (placeLights)
    ocean::SeaQuery sea;                    // the recorded ships' hull points (floatShips)
    std::vector<glm::dvec2> hullPoints;
    std::vector<double> hullHeights;
    double firstFrameSeconds = 0.0;
    // --frames: the frames rendered and kept, the pre-roll's time, and the rendered frames whose images are
    // still being written (landFrames), with their index in viewFrames per view.
    long long framesRendered = 0, framesKept = 0;
    double prerollSeconds = 0.0;
    struct Landing {
        long long k;
        std::vector<size_t> index;
    };
    std::deque<Landing> landing;
    const bool tty;
    ReplayRunInfo mInfo;
};

std::vector<std::unique_ptr<gl::FrameTargets>> makeTargets(const std::vector<ReplayView>& views) {
    std::vector<std::unique_ptr<gl::FrameTargets>> targets;
    for (const ReplayView& v : views)
        targets.push_back(std::make_unique<gl::FrameTargets>(v.width, v.height));
    return targets;
}

ecs::Entity addOcean(ecs::Registry& registry, const ocean::OceanDesc& desc) {
    const ecs::Entity e = registry.create();
    registry.emplace<ocean::OceanComponent>(e, ocean::makeOcean(desc));
    return e;
}

ReplayRun::ReplayRun(const ReplayOptions& o_, const ReplayInput& input_, const FramePlan& plan_,
                     Clock::time_point t0_)
    : o(o_), input(input_), plan(plan_), t0(t0_), writeImages(o.writeImages && !o.outDir.empty()),
      oceanDesc(oceanWithEnvironment(o, environmentJson)),
      environmentName(o.environment ? o.environment->filename().string() : "procedural"),
      colour(replayColour(o)),
      context(gl::createHeadlessContext(
          {.eglDevice = o.eglDevice, .cudaDevice = o.eglDeviceAuto ? visibleCudaDevice() : o.cudaDevice})),
      oceanEntity(addOcean(registry, oceanDesc)), targets(makeTargets(input.views)), tonemapper(colour),
      extraViews(makeExtraViews(o, colour)), gpuTimer(context->info()), effects(registry, events),
      timeline(registry, events, effects), images(writeImages),
      viewFrames(input.views.size(), nlohmann::json::array()),
      lights(parseReplayLights(o.lights, input, std::exp2(o.exposureEv))),
      tty(o.progress && isatty(STDERR_FILENO)) {
    if (const ocean::Status s = sea.init(registry.get<ocean::OceanComponent>(oceanEntity)); !s)
        throw std::runtime_error("replay: " + s.message);
    if (o.profile) { // the ocean's passes (OceanRenderer::setPassTiming) and the replay's, one clock
        renderer.setPassTiming(ocean::passClock(gpuTimer.clock()));
        passTimer = std::make_unique<gl::PassTimer>(gpuTimer.clock(), ReplayPassCount);
    }
    if (o.objects)
        objects = replayObjects(input, plan.start, plan.end);
    if (!objects.empty())
        objectRenderer = std::make_unique<ObjectRenderer>();
    if (o.events)
        scheduleEvents(timeline, input, plan.start);
    if (!o.outDir.empty()) {
        out.emplace(o.outDir, o.frames.has_value()); // a chunk shares DIR with the run's other chunks
        if (out->staleRemoved() > 0)
            logInfo("replay: removed " + std::to_string(out->staleRemoved()) + " staging folder(s) of " +
                    "earlier runs into " + o.outDir.string() + " that did not finish (killed)");
    }
    if (o.video)
        video = std::make_unique<VideoWriter>(*o.video, input.views.front().width, input.views.front().height,
                                              o.fps);
    mInfo = {context->info().renderer, context->info().version, gpuTimer.clockName(),
             colour.configDescription(), &gpuTimer.samples()};
}

/// Frame k: the simulation advanced to its time, then (unless it is --frames' pre-roll or a frame an
/// earlier run of the chunk left whole) every view rendered.
void ReplayRun::renderFrame(long long k) {
    const auto f0 = Clock::now();
    const double t = plan.timeOf(k);
    const AliveObjects alive = advance(t);
    if (o.frames && k < o.frames->first) { // the pre-roll: the chunk starts from the one-process run's state
        prerollSeconds += std::chrono::duration<double>(Clock::now() - f0).count();
        return;
    }
    if (o.frames && writeImages && keepFrame(k)) {
        ++framesKept;
        return;
    }
    Landing landed{k, {}};
    for (size_t vi = 0; vi < input.views.size(); ++vi) {
        nlohmann::json fj = renderView(k, vi, t, alive);
        landed.index.push_back(viewFrames[vi].size());
        viewFrames[vi].push_back(std::move(fj));
    }
    if (o.frames && writeImages)
        landing.push_back(std::move(landed));
    images.collect(false, viewFrames);
    landFrames();
    const auto f1 = Clock::now();
    frameWallMs.push_back(msBetween(f0, f1));
    if (framesRendered++ == 0)
        firstFrameSeconds = std::chrono::duration<double>(f1 - t0).count();
    if (tty)
        progress(k, t, f1);
}

/// The simulation at time t, rendered or not: the effects' timeline stepped (wakes extend their paths,
/// explosions start), the recording's objects at t, the ships floated on the sea.
AliveObjects ReplayRun::advance(double t) {
    timeline.step(t, input.views.front().camera(t).position);
    AliveObjects alive;
    for (const ReplayObject& obj : objects)
        if (t >= obj.start && t <= obj.end)
            alive.push_back({obj.id, {obj.shape, obj.length, obj.track->poseAt(t)}});
    floatShips(t, alive);
    placeLights(t);
    return alive;
}

/// --light: the spot lights at time t, as SpotLight components the registry's adapter hands the renderer.
void ReplayRun::placeLights(double t) {
    for (const ecs::Entity e : lightEntities)
        registry.destroy(e);
    lightEntities.clear();
    for (const ocean::SpotLight& s : replayLightsAt(lights, input, t, std::exp2(o.exposureEv))) {
        lightEntities.push_back(registry.create());
        registry.emplace<ocean::SpotLight>(lightEntities.back(), s);
    }
}

/// "frame_00012", or "<view>_frame_00012" for a named view.
std::string ReplayRun::frameBase(size_t vi, long long k) const {
    const std::string& view = input.views[vi].name;
    char number[32];
    std::snprintf(number, sizeof number, "frame_%05lld", k);
    return view.empty() ? std::string(number) : view + "_" + number;
}

/// --frames' resume: frame k is kept when every view's sidecar names this run and matches its files; its
/// summary entries come from the sidecars.
bool ReplayRun::keepFrame(long long k) {
    std::vector<nlohmann::json> entries;
    for (size_t vi = 0; vi < input.views.size(); ++vi) {
        std::optional<nlohmann::json> e = keptFrame(o.outDir, frameBase(vi, k), o.runKey);
        if (!e)
            return false;
        entries.push_back(std::move(*e));
    }
    for (size_t vi = 0; vi < input.views.size(); ++vi)
        viewFrames[vi].push_back(std::move(entries[vi]));
    return true;
}

/// --frames: every rendered frame whose images are all written lands in DIR, view by view: its files
/// renamed in, then its sidecar (ChunkFrames.h). A chunk killed at any point leaves whole frames only.
void ReplayRun::landFrames() {
    while (!landing.empty() && landing.front().k < images.oldestPending()) {
        const Landing& l = landing.front();
        for (size_t vi = 0; vi < input.views.size(); ++vi) {
            const nlohmann::json& entry = viewFrames[vi][l.index[vi]];
            out->publish(entryFiles(entry));
            out->land(sidecarName(frameBase(vi, l.k)), sidecarText(o.outDir, o.runKey, entry));
        }
        landing.pop_front();
    }
}

/// The recorded ships ride the sea drawn under them (ocean/Buoyancy.h): the heave, pitch and roll of the
/// plane through the sea's heights under each hull's points, added to what the recording says (DCS records
/// its ships level at sea level), in one batched query; the wakes left out, as the game's ships do.
void ReplayRun::floatShips(double t, AliveObjects& alive) {
    using ocean::HULL_POINTS;
    constexpr double SHIP_HALF_BEAM = 0.07; // of the length: ObjectRenderer's hull (beam 0.14 L)
    auto isShip = [](const DrawnObject& d) {
        return d.shape == ObjectShape::Ship || d.shape == ObjectShape::Carrier;
    };
    hullPoints.clear();
    for (const auto& [id, d] : alive) {
        if (!isShip(d))
            continue;
        hullPoints.resize(hullPoints.size() + HULL_POINTS);
        ocean::hullPoints(glm::dvec2(d.pose.position), d.pose.headingDeg, d.length, SHIP_HALF_BEAM * d.length,
                          std::span<glm::dvec2, HULL_POINTS>(hullPoints.end() - HULL_POINTS, HULL_POINTS));
    }
    if (hullPoints.empty())
        return;
    const ocean::RegistryEffects fx(registry);
    ocean::EffectsView view = fx.view();
    view.wakes = {};
    hullHeights.resize(hullPoints.size());
    ocean::Status s = sea.update(t, view);
    if (s)
        s = sea.heights(hullPoints, hullHeights);
    (void)sea.update(t, {}); // let the registry's effects go (their storage moves); the same t: no resampling
    if (!s)
        throw std::runtime_error("replay: the ships' sea heights: " + s.message);
    size_t k = 0;
    for (auto& [id, d] : alive) {
        if (!isShip(d))
            continue;
        const ocean::HullPose p =
            ocean::floatHull(std::span<const double, HULL_POINTS>(&hullHeights[k], HULL_POINTS), d.length,
                             SHIP_HALF_BEAM * d.length);
        k += HULL_POINTS;
        d.pose.position.z += p.heave;
        d.pose.pitchDeg += p.pitchDeg;
        d.pose.rollDeg += p.rollDeg;
    }
}

/// The sea, the objects and the main tonemap of one view, inside the GPU timer (and the pass timer with
/// --profile). Returns the objects drawn.
int ReplayRun::drawView(size_t vi, const ocean::OceanFrame& frame, const AliveObjects& alive) {
    const ReplayView& view = input.views[vi];
    gl::FrameTargets& target = *targets[vi];
    std::vector<DrawnObject> drawn;
    for (const auto& [id, object] : alive)
        if (id != view.hiddenObject.value_or(~uint64_t(0)))
            drawn.push_back(object);
    const double drawEarthRadius = oceanDesc.earthCurvature ? ocean::EARTH_RADIUS : 0.0;
    gpuTimer.begin();
    render(renderer, registry, frame);
    if (passTimer)
        passTimer->beginFrame();
    const int objectsDrawn =
        objectRenderer
            ? objectRenderer->draw(drawn, frame.camera, target.sceneFramebuffer().id(), view.width,
                                   view.height, oceanDesc.lighting.sunDirection, drawEarthRadius,
                                   oceanDesc.lighting.sunIntensity / ocean::LightingDesc{}.sunIntensity)
            : 0;
    if (passTimer)
        passTimer->mark(PassObjects);
    tonemapper.run(target.sceneColor(), target.displayFramebuffer(), view.width, view.height);
    if (passTimer) {
        passTimer->mark(PassTonemap);
        passTimer->endFrame();
    }
    gpuTimer.end();
    return objectsDrawn;
}

capture::Metadata ReplayRun::frameMetadata(long long k, double t, const Pose& pose,
                                           const ReplayView& view) const {
    capture::Metadata meta;
    meta.numbers = {{"frame", static_cast<double>(k)},   {"time_s", t},
                    {"camera_x_m", pose.position.x},     {"camera_y_m", pose.position.y},
                    {"camera_z_m", pose.position.z},     {"camera_heading_deg", pose.headingDeg},
                    {"camera_pitch_deg", pose.pitchDeg}, {"camera_roll_deg", pose.rollDeg}};
    meta.strings = {{"ocio_config", colour.configDescription()},
                    {"ocio_display", colour.selectedDisplay()},
                    {"ocio_view", colour.selectedView()},
                    {"gl_renderer", context->info().renderer},
                    {"flight", o.flight.filename().string()},
                    {"rig", view.rig},
                    {"environment", environmentName}};
    return meta;
}

/// One view of frame k: drawn, read back, its images queued (or its pixels hashed), the extra views
/// tonemapped; returns the frame's summary.json entry.
nlohmann::json ReplayRun::renderView(long long k, size_t vi, double t, const AliveObjects& alive) {
    const ReplayView& view = input.views[vi];
    gl::FrameTargets& target = *targets[vi];
    const Pose pose = view.camera(t);
    const ocean::OceanFrame frame =
        ocean::makeOceanFrame(pose, view.fovYDeg * static_cast<float>(std::numbers::pi / 180.0), view.width,
                              view.height, t, target.sceneFramebuffer().id());
    const int objectsDrawn = drawView(vi, frame, alive);
    ViewTimes times;
    times.readStart = Clock::now();
    target.readScene(scene);
    target.readDisplay(display);
    times.readEnd = Clock::now();

    const std::string name = frameBase(vi, k);
    const std::string exrName = name + ".exr", pngName = name + ".png";
    nlohmann::json fj;
    fj["index"] = k;
    fj["time_s"] = t;
    fj["pose"] = poseJson(pose);
    if (writeImages) {
        images.frame(vi, viewFrames[vi].size(), k, out->staged(exrName), out->staged(pngName), view.width,
                     view.height, scene, display, frameMetadata(k, t, pose, view), o.imageCompression);
        fj["exr"] = exrName;
        fj["png"] = pngName;
        fj["exr_pixel_hash"] = nullptr; // filled by ImageWriter::collect
    } else {
        const std::vector<uint16_t> half = capture::toHalf(scene.data(), scene.size());
        fj["exr_pixel_hash"] = hex64(capture::hashHalfPixels(half.data(), half.size()));
    }
    if (video && vi == 0)
        video->addFrame(display.data());
    nlohmann::json extraPngs = extraViewPasses(vi, k, name, times);
    if (writeImages && !extraViews.empty())
        fj["extra_views"] = std::move(extraPngs);
    times.encodeEnd = Clock::now();
    fj["counters"] =
        countersJson(renderer.lastStats(), effects.counters(), objectsDrawn, 1 + extraViews.size());
    if (passTimer)
        fj["pass_ms"] = passJson(times);
    return fj;
}

/// The extra views' tonemaps of view vi (and their PNGs); returns their entries for summary.json.
nlohmann::json ReplayRun::extraViewPasses(size_t vi, long long k, const std::string& name, ViewTimes& times) {
    const ReplayView& view = input.views[vi];
    gl::FrameTargets& target = *targets[vi];
    nlohmann::json extraPngs = nlohmann::json::array();
    for (ExtraView& e : extraViews) {
        const auto e0 = Clock::now();
        e.pass->run(target.sceneColor(), target.displayFramebuffer(), view.width, view.height);
        if (writeImages)
            target.readDisplay(display);
        times.extraTonemapMs += msBetween(e0, Clock::now());
        if (writeImages) {
            const std::string png = name + "." + e.suffix + ".png";
            images.png(vi, k, out->staged(png), view.width, view.height, display, o.imageCompression);
            extraPngs.push_back({{"view", e.view}, {"png", png}});
        }
    }
    return extraPngs;
}

/// --profile: the ocean's and the replay's pass timers (on hardware the newest frame whose timestamps have
/// arrived, a few frames behind; on llvmpipe this one), readback, and the main thread's time handing the
/// images to the encoder (copies; waits when two frames are queued) or hashing them, and the video frame
/// (the encoding itself overlaps rendering).
nlohmann::json ReplayRun::passJson(const ViewTimes& times) {
    const ocean::OceanPassTimes& pt = renderer.lastStats().passTimes;
    nlohmann::json pj;
    if (pt.measured)
        pj = {{"compute", pt.computeMs},
              {"sky", pt.skyMs},
              {"sea", pt.seaMs},
              {"effects", pt.effectsMs},
              {"shade", pt.shadeMs}};
    if (auto own = passTimer->poll()) {
        pj["objects"] = (*own)[PassObjects];
        pj["tonemap"] = (*own)[PassTonemap];
    }
    pj["readback"] = msBetween(times.readStart, times.readEnd);
    pj["encode"] = msBetween(times.readEnd, times.encodeEnd) - times.extraTonemapMs;
    if (!extraViews.empty())
        pj["extra_views"] = times.extraTonemapMs;
    for (const auto& [pass, value] : pj.items())
        passSamples[pass].push_back(value.get<double>());
    return pj;
}

void ReplayRun::progress(long long k, double t, Clock::time_point now) const {
    const double elapsed = std::chrono::duration<double>(now - t0).count() - firstFrameSeconds;
    const double eta =
        k > 0 ? elapsed / static_cast<double>(k) * static_cast<double>(plan.count - k - 1) : 0.0;
    const int width = 24;
    const int filled = static_cast<int>(width * (k + 1) / plan.count);
    std::fprintf(stderr, "\rpacifica replay [%.*s%*s] %lld/%lld  t=%.2f s  ETA %d:%02d   ", filled,
                 "########################", width - filled, "", k + 1, plan.count, t,
                 static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
}

void ReplayRun::finish() {
    if (tty)
        std::fprintf(stderr, "\n");
    images.collect(true, viewFrames); // every image written (or the first failure thrown) before the summary
    landFrames();
    if (video)
        video->finish(); // the video is in place only now; a failure before leaves none
    gpuTimer.drain();    // timer queries of the last frames are still in flight on real GPUs
    const double totalSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
    if (out && o.frames)
        out->land(chunkSummaryName(*o.frames), reportText(summary(totalSeconds)));
    else if (out)
        out->commit(summary(totalSeconds));
    if (o.frames)
        logInfo("replay: frames " + std::to_string(o.frames->first) + "-" + std::to_string(o.frames->last) +
                ": " + std::to_string(framesRendered) + " rendered, " + std::to_string(framesKept) +
                " kept (their checksums matched), after a pre-roll of " + std::to_string(o.frames->first) +
                " frames in " + shortNumber(prerollSeconds) + " s; " + shortNumber(totalSeconds) +
                " s in all -> " + o.outDir.string());
    else
        logInfo("replay: " + std::to_string(plan.count) + " frames in " + std::to_string(totalSeconds) +
                " s -> " + (o.outDir.empty() ? o.video->string() : o.outDir.string()));
}

/// summary's "chunk" (--frames): the range, the pre-roll, what was rendered and kept, and where.
nlohmann::json ReplayRun::chunkJson() const {
    char host[256] = {};
    gethostname(host, sizeof host - 1);
    return {{"first", o.frames->first},
            {"last", o.frames->last},
            {"run_frames", plan.count},
            {"preroll_frames", o.frames->first},
            {"preroll_s", prerollSeconds},
            {"rendered", framesRendered},
            {"kept", framesKept},
            {"host", host},
            {"gl_renderer", context->info().renderer},
            {"gl_device", context->info().device},
            {"cuda_visible_devices", environment("CUDA_VISIBLE_DEVICES")},
            {"slurm_job_id", environment("SLURM_JOB_ID")},
            {"slurm_array_task_id", environment("SLURM_ARRAY_TASK_ID")},
            {"run_key", o.runKey}};
}

/// summary.json: the run's inputs, GL and OCIO, one entry per view with its frames ("frames" repeats the
/// first view's, for single-view readers), and the timings.
nlohmann::json ReplayRun::summary(double totalSeconds) const {
    const gl::ContextInfo& gl = context->info();
    nlohmann::json s;
    s["flight"] = o.flight.string();
    s["format"] = input.format;
    s["recording"] = input.summary;
    s["gl"] = {{"vendor", gl.vendor},     {"renderer", gl.renderer}, {"version", gl.version},
               {"platform", gl.platform}, {"device", gl.device},     {"uuid", gl.uuid}};
    s["ocio"] = {{"config", colour.configDescription()},
                 {"input", colour.input().empty() ? std::string("scene_linear") : colour.input()},
                 {"display", colour.selectedDisplay()},
                 {"view", colour.selectedView()},
                 {"extra_views", o.extraViews}};
    s["environment"] = environmentJson;
    s["exposure_ev"] = o.exposureEv; // the EXR holds radiance x 2^exposure_ev
    s["size"] = {input.views.front().width, input.views.front().height};
    s["fps"] = o.fps;
    s["speed"] = o.speed;
    s["start_s"] = plan.start;
    s["end_s"] = plan.end;
    s["images_written"] = writeImages;
    s["video"] = o.video ? nlohmann::json{{"file", o.video->string()}, {"frames", video->frames()}}
                         : nlohmann::json(nullptr);
    s["hash"] = "XXH64 of the scene-linear half-float RGBA pixels, rows top-down";
    s["events"] = {{"applied", o.events},
                   {"explosions", o.events ? input.explosions.size() : 0},
                   {"ships", o.events ? input.ships.size() : 0},
                   {"explosions_dropped_total", effects.counters().totalDroppedExplosions}};
    nlohmann::json views = nlohmann::json::array();
    for (size_t vi = 0; vi < input.views.size(); ++vi) {
        const ReplayView& v = input.views[vi];
        views.push_back({{"name", v.name},
                         {"rig", v.rig},
                         {"size", {v.width, v.height}},
                         {"fov_deg", v.fovYDeg},
                         {"frames", viewFrames[vi]}});
    }
    s["views"] = std::move(views);
    s["frames"] = viewFrames.front();
    s["timings"] = {
        {"gpu_clock", gpuTimer.clockName()},
        {"gpu_ms_median", median(gpuTimer.samples())},
        {"frame_wall_clock", "steady_clock, whole frame (all views) incl. readback and image writes"},
        {"frame_wall_ms_median", median(frameWallMs)},
        {"time_to_first_frame_s", firstFrameSeconds},
        {"total_s", totalSeconds},
        {"frames_per_second_overall", static_cast<double>(framesRendered) / totalSeconds},
        {"frames_per_second_steady", 1000.0 / std::max(median(frameWallMs), 1e-9)}};
    if (o.frames)
        s["chunk"] = chunkJson();
    if (passTimer) {
        nlohmann::json medians;
        for (const auto& [name, v] : passSamples)
            medians[name] = median(v);
        s["timings"]["passes_ms_median"] = std::move(medians);
        s["timings"]["pass_clock"] = std::string(renderer.passTimingClock()) +
                                     " (GPU passes); steady_clock (readback, encode, extra_views)";
    }
    return s;
}

} // namespace

struct ReplaySession::State {
    Clock::time_point t0;
    ReplayOptions o;
    ReplayInput input;
    FramePlan plan;
    std::optional<ReplayRun> run;
};

/// Validate everything first (options, the flight, the frames, ffmpeg), then build the run.
ReplaySession::ReplaySession(const ReplayOptions& o) : mState(std::make_unique<State>()) {
    State& s = *mState;
    s.t0 = Clock::now();
    s.o = o;
    checkReplayOptions(s.o);
    if (!s.o.outDir.empty())
        OutputTransaction::checkWritable(s.o.outDir); // before a GL context is made or a frame rendered
    s.input = loadReplayInput(s.o.flight, s.o.rigs, s.o.width, s.o.height, s.o.fovYDeg);
    s.plan = planFrames(s.o, s.input);
    if (s.o.video)
        VideoWriter::findFfmpeg(*s.o.video); // extension and ffmpeg checked before anything is written
    s.run.emplace(s.o, s.input, s.plan, s.t0);
}

ReplaySession::~ReplaySession() = default;

long long ReplaySession::frameCount() const {
    return mState->plan.count;
}

FrameRange ReplaySession::frameRange() const {
    return mState->o.frames.value_or(FrameRange{0, mState->plan.count - 1});
}

void ReplaySession::renderFrame(long long k) {
    mState->run->renderFrame(k);
}

void ReplaySession::finish() {
    mState->run->finish();
}

const ReplayRunInfo& ReplaySession::info() const {
    return mState->run->info();
}

std::string visibleCudaDevice() {
    const char* v = std::getenv("CUDA_VISIBLE_DEVICES");
    const std::string first = std::string(v ? v : "").substr(0, std::string(v ? v : "").find(','));
    // An index there is the GPU's number before the variable applies; CUDA, and NVIDIA's EGL with it, number
    // the visible GPUs from 0, so the first one is CUDA device 0 of this process (seen on 2x H200:
    // CUDA_VISIBLE_DEVICES=1 leaves EGL device 1 as CUDA device 0). A GPU-UUID names it either way.
    if (first.empty() || first.rfind("GPU-", 0) == 0)
        return first;
    return "0";
}

long long replayFrameCount(const ReplayOptions& o) {
    checkReplayOptions(o);
    const ReplayInput input = loadReplayInput(o.flight, o.rigs, o.width, o.height, o.fovYDeg);
    ReplayOptions whole = o;
    whole.frames.reset(); // the run's count, whatever chunk the options name
    return planFrames(whole, input).count;
}

/// A failure anywhere removes what the run wrote (the session's output transaction is never committed).
void runReplay(const ReplayOptions& o) {
    ReplaySession session(o);
    for (long long k = 0; k <= session.frameRange().last; ++k)
        session.renderFrame(k);
    session.finish();
}

} // namespace pacifica::tools
