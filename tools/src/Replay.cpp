// Replay implementation: validate everything first, then render frame by frame; on any failure remove
// what this run wrote. summary.json is written last and atomically.
#include "Replay.h"

#include "FlightPath.h"
#include "ReplayInput.h"
#include "VideoWriter.h"
#include "WorkerQueue.h"
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
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <future>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
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

std::string hex64(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

/// Output as a transaction: frames are written into a hidden staging directory inside DIR and moved into
/// DIR only when the whole run succeeded (summary.json last), so a failed run leaves DIR exactly as it was
/// (files of an earlier run included) and a directory it had to create is removed again.
class OutputTransaction {
public:
    explicit OutputTransaction(fs::path dir) : mDir(std::move(dir)) {
        std::error_code ec;
        if (!fs::exists(mDir, ec)) {
            // Remember the outermost directory we create, to remove exactly that on failure.
            fs::path probe = mDir;
            while (!probe.empty() && !fs::exists(probe, ec)) {
                mCreatedRoot = probe;
                probe = probe.parent_path();
            }
            fs::create_directories(mDir, ec);
            if (ec)
                throw UsageError("--out: cannot create directory '" + mDir.string() + "': " + ec.message());
        } else if (!fs::is_directory(mDir, ec)) {
            throw UsageError("--out: '" + mDir.string() + "' exists and is not a directory");
        }
        mStaging = mDir / (".pacifica-staging-" + std::to_string(getpid()));
        fs::create_directory(mStaging, ec);
        if (ec)
            throw UsageError("--out: cannot write into '" + mDir.string() + "': " + ec.message());
    }
    ~OutputTransaction() {
        std::error_code ec;
        fs::remove_all(mStaging, ec);
        if (!mCommitted && !mCreatedRoot.empty())
            fs::remove_all(mCreatedRoot, ec); // everything under it is ours
    }
    /// Where to write a file that will appear as DIR/name on commit.
    fs::path staged(const std::string& name) {
        mNames.push_back(name);
        return mStaging / name;
    }
    /// Moves every staged file into DIR, then writes summary.json (atomically) last. Files of an earlier run
    /// that get replaced are kept aside until the end, so a failure part-way puts DIR back as it was.
    void commit(const nlohmann::json& summary) {
        std::error_code ec;
        for (const std::string& n :
             mNames) { // check first: never half-commit over something we can't replace
            const fs::path dest = mDir / n;
            if (fs::exists(dest, ec) && !fs::is_regular_file(dest, ec))
                throw std::runtime_error(dest.string() +
                                         ": exists and is not a regular file; not replacing it");
        }
        const fs::path old = mStaging / ".replaced";
        fs::create_directory(old);
        std::vector<std::string> moved, replaced;
        try {
            for (const std::string& n : mNames) {
                if (fs::exists(mDir / n, ec)) {
                    fs::rename(mDir / n, old / n);
                    replaced.push_back(n);
                }
                fs::rename(mStaging / n, mDir / n);
                moved.push_back(n);
            }
            writeJsonAtomic(mDir / "summary.json", summary);
        } catch (...) {
            for (const std::string& n : moved)
                fs::remove(mDir / n, ec);
            for (const std::string& n : replaced)
                fs::rename(old / n, mDir / n, ec);
            throw;
        }
        mCommitted = true;
    }

private:
    static void writeJsonAtomic(const fs::path& path, const nlohmann::json& j);
    fs::path mDir, mStaging, mCreatedRoot;
    std::vector<std::string> mNames;
    bool mCommitted = false;
};

void OutputTransaction::writeJsonAtomic(const fs::path& path, const nlohmann::json& j) {
    const fs::path tmp =
        path.parent_path() / ("." + path.filename().string() + ".tmp-" + std::to_string(getpid()));
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << j.dump(2) << '\n';
        out.flush();
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw std::runtime_error(path.string() + ": cannot write summary");
        }
    }
    fs::rename(tmp, path);
}

/// --env: reads an HDR lat-long image and validates it into an EnvironmentMap (alpha dropped). Errors name
/// the file: "FILE: pixel (x,y) is NaN", "FILE: expected 3 (RGB) or 4 (RGBA) channels, got 1".
std::shared_ptr<const ocean::EnvironmentMap> loadEnvironment(const fs::path& file) {
    const capture::Image image = capture::readImage(file); // CaptureError "FILE: ..." if missing/garbled
    if (image.channels != 3 && image.channels != 4)
        throw std::runtime_error(file.string() + ": expected 3 (RGB) or 4 (RGBA) channels, got " +
                                 std::to_string(image.channels));
    const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
    std::vector<float> rgb(pixels * 3);
    for (size_t p = 0; p < pixels; ++p)
        for (size_t c = 0; c < 3; ++c)
            rgb[p * 3 + c] = image.pixels[p * static_cast<size_t>(image.channels) + c];
    try {
        return std::make_shared<const ocean::EnvironmentMap>(
            ocean::makeEnvironmentMap(image.width, image.height, std::move(rgb)));
    } catch (const ocean::EnvironmentMapError& e) {
        throw std::runtime_error(file.string() + ": " + e.problem());
    }
}

} // namespace

void parseSize(const std::string& text, int& width, int& height) {
    const size_t x = text.find('x');
    auto bad = [&] {
        return UsageError("--size: expected WxH with 16 <= W,H <= 8192 (e.g. 640x360), got '" + text + "'");
    };
    if (x == std::string::npos)
        throw bad();
    try {
        size_t used = 0;
        width = std::stoi(text.substr(0, x), &used);
        if (used != x)
            throw bad();
        height = std::stoi(text.substr(x + 1), &used);
        if (used != text.size() - x - 1)
            throw bad();
    } catch (const std::logic_error&) {
        throw bad();
    }
    if (width < 16 || height < 16 || width > 8192 || height > 8192)
        throw bad();
}

void runReplay(const ReplayOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!std::isfinite(o.fps) || o.fps <= 0.0 || o.fps > 1000.0)
        throw UsageError("--fps must be in (0, 1000], got " + std::to_string(o.fps));
    if (!std::isfinite(o.fovYDeg) || o.fovYDeg < 1.0f || o.fovYDeg > 170.0f)
        throw UsageError("--fov must be in [1, 170] degrees, got " + std::to_string(o.fovYDeg));
    if (!std::isfinite(o.speed) || o.speed <= 0.0 || o.speed > 1e6)
        throw UsageError("--speed must be in (0, 1e6], got " + std::to_string(o.speed));
    if (o.maxFrames < 1)
        throw UsageError("--max-frames must be >= 1, got " + std::to_string(o.maxFrames));
    if (o.outDir.empty() && !o.video)
        throw UsageError("--out: an output directory is required (or --video FILE alone)");
    const bool writeImages = o.writeImages && !o.outDir.empty(); // --video without --out: the video only

    // 1. Everything that can be checked without touching the output directory.
    const ReplayInput input = loadReplayInput(o.flight, o.rigs, o.width, o.height, o.fovYDeg);
    const double start =
        o.start ? parseTimeArgument(*o.start, input.referenceUnix, "--start") : input.startTime;
    const double end = o.end ? parseTimeArgument(*o.end, input.referenceUnix, "--end") : input.endTime;
    if (!std::isfinite(start) || start < input.startTime || start > input.endTime)
        throw UsageError("--start " + std::to_string(start) + " is outside the flight [" +
                         std::to_string(input.startTime) + ", " + std::to_string(input.endTime) + "]");
    if (!std::isfinite(end) || end < start || end > input.endTime)
        throw UsageError("--end " + std::to_string(end) + " must be within [--start, " +
                         std::to_string(input.endTime) + "]");
    const double frameStep = o.speed / o.fps; // recording seconds per frame
    const double frameCountD = std::floor((end - start) / frameStep + 1e-9) + 1.0;
    if (frameCountD > static_cast<double>(o.maxFrames))
        throw UsageError("the run would render " + std::to_string(static_cast<long long>(frameCountD)) +
                         " frames (" + shortNumber(end - start) + " s at --fps " + shortNumber(o.fps) +
                         ", --speed " + shortNumber(o.speed) + "), more than --max-frames " +
                         std::to_string(o.maxFrames) +
                         "; shorten --start/--end, lower --fps, raise --speed, or "
                         "allow it with --max-frames");
    const long long frameCount = static_cast<long long>(frameCountD);
    if (o.video)
        VideoWriter::findFfmpeg(*o.video); // extension and ffmpeg checked before anything is written
    ocean::OceanDesc oceanDesc = o.ocean;
    nlohmann::json environmentJson = nullptr; // summary.json: null = the procedural sky
    if (o.environment) {
        oceanDesc.lighting.environment = loadEnvironment(*o.environment);
        const glm::dvec3 sun = ocean::environmentBrightestDirection(*oceanDesc.lighting.environment);
        if (sun.z > 0.0) // a sun below the horizon would leave the sea unlit: keep the default then
            oceanDesc.lighting.sunDirection = sun;
        environmentJson = {{"file", o.environment->string()},
                           {"width", oceanDesc.lighting.environment->width},
                           {"height", oceanDesc.lighting.environment->height},
                           {"sun_direction",
                            {oceanDesc.lighting.sunDirection.x, oceanDesc.lighting.sunDirection.y,
                             oceanDesc.lighting.sunDirection.z}}};
    }
    const std::string environmentName = o.environment ? o.environment->filename().string() : "procedural";
    color::ColorPipeline colour = color::ColorPipeline::fromEnvironmentOr(o.ocioConfig);
    // The renderer's frames are linear Rec.709: a config whose scene_linear role is another space (ACEScg in
    // the ACES studio and CG configs) is entered through its linear Rec.709 colour space when it has one.
    if (const std::string rec709 = colour.linearRec709ColorSpace(); !rec709.empty())
        colour.setInput(rec709);
    else
        std::fprintf(stderr,
                     "pacifica: warning: the OCIO config has no linear Rec.709 colour space; frames enter it "
                     "as its scene_linear role\n");
    colour.select(o.display, o.view);
    std::unique_ptr<gl::GlContext> context = gl::createHeadlessContext();

    // 2. Scene: one ocean entity; the GL resources (one set of frame targets per view).
    ecs::Registry registry;
    const ecs::Entity oceanEntity = registry.create();
    registry.emplace<ocean::OceanComponent>(oceanEntity, ocean::makeOcean(oceanDesc));
    ocean::OceanRenderer renderer;
    std::vector<std::unique_ptr<gl::FrameTargets>> targets;
    for (const ReplayView& v : input.views)
        targets.push_back(std::make_unique<gl::FrameTargets>(v.width, v.height));
    color::Tonemapper tonemapper(colour);
    // Extra views: one more tonemap pass each over the same rendered scene (no scene pass is repeated).
    struct ExtraView {
        std::string view, suffix;
        std::unique_ptr<color::Tonemapper> pass;
    };
    std::vector<ExtraView> extraViews;
    for (const std::string& v : o.extraViews) {
        color::ColorPipeline other = colour;
        other.select(colour.selectedDisplay(), v); // an unknown view: ColorError listing the valid ones
        std::string suffix;
        for (char c : v)
            suffix += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '-';
        for (const ExtraView& e : extraViews)
            if (e.suffix == suffix)
                throw std::runtime_error("--view '" + v + "' is given twice");
        extraViews.push_back({v, suffix, std::make_unique<color::Tonemapper>(other)});
    }
    gl::GpuTimer gpuTimer(context->info());
    // --profile: the ocean's passes (OceanRenderer::setPassTiming), the replay's own GPU passes (objects,
    // extra and main tonemaps) with the same clock, readback and encoding on the CPU's steady_clock.
    enum ReplayPass { PassObjects, PassTonemap, ReplayPassCount };
    std::unique_ptr<gl::PassTimer> passTimer;
    if (o.profile) {
        renderer.setPassTiming(gpuTimer.clock());
        passTimer = std::make_unique<gl::PassTimer>(gpuTimer.clock(), ReplayPassCount);
    }
    std::map<std::string, std::vector<double>> passSamples; // per pass name, one value per view frame
    const std::vector<ReplayObject> objects =
        o.objects ? replayObjects(input, start, end) : std::vector<ReplayObject>{};
    std::unique_ptr<ObjectRenderer> objectRenderer;
    if (!objects.empty())
        objectRenderer = std::make_unique<ObjectRenderer>();
    const double drawEarthRadius = oceanDesc.earthCurvature ? ocean::EARTH_RADIUS : 0.0;

    // Events (Effects.h): ships are entities whose position follows their track; explosions are spawned
    // by events when the clock passes them. The ships' wakes are built from their path before the first
    // frame (0.5 s steps from the earliest ship sample), so a ship that sailed before --start has a wake.
    // The simulation advances once per frame; every view renders that same state.
    ecs::EventQueue events;
    ocean::EffectsSystem effects(registry, events);
    std::vector<ecs::Entity> shipEntities;
    size_t nextExplosion = 0;
    const std::vector<ExplosionEvent> noExplosions;
    const std::vector<ShipTrack> noShips;
    const std::vector<ExplosionEvent>& explosionEvents = o.events ? input.explosions : noExplosions;
    const std::vector<ShipTrack>& shipTracks = o.events ? input.ships : noShips;
    for (size_t i = 0; i < shipTracks.size(); ++i) {
        const ShipTrack& track = shipTracks[i];
        const ecs::Entity e = registry.create();
        registry.emplace<ocean::Ship>(e,
                                      ocean::Ship{track.positionAt(track.startTime()), input.shipLengths[i]});
        events.enqueue(ocean::AttachShipTrail{e, ocean::WakeParams{}});
        shipEntities.push_back(e);
    }
    auto advanceEffects = [&](double t, const glm::dvec3& camera) {
        for (size_t i = 0; i < shipTracks.size(); ++i)
            registry.get<ocean::Ship>(shipEntities[i]).position = shipTracks[i].positionAt(t);
        for (; nextExplosion < explosionEvents.size() && explosionEvents[nextExplosion].time <= t;
             ++nextExplosion) {
            const ExplosionEvent& x = explosionEvents[nextExplosion];
            events.enqueue(ocean::SpawnExplosion{{x.x, x.y}, x.time, x.strength});
        }
        events.dispatch();
        effects.update(t, camera);
    };
    {
        double warm = start;
        for (const ShipTrack& track : shipTracks)
            warm = std::min(warm, track.startTime());
        // Wakes older than their foam life are gone anyway: warm up at most 600 s of ship history.
        warm = std::max(warm, start - 600.0);
        const glm::dvec3 camera = input.views.front().camera(start).position;
        for (double tw = warm; tw < start; tw += 0.5)
            advanceEffects(tw, camera);
    }

    std::optional<OutputTransaction> out;
    if (!o.outDir.empty())
        out.emplace(o.outDir);
    std::unique_ptr<VideoWriter> video;
    if (o.video)
        video = std::make_unique<VideoWriter>(*o.video, input.views.front().width, input.views.front().height,
                                              o.fps);
    // Image encoding (EXR ZIP + PNG) runs on a worker thread while the next frame renders; at most two
    // frames wait (WorkerQueue.h). Declared after `out`: it finishes its jobs before the staging directory
    // goes. Each frame's EXR hash comes back through a future and is filled into its JSON entry.
    std::optional<WorkerQueue<uint64_t>> encoder;
    if (writeImages)
        encoder.emplace(2);
    struct PendingImage {
        size_t view, frame; // viewFrames[view][frame]; frame == npos: an extra view's PNG (no hash)
        std::future<uint64_t> hash;
    };
    std::deque<PendingImage> pendingImages;
    std::vector<nlohmann::json> viewFrames(input.views.size(), nlohmann::json::array());
    auto collectImages = [&](bool wait) { // rethrows a failed write as soon as it is seen
        while (!pendingImages.empty() && (wait || pendingImages.front().hash.wait_for(std::chrono::seconds(
                                                      0)) == std::future_status::ready)) {
            PendingImage p = std::move(pendingImages.front());
            pendingImages.pop_front();
            const uint64_t h = p.hash.get();
            if (p.frame != std::string::npos)
                viewFrames[p.view][p.frame]["exr_pixel_hash"] = hex64(h);
        }
    };
    std::vector<float> scene, display;
    std::vector<double> frameWallMs;
    double firstFrameSeconds = 0.0;
    const bool tty = o.progress && isatty(STDERR_FILENO);

    for (long long k = 0; k < frameCount; ++k) {
        const auto f0 = std::chrono::steady_clock::now();
        // Frame time from the index (not accumulated): frame k is exactly start + k * speed / fps.
        const double t = std::min(end, start + static_cast<double>(k) * frameStep);
        advanceEffects(t, input.views.front().camera(t).position);
        std::vector<std::pair<uint64_t, DrawnObject>> alive; // posed once per frame, drawn by every view
        for (const ReplayObject& obj : objects)
            if (t >= obj.start && t <= obj.end)
                alive.push_back({obj.id, {obj.shape, obj.length, obj.track->poseAt(t)}});
        for (size_t vi = 0; vi < input.views.size(); ++vi) {
            const ReplayView& view = input.views[vi];
            gl::FrameTargets& target = *targets[vi];
            const Pose pose = view.camera(t);
            ocean::OceanFrame frame;
            frame.camera =
                makeCameraFrame(pose, view.fovYDeg * static_cast<float>(std::numbers::pi / 180.0),
                                static_cast<float>(view.width) / static_cast<float>(view.height), 0.05f);
            frame.time = t;
            frame.targetFramebuffer = target.sceneFramebuffer().id();
            frame.width = view.width;
            frame.height = view.height;

            std::vector<DrawnObject> drawn;
            for (const auto& [id, object] : alive)
                if (id != view.hiddenObject.value_or(~uint64_t(0)))
                    drawn.push_back(object);
            gpuTimer.begin();
            renderer.render(registry, frame);
            if (passTimer)
                passTimer->beginFrame();
            const int objectsDrawn =
                objectRenderer
                    ? objectRenderer->draw(drawn, frame.camera, target.sceneFramebuffer().id(), view.width,
                                           view.height, oceanDesc.lighting.sunDirection, drawEarthRadius)
                    : 0;
            if (passTimer)
                passTimer->mark(PassObjects);
            tonemapper.run(target.sceneColor(), target.displayFramebuffer(), view.width, view.height);
            if (passTimer) {
                passTimer->mark(PassTonemap);
                passTimer->endFrame();
            }
            gpuTimer.end();
            const auto r0 = std::chrono::steady_clock::now();
            target.readScene(scene);
            target.readDisplay(display);
            const auto r1 = std::chrono::steady_clock::now();

            char name[96];
            std::snprintf(name, sizeof name, "%s%sframe_%05lld", view.name.c_str(),
                          view.name.empty() ? "" : "_", k);
            const std::string exrName = std::string(name) + ".exr", pngName = std::string(name) + ".png";
            uint64_t hash = 0;
            double extraTonemapMs = 0.0; // extra views: their tonemap + readback, timed on the CPU
            if (writeImages) {
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
                pendingImages.push_back(
                    {vi, viewFrames[vi].size(),
                     encoder->submit([exr = out->staged(exrName), png = out->staged(pngName), w = view.width,
                                      h = view.height, sceneCopy = scene, displayCopy = display, meta,
                                      compression = o.imageCompression] {
                         const uint64_t exrHash =
                             capture::writeExrHalf(exr, w, h, 4, sceneCopy.data(), meta, compression);
                         capture::writePng8(png, w, h, 4, displayCopy.data(), compression);
                         return exrHash;
                     })});
            } else {
                const std::vector<uint16_t> half = capture::toHalf(scene.data(), scene.size());
                hash = capture::hashHalfPixels(half.data(), half.size());
            }
            if (video && vi == 0)
                video->addFrame(display.data());
            nlohmann::json extraPngs = nlohmann::json::array();
            for (ExtraView& e : extraViews) {
                const auto e0 = std::chrono::steady_clock::now();
                e.pass->run(target.sceneColor(), target.displayFramebuffer(), view.width, view.height);
                if (writeImages)
                    target.readDisplay(display);
                extraTonemapMs +=
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - e0).count();
                if (writeImages) {
                    const std::string png = std::string(name) + "." + e.suffix + ".png";
                    pendingImages.push_back(
                        {vi, std::string::npos,
                         encoder->submit([path = out->staged(png), w = view.width, h = view.height,
                                          displayCopy = display, compression = o.imageCompression] {
                             capture::writePng8(path, w, h, 4, displayCopy.data(), compression);
                             return uint64_t{0};
                         })});
                    extraPngs.push_back({{"view", e.view}, {"png", png}});
                }
            }
            const auto r2 = std::chrono::steady_clock::now();

            nlohmann::json fj;
            fj["index"] = k;
            fj["time_s"] = t;
            fj["pose"] = {{"x_m", pose.position.x},     {"y_m", pose.position.y},
                          {"z_m", pose.position.z},     {"heading_deg", pose.headingDeg},
                          {"pitch_deg", pose.pitchDeg}, {"roll_deg", pose.rollDeg}};
            if (writeImages) {
                fj["exr"] = exrName;
                fj["png"] = pngName;
                if (!extraViews.empty())
                    fj["extra_views"] = extraPngs;
            }
            fj["exr_pixel_hash"] = writeImages
                                       ? nlohmann::json(nullptr)
                                       : nlohmann::json(hex64(hash)); // images: filled by collectImages
            // What the frame cost and did (OceanStats, EffectCounters): absent effects show zeros.
            const ocean::OceanStats& st = renderer.lastStats();
            const ocean::EffectCounters& fx = effects.counters();
            auto kindJson = [](const ocean::EffectKindStats& ks) {
                return nlohmann::json{{"active", ks.active},   {"drawn", ks.drawn},
                                      {"passes", ks.passes},   {"draws", ks.draws},
                                      {"uploads", ks.uploads}, {"vertices", ks.vertices}};
            };
            fj["counters"] = {{"passes", st.passes},
                              {"draws", st.draws},
                              {"uploads", st.uploads},
                              {"vertices", st.vertices},
                              {"programs_built", st.programsBuilt},
                              {"compute_shaded", st.computeShaded},
                              {"shade_tiled", st.shadeTiled},
                              {"explosions", kindJson(st.explosions)},
                              {"wakes", kindJson(st.wakes)},
                              {"explosions_spawned", fx.spawned},
                              {"effects_ended", fx.ended},
                              {"explosions_dropped", fx.droppedExplosions},
                              {"wakes_dropped", fx.droppedWakes},
                              {"events_rejected", fx.rejected},
                              {"objects_drawn", objectsDrawn},
                              {"tonemap_passes", 1 + extraViews.size()}};
            if (passTimer) {
                // The ocean's and the replay's pass timers: on hardware the newest frame whose timestamps
                // have arrived (a few frames behind), on llvmpipe this one.
                const ocean::OceanPassTimes& pt = st.passTimes;
                auto ms = [](std::chrono::steady_clock::duration d) {
                    return std::chrono::duration<double, std::milli>(d).count();
                };
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
                pj["readback"] = ms(r1 - r0);
                // Main-thread time handing the images to the encoder (copies; waits when two frames are
                // queued) or hashing them, and the video frame; the encoding itself overlaps rendering.
                pj["encode"] = ms(r2 - r1) - extraTonemapMs;
                if (!extraViews.empty())
                    pj["extra_views"] = extraTonemapMs;
                for (const auto& [pass, value] : pj.items())
                    passSamples[pass].push_back(value.get<double>());
                fj["pass_ms"] = std::move(pj);
            }
            viewFrames[vi].push_back(std::move(fj));
        }
        collectImages(false);
        const auto f1 = std::chrono::steady_clock::now();
        frameWallMs.push_back(std::chrono::duration<double, std::milli>(f1 - f0).count());
        if (k == 0)
            firstFrameSeconds = std::chrono::duration<double>(f1 - t0).count();
        if (tty) {
            const double elapsed = std::chrono::duration<double>(f1 - t0).count() - firstFrameSeconds;
            const double eta =
                k > 0 ? elapsed / static_cast<double>(k) * static_cast<double>(frameCount - k - 1) : 0.0;
            const int width = 24;
            const int filled = static_cast<int>(width * (k + 1) / frameCount);
            std::fprintf(stderr, "\rpacifica replay [%.*s%*s] %lld/%lld  t=%.2f s  ETA %d:%02d   ", filled,
                         "########################", width - filled, "", k + 1, frameCount, t,
                         static_cast<int>(eta) / 60, static_cast<int>(eta) % 60);
        }
    }
    if (tty)
        std::fprintf(stderr, "\n");
    collectImages(true); // every image written (or the first failure thrown) before the summary
    if (video)
        video->finish(); // the video is in place only now; a failure before leaves none

    gpuTimer.drain(); // timer queries of the last frames are still in flight on real GPUs
    const double totalSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    nlohmann::json summary;
    summary["flight"] = o.flight.string();
    summary["format"] = input.format;
    summary["recording"] = input.summary;
    summary["gl"] = {{"vendor", context->info().vendor},
                     {"renderer", context->info().renderer},
                     {"version", context->info().version},
                     {"platform", context->info().platform}};
    summary["ocio"] = {{"config", colour.configDescription()},
                       {"input", colour.input().empty() ? std::string("scene_linear") : colour.input()},
                       {"display", colour.selectedDisplay()},
                       {"view", colour.selectedView()},
                       {"extra_views", o.extraViews}};
    summary["environment"] = environmentJson;
    summary["size"] = {input.views.front().width, input.views.front().height};
    summary["fps"] = o.fps;
    summary["speed"] = o.speed;
    summary["start_s"] = start;
    summary["end_s"] = end;
    summary["images_written"] = writeImages;
    summary["video"] = o.video ? nlohmann::json{{"file", o.video->string()}, {"frames", video->frames()}}
                               : nlohmann::json(nullptr);
    summary["hash"] = "XXH64 of the scene-linear half-float RGBA pixels, rows top-down";
    summary["events"] = {{"applied", o.events},
                         {"explosions", explosionEvents.size()},
                         {"ships", shipTracks.size()},
                         {"explosions_dropped_total", effects.counters().totalDroppedExplosions}};
    // One entry per view with its frames; "frames" repeats the first view's, for single-view readers.
    nlohmann::json views = nlohmann::json::array();
    for (size_t vi = 0; vi < input.views.size(); ++vi) {
        const ReplayView& v = input.views[vi];
        views.push_back({{"name", v.name},
                         {"rig", v.rig},
                         {"size", {v.width, v.height}},
                         {"fov_deg", v.fovYDeg},
                         {"frames", viewFrames[vi]}});
    }
    summary["views"] = std::move(views);
    summary["frames"] = std::move(viewFrames.front());
    summary["timings"] = {
        {"gpu_clock", gpuTimer.clockName()},
        {"gpu_ms_median", median(gpuTimer.samples())},
        {"frame_wall_clock", "steady_clock, whole frame (all views) incl. readback and image writes"},
        {"frame_wall_ms_median", median(frameWallMs)},
        {"time_to_first_frame_s", firstFrameSeconds},
        {"total_s", totalSeconds},
        {"frames_per_second_overall", static_cast<double>(frameCount) / totalSeconds},
        {"frames_per_second_steady", 1000.0 / std::max(median(frameWallMs), 1e-9)}};
    if (passTimer) {
        nlohmann::json medians;
        for (const auto& [name, v] : passSamples)
            medians[name] = median(v);
        summary["timings"]["passes_ms_median"] = std::move(medians);
        summary["timings"]["pass_clock"] = std::string(renderer.passTimingClock()) +
                                           " (GPU passes); steady_clock (readback, encode, extra_views)";
    }
    if (out)
        out->commit(summary);
    logInfo("replay: " + std::to_string(frameCount) + " frames in " + std::to_string(totalSeconds) +
            " s -> " + (o.outDir.empty() ? o.video->string() : o.outDir.string()));
}

} // namespace pacifica::tools
