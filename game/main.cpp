// pacifica-game: a small flight game embedding the ocean the way a studio would -- only public headers and
// Pacifica:: targets. The game owns its loop, window, camera, framebuffers and GL state and lends the scene
// framebuffer to the ocean. Take off from the carrier, sink the three target ships with bombs and rockets,
// don't fly into the sea (README.md in this folder has the controls).
//
//   pacifica-game [options]           (--help lists them; bad values exit 2 naming the option)
//
// Scripted runs (--autopilot, --frames N) step exactly 1/--fps seconds per frame, so a run is the same on
// any machine; --screenshot T:FILE writes the window (HUD included) at game time T; --summary FILE writes
// what happened as JSON; --record FILE writes the session as Tacview ACMI 2.2 for `pacifica replay`; --bench
// FILE times each quality preset (docs/GAME.md).
#include "Hud.h"
#include "Input.h"
#include "Options.h"

#include <engine/AtomicFile.h>
#include <engine/CameraPoses.h>
#include <engine/Ecs.h>
#include <engine/Log.h>
#include <engine/Space.h>
#include <engine/Stats.h>
#include <engine/Time.h>
#include <engine/capture/Png.h>
#include <engine/color/ColorPipeline.h>
#include <engine/color/Tonemapper.h>
#include <engine/gl/FrameTargets.h>
#include <engine/gl/GlContext.h>
#include <engine/gl/GpuTimer.h>
#include <engine/gl/ObjectRenderer.h>
#include <game/Autopilot.h>
#include <game/Night.h>
#include <game/SessionRecorder.h>
#include <game/World.h>
#include <ocean/Effects.h>
#include <ocean/Ocean.h>
#include <ocean/OceanConstants.h>
#include <ocean/OceanHost.h>
#include <ocean/Presets.h>
#include <ocean/SeaState.h>

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pacifica;

namespace {

constexpr double STEP = 1.0 / 120.0;        ///< simulation step, s
constexpr double HISTORY_S = 20.0;          ///< the player's track kept for the chase camera
constexpr double WATCH_S = 10.0;            ///< the weapon camera watches an impact this long
constexpr double PREHISTORY_S = 120.0;      ///< ships sail this long before the first frame (wakes)
constexpr double AIRCRAFT_LENGTH = 17.0;    ///< m, the drawn jet
constexpr double SCRIPTED_RECORD_HZ = 10.0; ///< recording rate of positions (events keep their own time)

/// The ocean for a quality preset, surface model and sea state: the wind speed sets every model's wave
/// height and the whitecap coverage through ocean::applySeaState (ocean/SeaState.h).
ocean::OceanComponent buildOcean(const game::SeaSettings& s) {
    ocean::OceanDesc d = ocean::oceanPreset(ocean::parseQuality(s.quality));
    d.model = static_cast<ocean::SurfaceKind>(game::parseSurfaceModelIndex(s.model));
    d = ocean::applySeaState(d, {s.windSpeed, d.octaves.windDirectionDeg});
    return ocean::makeOcean(s.night ? game::nightSea(d) : d);
}

/// Everything a sortie owns; rebuilt for a new sortie.
struct Sortie {
    ecs::Registry registry;
    ecs::EventQueue events;
    ecs::Entity ocean;
    std::unique_ptr<ocean::EffectsSystem> effects;
    std::unique_ptr<ocean::EffectsTimeline> timeline; ///< no tracks: the world moves the ships
    std::unique_ptr<game::World> world;
    game::Autopilot autopilot;
    std::deque<std::pair<double, Pose>> history;
    FixedStepClock clock{STEP};
    /// The newest impact or splash (the weapon camera watches it for WATCH_S).
    std::optional<game::GameEvent> lastImpact;
    std::vector<game::GameEvent> splashes; ///< impacts and ditchings still drawn as a plume
    glm::dvec2 impactFrom{0.0, 1.0};       ///< horizontal direction the weapon came from (unit)
    std::vector<ecs::Entity> lamps;        ///< --night: the carrier's SpotLight entities (placeLamps)

    /// `sea` is shared, not rebuilt: a new sortie on the same sea costs no surface build and no upload.
    explicit Sortie(const ocean::OceanComponent& sea) {
        ocean = registry.create();
        registry.emplace<ocean::OceanComponent>(ocean, sea);
        effects = std::make_unique<ocean::EffectsSystem>(registry, events);
        timeline = std::make_unique<ocean::EffectsTimeline>(registry, events, *effects);
        world = std::make_unique<game::World>(registry, events, ocean);
    }
    /// The ships' wakes before the first frame (their routes run backwards in time).
    void prehistory(game::SessionRecorder* rec) {
        timeline->warmUp(-PREHISTORY_S, 0.0, world->player().pose.position, [&](double t) {
            world->placeShips(t, false);
            if (rec)
                rec->recordShips(*world, t);
        });
        world->placeShips(0.0);
        history.emplace_back(0.0, world->player().pose);
    }
    /// --night: the carrier's lamps at the world's time, as SpotLight components the renderer's adapter
    /// reads.
    void placeLamps() {
        for (const ecs::Entity e : lamps)
            registry.destroy(e);
        lamps.clear();
        for (const ocean::SpotLight& s : game::carrierLights(*world, std::exp2(game::NIGHT_EXPOSURE_EV))) {
            lamps.push_back(registry.create());
            registry.emplace<ocean::SpotLight>(lamps.back(), s);
        }
    }
    Pose playerAt(double t) const {
        if (t >= history.back().first)
            return history.back().second;
        if (t <= history.front().first)
            return history.front().second;
        const auto it = std::lower_bound(history.begin(), history.end(), t,
                                         [](const auto& h, double v) { return h.first < v; });
        const auto& b = *it;
        const auto& a = *(it - 1);
        return interpolatePose(a.second, b.second, (t - a.first) / (b.first - a.first));
    }
};

/// `p` lifted to 1.5 m above the sea under it where it would be lower (the sea's CPU query, as drawn).
Pose aboveTheWaves(Pose p, const game::World& w) {
    p.position.z = std::max(p.position.z, w.seaHeight(glm::dvec2(p.position)) + 1.5);
    return p;
}

Pose cameraPose(const Sortie& s, game::CameraMode mode, double t, double orbitAzimuth) {
    const game::World& w = *s.world;
    switch (mode) {
    case game::CameraMode::Cockpit:
        return cockpitPose(w.player().pose, {4.0, 0.0, 1.3});
    case game::CameraMode::Orbit:
        return orbitPose(w.player().pose.position, 90.0, 12.0, orbitAzimuth);
    case game::CameraMode::Weapon: {
        // The newest weapon in flight, from behind and above; then the place it hit, from 250 m back.
        const auto& ws = w.weapons();
        if (!ws.empty()) {
            const game::Weapon& wp = ws.back();
            glm::dvec2 dir(wp.velocity);
            dir = glm::length(dir) > 1e-6 ? glm::normalize(dir) : glm::dvec2(0.0, 1.0);
            return lookAtPose(wp.position - 40.0 * glm::dvec3(dir, 0.0) + glm::dvec3(0, 0, 12.0),
                              wp.position);
        }
        if (s.lastImpact && t - s.lastImpact->time < WATCH_S) {
            const glm::dvec3 at = s.lastImpact->position;
            return lookAtPose(at - 250.0 * glm::dvec3(s.impactFrom, 0.0) + glm::dvec3(0, 0, 60.0),
                              at + glm::dvec3(0, 0, 10.0));
        }
        break;
    }
    case game::CameraMode::Ship: {
        // Low over the sea, 1.6 hull lengths out, circling a point a fifth of the hull's length above its
        // centre: the bow and the stern rise and fall against the horizon.
        const game::ShipState& ship = w.ships()[w.nearestAfloatTarget(glm::dvec2(w.player().pose.position))];
        const glm::dvec3 centre(glm::dvec2(ship.pose.position), 0.2 * ship.spec.length);
        return aboveTheWaves(orbitPose(centre, 1.6 * ship.spec.length, 3.0, orbitAzimuth), w);
    }
    case game::CameraMode::Chase:
        break;
    }
    // Never below the waves (the chase camera of an aircraft skimming the sea).
    return aboveTheWaves(chasePose([&](double tt) { return s.playerAt(tt); }, t, 45.0, 9.0, 0.8), w);
}

/// A splash's white water column: rises to H = 45 m x strength^(1/3) (a 500 kg bomb ~45 m) with
/// 1 - e^(-tau / 0.35 s), stands, then falls back into the sea between 2 and SPLASH_S seconds. The ocean's
/// explosion effect (rings and crown foam) carries on after it.
constexpr double SPLASH_S = 6.0;
std::optional<gl::DrawnObject> splashPlume(const game::GameEvent& e, double t) {
    const double tau = t - e.time;
    if (tau < 0.0 || tau > SPLASH_S || e.strength <= 0.0)
        return std::nullopt;
    const double height = 45.0 * std::cbrt(e.strength) * (1.0 - std::exp(-tau / 0.35));
    gl::DrawnObject o;
    o.shape = gl::ObjectShape::Plume;
    o.length = height;
    o.pose.position =
        e.position - glm::dvec3(0.0, 0.0, height * std::clamp((tau - 2.0) / (SPLASH_S - 2.0), 0.0, 1.0));
    o.albedo = glm::vec3(0.82f, 0.85f, 0.86f);
    return o;
}

/// The game's own objects: carrier, ships (settling when sunk), the player's jet, weapons in flight,
/// splashes.
std::vector<gl::DrawnObject> sceneObjects(const Sortie& sortie, game::CameraMode mode) {
    const game::World& w = *sortie.world;
    std::vector<gl::DrawnObject> out;
    for (const game::GameEvent& e : sortie.splashes)
        if (const auto p = splashPlume(e, w.time()))
            out.push_back(*p);
    for (const game::ShipState& s : w.ships()) {
        if (!s.visibleAt(w.time()))
            continue;
        gl::DrawnObject o;
        o.shape = s.spec.carrier ? gl::ObjectShape::Carrier : gl::ObjectShape::Ship;
        o.length = s.spec.length;
        o.pose = s.pose;
        o.albedo = s.sunkAt ? glm::vec3(0.08f, 0.07f, 0.06f)
                            : (s.spec.target ? glm::vec3(0.26f, 0.2f, 0.18f) : glm::vec3(0.2f, 0.22f, 0.24f));
        out.push_back(o);
    }
    if (mode != game::CameraMode::Cockpit && w.state() != game::SortieState::Ditched) {
        gl::DrawnObject o;
        o.shape = gl::ObjectShape::Aircraft;
        o.length = AIRCRAFT_LENGTH;
        o.pose = w.player().pose;
        o.albedo = glm::vec3(0.45f, 0.47f, 0.5f);
        out.push_back(o);
    }
    for (const game::Weapon& wp : w.weapons()) {
        gl::DrawnObject o;
        o.shape = gl::ObjectShape::Weapon;
        o.length = wp.kind == game::WeaponKind::Bomb ? 3.3 : 2.7;
        o.pose.position = wp.position;
        const double horiz = std::hypot(wp.velocity.x, wp.velocity.y);
        o.pose.headingDeg = std::atan2(wp.velocity.x, wp.velocity.y) * 180.0 / std::numbers::pi;
        o.pose.pitchDeg = std::atan2(wp.velocity.z, horiz) * 180.0 / std::numbers::pi;
        o.albedo = glm::vec3(0.3f, 0.3f, 0.28f);
        out.push_back(o);
    }
    return out;
}

/// The OCIO view pipelines, built on first use.
class Tonemappers {
public:
    explicit Tonemappers(color::ColorPipeline base) : mBase(std::move(base)) {}
    color::Tonemapper& get(const std::string& view) {
        auto it = mByView.find(view);
        if (it == mByView.end()) {
            color::ColorPipeline p = mBase;
            p.select(mBase.defaultDisplay(), view);
            it = mByView.emplace(view, std::make_unique<color::Tonemapper>(p)).first;
        }
        return *it->second;
    }
    std::vector<std::string> views() const { return mBase.views(mBase.defaultDisplay()); }
    std::string defaultView() const { return mBase.defaultView(mBase.defaultDisplay()); }

private:
    color::ColorPipeline mBase;
    std::map<std::string, std::unique_ptr<color::Tonemapper>> mByView;
};

std::vector<float> readPixels(unsigned fbo, bool backBuffer, int w, int h) {
    std::vector<unsigned char> bytes(static_cast<size_t>(w) * h * 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    if (backBuffer)
        glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    std::vector<float> out(bytes.size());
    for (int y = 0; y < h; ++y) // GL rows are bottom-up; images top-down
        for (int x = 0; x < w * 4; ++x)
            out[static_cast<size_t>(h - 1 - y) * w * 4 + x] =
                bytes[static_cast<size_t>(y) * w * 4 + x] / 255.0f;
    return out;
}

struct RunResult {
    int exitCode = 0;
    std::vector<double> cpuMs, gpuMs;
    std::string renderer, gpuClock;
};

std::unique_ptr<gl::GlContext> makeContext(const game::Options& opt) {
    return opt.headless ? gl::createHeadlessContext({.width = opt.width, .height = opt.height, .debug = true})
                        : gl::createWindowContext({.width = opt.width,
                                                   .height = opt.height,
                                                   .title = "Pacifica",
                                                   .vsync = !opt.scripted()});
}

/// The game state a session starts from: the options' sea, camera, OCIO views (checked against the config)
/// and HUD.
game::GameState initialState(const game::Options& opt, const Tonemappers& tonemappers) {
    game::GameState gs;
    gs.sea = opt.sea;
    gs.camera = opt.camera;
    gs.view = opt.view.empty() ? tonemappers.defaultView() : opt.view;
    gs.wipeView = opt.wipeView;
    gs.wipe = !opt.wipeView.empty();
    gs.wipePosition = opt.wipePosition;
    gs.hud = opt.hud;
    gs.views = tonemappers.views();
    for (const std::string& v : {gs.view, gs.wipeView})
        if (!v.empty() && std::find(gs.views.begin(), gs.views.end(), v) == gs.views.end()) {
            std::string list;
            for (const std::string& x : gs.views)
                list += (list.empty() ? "" : ", ") + x;
            throw game::UsageError("--view/--wipe: no OCIO view '" + v + "' (this config has: " + list + ")");
        }
    return gs;
}

/// Every ship's float on the sea now: heave (metres), pitch and roll (degrees) from its hull points' sea
/// heights (game::World::placeShips), as drawn.
nlohmann::json shipsJson(const game::World& world) {
    nlohmann::json out = nlohmann::json::array();
    for (const game::ShipState& s : world.ships())
        out.push_back({{"name", s.spec.name},
                       {"afloat", !s.sunkAt},
                       {"x", s.pose.position.x},
                       {"y", s.pose.position.y},
                       {"heave_m", s.pose.position.z},
                       {"pitch_deg", s.pose.pitchDeg},
                       {"roll_deg", s.pose.rollDeg}});
    return out;
}

nlohmann::json eventsJson(const game::World& world, const game::SessionRecorder* recorder) {
    nlohmann::json ev = nlohmann::json::array();
    for (const game::GameEvent& e : world.history()) {
        nlohmann::json x = {{"kind", game::toString(e.kind)},
                            {"time_s", e.time},
                            {"x", e.position.x},
                            {"y", e.position.y},
                            {"ship", e.ship},
                            {"weapon", e.weapon},
                            {"strength", e.strength}};
        if (recorder) { // where and when the recording has it
            const glm::dvec3 g = recorder->geodetic(e.position);
            x["latitude_deg"] = g.x;
            x["longitude_deg"] = g.y;
            x["record_time_s"] = recorder->recordTime(e.time);
        }
        ev.push_back(x);
    }
    return ev;
}

nlohmann::json shipsJson(const game::World& world, const game::SessionRecorder* recorder) {
    nlohmann::json ships = nlohmann::json::array();
    for (const game::ShipState& sh : world.ships()) {
        nlohmann::json x = {{"name", sh.spec.name},
                            {"id", sh.id},
                            {"sunk", sh.sunkAt.has_value()},
                            {"x", sh.pose.position.x},
                            {"y", sh.pose.position.y}};
        if (recorder) {
            const glm::dvec3 g = recorder->geodetic(glm::dvec3(glm::dvec2(sh.pose.position), 0.0));
            x["latitude_deg"] = g.x;
            x["longitude_deg"] = g.y;
        }
        ships.push_back(x);
    }
    return ships;
}

/// A sortie on `sea` whose ships have sailed their prehistory (recorded by `recorder` when given).
std::unique_ptr<Sortie> newSortie(const ocean::OceanComponent& sea, int maxSteps,
                                  game::SessionRecorder* recorder) {
    auto sortie = std::make_unique<Sortie>(sea);
    sortie->clock.setMaxStepsPerAdvance(maxSteps);
    sortie->prehistory(recorder);
    return sortie;
}

/// One session in the context ctx (the window or headless context, kept across the benchmark's runs):
/// frame() polls the input, steps the sortie, draws and takes the screenshots due; finish() ends the
/// recording, prints the result line and writes --summary.
class Session {
public:
    Session(const game::Options& opt, gl::GlContext* ctx);
    /// One frame; false when the session ends (quit, window closed, --frames reached).
    bool frame();
    RunResult finish();

private:
    void applyInput(const game::InputState& in);
    void restartSortie();
    /// The fixed steps of this frame's game time, then the world's events (banners, splashes, recording).
    void simulate(const game::InputState& in, double realDt, double scale);
    void draw(const Pose& camPose, const glm::ivec2& size);
    void takeScreenshots(const gl::Framebuffer& display, const glm::ivec2& size);
    nlohmann::json summary() const;

    const game::Options& opt;
    gl::GlContext* ctx;
    Tonemappers tonemappers;
    game::GameState gs;
    int maxSteps; // scripted runs take every step of a long frame (--fps 4: 30 steps); play caps at 30
    std::unique_ptr<game::SessionRecorder> recorder;
    std::unique_ptr<Sortie> sortie;
    std::unique_ptr<ocean::OceanRenderer> renderer;
    gl::ObjectRenderer objects;
    game::Input input;
    game::Hud hud;
    gl::GpuTimer gpuTimer;
    std::unique_ptr<gl::FrameTargets> targets, wipeTargets;
    std::vector<std::pair<double, std::string>> screenshots;
    nlohmann::json shots = nlohmann::json::array();
    std::vector<double> cpuMs;
    long long frames = 0;
    int glErrors = 0;
    int screenshotErrors = 0; ///< screenshots that could not be written (the run goes on; exit code 1)
    double lastRecord = -1e9;
    std::vector<std::string> messages; // every banner shown, for the summary
    double orbitAzimuth = 200.0;
    std::chrono::steady_clock::time_point last;
};

Session::Session(const game::Options& o, gl::GlContext* c)
    : opt(o), ctx(c), tonemappers(color::ColorPipeline::fromEnvironmentOr(std::nullopt)),
      gs(initialState(opt, tonemappers)),
      maxSteps(opt.scripted() ? static_cast<int>(std::ceil(1.0 / (opt.fps * STEP))) + 1 : 30),
      recorder(opt.record.empty() ? nullptr : std::make_unique<game::SessionRecorder>(opt.record)),
      sortie(newSortie(buildOcean(gs.sea), maxSteps, recorder.get())),
      renderer(std::make_unique<ocean::OceanRenderer>()), input(*ctx), hud(*ctx), gpuTimer(ctx->info()),
      screenshots(opt.screenshots) {
    ctx->makeCurrent();
    std::sort(screenshots.begin(), screenshots.end());
    last = std::chrono::steady_clock::now();
}

bool Session::frame() {
    if (ctx->shouldClose())
        return false;
    const auto frameStart = std::chrono::steady_clock::now();
    ctx->pollEvents();
    const game::InputState in = opt.autopilot || opt.headless
                                    ? game::InputState{}
                                    : input.poll(hud.wantsKeyboard(), hud.wantsMouse());
    applyInput(in); // keys typed with Escape in one poll still count (the summary shows them)
    if (in.quit)
        return false;
    const double realDt =
        opt.scripted() ? 1.0 / opt.fps : std::chrono::duration<double>(frameStart - last).count();
    last = frameStart;
    const double scale = gs.paused ? 0.0 : (gs.slowMotion ? 0.25 : 1.0);
    simulate(in, realDt, scale);
    const game::World& world = *sortie->world;
    orbitAzimuth += 12.0 * realDt * scale;
    const Pose camPose = cameraPose(*sortie, gs.camera, world.time(), orbitAzimuth);
    sortie->timeline->step(world.time(), camPose.position);
    if (gs.sea.night)
        sortie->placeLamps();

    const glm::ivec2 size = opt.headless ? glm::ivec2(opt.width, opt.height) : ctx->framebufferSize();
    if (size.x <= 0 || size.y <= 0)
        return true; // minimised
    draw(camPose, size);
    ctx->swapBuffers();
    cpuMs.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count());
    ++frames;
    return opt.frames <= 0 || frames < opt.frames;
}

void Session::applyInput(const game::InputState& in) {
    if (in.pause)
        gs.paused = !gs.paused;
    if (in.slowMotion)
        gs.slowMotion = !gs.slowMotion;
    if (in.nextCamera)
        gs.camera = game::CameraMode((static_cast<int>(gs.camera) + 1) % game::CAMERA_MODES);
    if (in.toggleHud)
        gs.hud = !gs.hud;
    if (in.restart || gs.restartRequested)
        restartSortie();
    if (gs.seaChanged) { // a live switch: the same sortie on the new sea
        gs.seaChanged = false;
        sortie->registry.emplaceOrReplace<ocean::OceanComponent>(sortie->ocean, buildOcean(gs.sea));
    }
}

void Session::restartSortie() {
    gs.restartRequested = false;
    std::string note = "New sortie";
    if (recorder) { // a recording holds one sortie: it is finished here, the new one is not recorded
        recorder->record(*sortie->world, sortie->world->takeEvents());
        recorder->finish();
        recorder.reset();
        note += " (" + opt.record + " saved; this sortie is not recorded)";
    }
    messages.push_back(note);
    // The renderer stays (its programs are built) and so does the sea: the new registry's ocean entity gets
    // the same handle and the same surface (immutable, shared), so the renderer keeps that ocean's textures.
    // The live sea switch keeps the component equal to gs.sea.
    sortie = newSortie(sortie->registry.get<ocean::OceanComponent>(sortie->ocean), maxSteps, nullptr);
    gs.banner = note;
    gs.bannerUntil = 3.0;
}

void Session::simulate(const game::InputState& in, double realDt, double scale) {
    game::World& world = *sortie->world;
    const int steps = sortie->clock.advance((opt.scripted() ? realDt : std::min(realDt, 0.25)) * scale);
    for (int s = 0; s < steps; ++s) {
        game::FlightControls c = in.controls;
        if (opt.autopilot || gs.autopilot) {
            const game::AutopilotDecision d = sortie->autopilot.decide(world);
            c = d.controls;
            gs.autopilotPhase = d.phase;
            if (d.releaseBomb)
                sortie->autopilot.released(world.fire(game::WeaponKind::Bomb), world.time());
        } else {
            if (in.bomb && s == 0)
                world.fire(game::WeaponKind::Bomb);
            if (in.rocket)
                world.fire(game::WeaponKind::Rocket);
        }
        world.step(c, STEP);
        sortie->history.emplace_back(world.time(), world.player().pose);
        while (sortie->history.size() > 2 && sortie->history.front().first < world.time() - HISTORY_S)
            sortie->history.pop_front();
    }
    const std::vector<game::GameEvent> events = world.takeEvents();
    for (const game::GameEvent& e : events) {
        game::announce(gs, world, e, messages);
        if (e.kind == game::GameEvent::Kind::Impact || e.kind == game::GameEvent::Kind::Ditched) {
            sortie->lastImpact = e;
            sortie->splashes.push_back(e);
            const double h = world.player().pose.headingDeg * std::numbers::pi / 180.0;
            sortie->impactFrom = glm::dvec2(std::sin(h), std::cos(h)); // the way the player flew in
        }
    }
    if (recorder && (!events.empty() || world.time() - lastRecord >= 1.0 / SCRIPTED_RECORD_HZ - 1e-9)) {
        recorder->record(world, events);
        lastRecord = world.time();
    }
    std::erase_if(sortie->splashes,
                  [&](const game::GameEvent& e) { return world.time() - e.time > SPLASH_S; });
}

/// The sea, the objects, the tonemap (and the wipe's second view), the HUD; then the screenshots due.
void Session::draw(const Pose& camPose, const glm::ivec2& size) {
    const game::World& world = *sortie->world;
    if (!targets || targets->width() != size.x || targets->height() != size.y)
        targets = std::make_unique<gl::FrameTargets>(size.x, size.y);
    gpuTimer.begin();
    const ocean::OceanFrame f =
        ocean::makeOceanFrame(camPose, static_cast<float>(gs.fovDeg * std::numbers::pi / 180.0), size.x,
                              size.y, world.time(), targets->sceneFramebuffer().id());
    render(*renderer, sortie->registry, f);
    const ocean::OceanComponent& oc = sortie->registry.get<ocean::OceanComponent>(sortie->ocean);
    gs.objectsDrawn = objects.draw(sceneObjects(*sortie, gs.camera), f.camera, f.targetFramebuffer, size.x,
                                   size.y, oc.desc.lighting.sunDirection, ocean::EARTH_RADIUS,
                                   oc.desc.lighting.sunIntensity / ocean::LightingDesc{}.sunIntensity);
    // The display: the host's default framebuffer (window) or its own display target (headless).
    const gl::Framebuffer display =
        opt.headless ? gl::Framebuffer::wrap(targets->displayFramebuffer().id()) : gl::Framebuffer::wrap(0);
    tonemappers.get(gs.view).run(targets->sceneColor(), display, size.x, size.y);
    if (gs.wipe && !gs.wipeView.empty()) {
        // Split screen: the second OCIO view right of the wipe line.
        if (!wipeTargets || wipeTargets->width() != size.x || wipeTargets->height() != size.y)
            wipeTargets = std::make_unique<gl::FrameTargets>(size.x, size.y);
        tonemappers.get(gs.wipeView)
            .run(targets->sceneColor(), wipeTargets->displayFramebuffer(), size.x, size.y);
        const int x0 = std::clamp(static_cast<int>(gs.wipePosition * size.x), 0, size.x);
        glBlitNamedFramebuffer(wipeTargets->displayFramebuffer().id(), display.id(), x0, 0, size.x, size.y,
                               x0, 0, size.x, size.y, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    gs.stats = renderer->lastStats();
    gs.frameCpuMs = cpuMs.empty() ? 0.0 : cpuMs.back();
    if (const auto g = gpuTimer.poll())
        gs.frameGpuMs = *g;
    gs.gpuClock = gpuTimer.clockName();
    gs.gamepad = input.gamepadName();
    if (gs.hud)
        hud.draw(gs, world, display.id(), size.x, size.y);
    gpuTimer.end();
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError())
        ++glErrors;
    takeScreenshots(display, size);
}

void Session::takeScreenshots(const gl::Framebuffer& display, const glm::ivec2& size) {
    const double time = sortie->world->time();
    while (!screenshots.empty() && time >= screenshots.front().first - 1e-9) {
        const std::vector<float> px = readPixels(display.id(), !opt.headless, size.x, size.y);
        nlohmann::json shot = {{"file", screenshots.front().second},
                               {"time_s", time},
                               {"frame", frames},
                               {"ships", shipsJson(*sortie->world)}};
        try { // a screenshot that cannot be written (a missing folder, a full disk) does not stop the game
            capture::writePng8(screenshots.front().second, size.x, size.y, 4, px.data());
        } catch (const std::exception& e) {
            std::fprintf(stderr, "pacifica-game: warning: screenshot not written, the game goes on: %s\n",
                         e.what());
            shot["error"] = e.what();
            ++screenshotErrors;
        }
        shots.push_back(std::move(shot));
        screenshots.erase(screenshots.begin());
    }
}

RunResult Session::finish() {
    gpuTimer.drain();
    if (recorder) {
        recorder->record(*sortie->world, sortie->world->takeEvents());
        recorder->finish();
    }
    const game::World& world = *sortie->world;
    std::printf("pacifica-game: %lld frames, t = %.3f s, %s, targets left %d, score %d, GL errors %d, %s\n",
                frames, world.time(), game::toString(world.state()), world.targetsLeft(), world.score(),
                glErrors, ctx->info().renderer.c_str());
    if (!opt.summary.empty())
        writeFileAtomically(opt.summary, summary().dump(2) + "\n");
    if (!screenshots.empty())
        std::fprintf(stderr,
                     "pacifica-game: warning: %zu screenshot(s) after the last frame were not taken\n",
                     screenshots.size());
    RunResult r;
    r.exitCode = glErrors == 0 && screenshotErrors == 0 ? 0 : 1;
    r.cpuMs = std::move(cpuMs);
    r.gpuMs = gpuTimer.samples();
    r.renderer = ctx->info().renderer;
    r.gpuClock = gs.gpuClock;
    return r;
}

/// --summary: what happened (state, score, events, ships), what was shown and what it cost.
nlohmann::json Session::summary() const {
    const game::World& world = *sortie->world;
    nlohmann::json j;
    j["frames"] = frames;
    j["time_s"] = world.time();
    j["state"] = game::toString(world.state());
    j["targets_left"] = world.targetsLeft();
    j["score"] = world.score();
    j["gl_errors"] = glErrors;
    j["gl_renderer"] = ctx->info().renderer;
    j["gamepad"] =
        input.gamepadName().empty() ? nlohmann::json(nullptr) : nlohmann::json(input.gamepadName());
    j["hud"] = {{"shown", gs.hud}, {"vertices", hud.lastVertexCount()}};
    j["screenshots"] = shots;
    j["messages"] = messages;
    j["cpu_ms_median"] = median(cpuMs);
    j["objects_drawn"] = gs.objectsDrawn;
    j["camera"] = game::toString(gs.camera);
    j["paused"] = gs.paused;
    j["slow_motion"] = gs.slowMotion;
    j["throttle"] = world.player().throttle;
    j["speed_over_deck_mps"] = glm::length(glm::dvec2(world.player().velocity) - world.ships()[0].velocity);
    j["counters"] = {{"passes", gs.stats.passes},
                     {"draws", gs.stats.draws},
                     {"explosions", gs.stats.explosions.active},
                     {"wakes", gs.stats.wakes.active},
                     {"spots", gs.stats.spots}};
    const glm::dvec3 p = world.player().pose.position;
    j["player"] = {{"x", p.x}, {"y", p.y}, {"z", p.z}, {"on_deck", world.player().onDeck}};
    j["events"] = eventsJson(world, recorder.get());
    j["ships"] = shipsJson(world);
    j["ships"] = shipsJson(world, recorder.get());
    return j;
}

RunResult run(const game::Options& opt, gl::GlContext* ctx) {
    Session session(opt, ctx);
    while (session.frame()) {
    }
    return session.finish();
}

/// --bench FILE: the autopilot's sortie for --frames frames (after 10 unmeasured) at each quality preset;
/// medians of the frame's wall time (CPU simulation + submission + the GPU's share where the clock waits)
/// and of the GPU time; frames/s = 1000 / wall median. docs/GAME.md has the figures.
int runBench(game::Options opt) {
    nlohmann::json j;
    j["size"] = std::to_string(opt.width) + "x" + std::to_string(opt.height);
    j["frames"] = opt.frames;
    j["presets"] = nlohmann::json::array();
    const long long measured = opt.frames;
    opt.autopilot = true;                                        // scripted stepping, vsync off
    const std::unique_ptr<gl::GlContext> ctx = makeContext(opt); // one window for every preset
    for (const char* q : {"low", "medium", "high"}) {
        game::Options o = opt;
        o.sea.quality = q;
        o.autopilot = true;
        o.frames = measured + 10; // 10 unmeasured frames first (shader builds, first uploads)
        o.summary.clear();
        o.record.clear();
        o.screenshots.clear();
        RunResult r = run(o, ctx.get());
        if (r.exitCode != 0)
            return r.exitCode;
        auto tail = [&](const std::vector<double>& v) {
            const size_t n = std::min<size_t>(v.size(), static_cast<size_t>(measured));
            return std::vector<double>(v.end() - static_cast<std::ptrdiff_t>(n), v.end());
        };
        const double cpu = median(tail(r.cpuMs)), gpu = median(tail(r.gpuMs));
        j["gl_renderer"] = r.renderer;
        j["gpu_clock"] = r.gpuClock;
        j["presets"].push_back({{"quality", q},
                                {"frame_ms_median", cpu},
                                {"gpu_ms_median", gpu},
                                {"fps", cpu > 0.0 ? 1000.0 / cpu : 0.0}});
        std::printf("pacifica-game bench: %s %dx%d: frame %.2f ms (%.1f fps), GPU %.2f ms (%s)\n", q,
                    opt.width, opt.height, cpu, cpu > 0.0 ? 1000.0 / cpu : 0.0, gpu, r.gpuClock.c_str());
    }
    writeFileAtomically(opt.bench, j.dump(2) + "\n");
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    game::Options opt;
    try {
        opt = game::parseOptions(argc, argv);
        if (opt.help)
            return 0;
    } catch (const game::UsageError& e) {
        std::fprintf(stderr, "pacifica-game: error: %s\n", e.what());
        return 2;
    }
    try {
        if (!opt.bench.empty())
            return runBench(opt);
        return run(opt, makeContext(opt).get()).exitCode;
    } catch (const game::UsageError& e) {
        std::fprintf(stderr, "pacifica-game: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pacifica-game: error: %s\n", e.what());
        return 1;
    }
}
