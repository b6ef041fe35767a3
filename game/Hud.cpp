// Hud: Dear ImGui overlay (Hud.h).
#include "Hud.h"

#include <engine/Log.h>
#include <engine/gl/GlContext.h>
#include <engine/gl/GlObjects.h>

#include <epoxy/gl.h>
// Dear ImGui's backends (Debian's libimgui-dev ships them in libimgui.a).
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace pacifica::game {

namespace {
constexpr double MS_TO_KT = 1.943844;
const char* QUALITIES[] = {"low", "medium", "high", "reference"};
const char* MODELS[] = {"octaves", "gerstner", "fft"};
const char* CAMERAS[] = {"cockpit", "chase", "orbit", "weapon", "ship"};

template <size_t N>
int indexOf(const char* (&list)[N], const std::string& v) {
    for (size_t i = 0; i < N; ++i)
        if (v == list[i])
            return static_cast<int>(i);
    return 0;
}
} // namespace

void announce(GameState& gs, const World& world, const GameEvent& e, std::vector<std::string>& log) {
    std::string text;
    switch (e.kind) {
    case GameEvent::Kind::ShipHit:
        text = "Hit on " + world.ships()[e.ship].spec.name;
        break;
    case GameEvent::Kind::ShipSunk:
        text = world.ships()[e.ship].spec.name + " sunk!";
        break;
    case GameEvent::Kind::Ditched:
        text = "SPLASH - you ditched. Backspace: new sortie";
        break;
    case GameEvent::Kind::MissionComplete:
        text = "Mission complete: all targets sunk. Score " + std::to_string(world.score());
        break;
    default:
        return;
    }
    gs.banner = text;
    gs.bannerUntil = e.time + (e.kind == GameEvent::Kind::Ditched ? 1e9 : 4.0);
    char stamp[32];
    std::snprintf(stamp, sizeof stamp, "%.2f s: ", e.time);
    log.push_back(stamp + text);
}

Hud::Hud(gl::GlContext& ctx) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini written next to the user's files
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 4.0f;
    ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 0.72f;
    if (auto* window = static_cast<GLFWwindow*>(ctx.nativeWindow())) {
        mWindowed = ImGui_ImplGlfw_InitForOpenGL(window, true);
    }
    mReady = ImGui_ImplOpenGL3_Init("#version 450 core");
    if (!mReady)
        logWarning("HUD: Dear ImGui's OpenGL 3 backend did not start; the HUD is off");
}

Hud::~Hud() {
    if (mReady)
        ImGui_ImplOpenGL3_Shutdown();
    if (mWindowed)
        ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

bool Hud::wantsKeyboard() const {
    return mReady && ImGui::GetIO().WantCaptureKeyboard;
}

bool Hud::wantsMouse() const {
    return mReady && ImGui::GetIO().WantCaptureMouse;
}

/// Flight data, top left.
void Hud::flightWindow(const GameState& gs, const World& world) {
    const AircraftState& a = world.player();
    const double agl = world.altitudeAboveWaves();
    ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(300, 0), ImGuiCond_Always);
    ImGui::Begin("Flight", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::Text("Speed     %5.0f kt  (%3.0f m/s)", a.airspeed() * MS_TO_KT, a.airspeed());
    ImGui::Text("Altitude  %6.1f m above the waves", agl);
    ImGui::Text("Heading   %05.1f deg", a.pose.headingDeg);
    ImGui::Text("Throttle  %3.0f %%   AoA %5.1f   %4.1f g", 100.0 * a.throttle, a.alphaDeg, a.loadFactor);
    if (a.stalled)
        ImGui::TextColored(ImVec4(1, 0.25f, 0.2f, 1), "STALL");
    else if (a.onDeck)
        ImGui::TextColored(ImVec4(0.6f, 0.9f, 1, 1), "On deck: R throttle, S pull up at %.0f kt",
                           world.params().stallSpeed() * MS_TO_KT);
    ImGui::Separator();
    ImGui::Text("Bombs %d  Rockets %d  Targets left %d", world.bombsLeft(), world.rocketsLeft(),
                world.targetsLeft());
    ImGui::Text("Time %.1f s  %s%s%s", world.time(), toString(world.state()), gs.paused ? "  PAUSED" : "",
                gs.slowMotion ? "  SLOW x0.25" : "");
    if (gs.autopilot || !gs.autopilotPhase.empty())
        ImGui::Text("Autopilot: %s", gs.autopilotPhase.c_str());
    if (gs.camera == CameraMode::Ship) { // the watched hull's float on the sea's heights (ocean::floatHull)
        const ShipState& s = world.ships()[world.nearestAfloatTarget(glm::dvec2(a.pose.position))];
        ImGui::Separator();
        ImGui::Text("%s: heave %+.2f m", s.spec.name.c_str(), s.pose.position.z);
        ImGui::Text("pitch %+.2f deg  roll %+.2f deg", s.pose.pitchDeg, s.pose.rollDeg);
    }
    ImGui::End();
}

/// Performance and the ocean's counters, top right.
void Hud::frameWindow(const GameState& gs, int w) {
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(w) - 270, 10), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(260, 0), ImGuiCond_Always);
    ImGui::Begin("Frame", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::Text("CPU %6.2f ms   GPU %6.2f ms", gs.frameCpuMs, gs.frameGpuMs);
    ImGui::TextDisabled("GPU clock: %s", gs.gpuClock.c_str());
    ImGui::Text("Ocean: %d passes, %d draws, %d uploads", gs.stats.passes, gs.stats.draws, gs.stats.uploads);
    ImGui::Text("Explosions %d   Wakes %d   Objects %d", gs.stats.explosions.active, gs.stats.wakes.active,
                gs.objectsDrawn);
    ImGui::Text("Gamepad: %s", gs.gamepad.empty() ? "none (keyboard + mouse)" : gs.gamepad.c_str());
    ImGui::End();
}

/// Live switches, bottom left.
void Hud::settingsWindow(GameState& gs, int h) {
    ImGui::SetNextWindowPos(ImVec2(10, static_cast<float>(h) - 10), ImGuiCond_Always, ImVec2(0, 1));
    ImGui::SetNextWindowSize(ImVec2(300, 0), ImGuiCond_Always);
    ImGui::SetNextWindowCollapsed(true, ImGuiCond_FirstUseEver); // click its title bar to open
    ImGui::Begin("Settings", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
    int cam = static_cast<int>(gs.camera);
    if (ImGui::Combo("Camera", &cam, CAMERAS, CAMERA_MODES))
        gs.camera = static_cast<CameraMode>(cam);
    int q = indexOf(QUALITIES, gs.sea.quality), m = indexOf(MODELS, gs.sea.model);
    if (ImGui::Combo("Quality", &q, QUALITIES, 4)) {
        gs.sea.quality = QUALITIES[q];
        gs.seaChanged = true;
    }
    if (ImGui::Combo("Surface", &m, MODELS, 3)) {
        gs.sea.model = MODELS[m];
        gs.seaChanged = true;
    }
    // The sea is rebuilt when the slider is let go, not on every drag step.
    if (!mWindEditing)
        mWind = static_cast<float>(gs.sea.windSpeed);
    ImGui::SliderFloat("Wind m/s", &mWind, 2.0f, 25.0f, "%.0f");
    mWindEditing = ImGui::IsItemActive();
    if (ImGui::IsItemDeactivatedAfterEdit()) {
        gs.sea.windSpeed = mWind;
        gs.seaChanged = true;
    }
    auto viewCombo = [&](const char* label, std::string& v) {
        if (ImGui::BeginCombo(label, v.c_str())) {
            for (const std::string& name : gs.views)
                if (ImGui::Selectable(name.c_str(), name == v))
                    v = name;
            ImGui::EndCombo();
        }
    };
    viewCombo("OCIO view", gs.view);
    bool wipe = gs.wipe;
    if (ImGui::Checkbox("Wipe", &wipe)) {
        gs.wipe = wipe;
        if (gs.wipe && gs.wipeView.empty())
            gs.wipeView = gs.views.size() > 1 && gs.views[0] == gs.view ? gs.views[1] : gs.views.front();
    }
    if (gs.wipe) {
        viewCombo("Right view", gs.wipeView);
        float p = static_cast<float>(gs.wipePosition);
        if (ImGui::SliderFloat("Wipe at", &p, 0.0f, 1.0f, "%.2f"))
            gs.wipePosition = p;
    }
    ImGui::Checkbox("Pause (P)", &gs.paused);
    ImGui::SameLine();
    ImGui::Checkbox("Slow x0.25 (T)", &gs.slowMotion);
    ImGui::Checkbox("Autopilot", &gs.autopilot);
    ImGui::SameLine();
    if (ImGui::Button("New sortie"))
        gs.restartRequested = true;
    ImGui::End();
}

/// The banner of the latest event and the wipe line.
void Hud::overlays(const GameState& gs, const World& world, int w, int h) {
    if (!gs.banner.empty() && world.time() < gs.bannerUntil) {
        ImGui::SetNextWindowPos(ImVec2(0.5f * w, 0.3f * h), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        ImGui::Begin("##banner", nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                         ImGuiWindowFlags_NoInputs);
        ImGui::SetWindowFontScale(1.6f);
        ImGui::TextColored(ImVec4(1, 0.85f, 0.3f, 1), "%s", gs.banner.c_str());
        ImGui::End();
    }
    if (gs.wipe) { // the wipe line
        const float x = static_cast<float>(gs.wipePosition * w);
        ImGui::GetForegroundDrawList()->AddLine(ImVec2(x, 0), ImVec2(x, static_cast<float>(h)),
                                                IM_COL32(255, 255, 255, 160), 2.0f);
    }
}

void Hud::draw(GameState& gs, const World& world, unsigned fbo, int w, int h) {
    mVertices = 0;
    if (!mReady)
        return;
    gl::StateGuard guard; // the backend changes blend, scissor, programs, bindings: the host gets them back
    ImGuiIO& io = ImGui::GetIO();
    if (mWindowed)
        ImGui_ImplGlfw_NewFrame();
    else {
        io.DisplaySize = ImVec2(static_cast<float>(w), static_cast<float>(h));
        io.DeltaTime = 1.0f / 30.0f;
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    flightWindow(gs, world);
    frameWindow(gs, w);
    settingsWindow(gs, h);
    overlays(gs, world, w, h);
    ImGui::Render();
    ImDrawData* dd = ImGui::GetDrawData();
    mVertices = dd->TotalVtxCount;
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, w, h);
    ImGui_ImplOpenGL3_RenderDrawData(dd);
}

} // namespace pacifica::game
