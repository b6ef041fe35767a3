// Hud: the game's Dear ImGui overlay (Debian's libimgui-dev, GLFW + OpenGL 3 backends) drawn into the
// display framebuffer after the tonemap: flight data (speed, altitude above the waves from the ocean's CPU
// height query, heading, throttle, angle of attack, g, stall warning), weapons and targets, CPU and GPU frame
// time, the ocean's counters (passes, draws, active effects), and live switches -- camera, quality preset,
// surface model, sea state, OCIO view, a split-screen wipe between two OCIO views, pause, slow motion,
// autopilot, new sortie. GameState carries what the HUD shows and what its switches change.
#pragma once

#include "Options.h"

#include <game/World.h>
#include <ocean/Ocean.h>

#include <string>
#include <vector>

namespace pacifica::gl {
class GlContext;
}

namespace pacifica::game {

struct GameState {
    SeaSettings sea;
    bool seaChanged = false; ///< set by the HUD: rebuild the ocean
    CameraMode camera = CameraMode::Chase;
    double fovDeg = 60.0;
    std::string view, wipeView;
    std::vector<std::string> views;
    bool wipe = false;
    double wipePosition = 0.5;
    bool hud = true;
    bool paused = false, slowMotion = false, autopilot = false;
    bool restartRequested = false;
    std::string autopilotPhase;
    std::string banner;
    double bannerUntil = 0.0; ///< game time the banner stays until
    std::string gamepad;
    ocean::OceanStats stats;
    double frameCpuMs = 0.0, frameGpuMs = 0.0;
    std::string gpuClock;
    int objectsDrawn = 0;
};

/// Turns a game event into the banner (and appends it to `log`).
void announce(GameState& gs, const World& world, const GameEvent& e, std::vector<std::string>& log);

class Hud {
public:
    /// Initialises Dear ImGui for the context's window (keyboard and mouse through GLFW) or, headless, for
    /// drawing only. If the OpenGL 3 backend cannot start, the HUD is off and a warning is logged.
    explicit Hud(gl::GlContext& ctx);
    ~Hud();
    Hud(const Hud&) = delete;
    Hud& operator=(const Hud&) = delete;

    /// Draws into framebuffer fbo (w x h). Saves and restores the GL state it touches.
    void draw(GameState& gs, const World& world, unsigned fbo, int w, int h);
    /// The HUD's widgets have the keyboard (a text field or a focused widget) / the mouse (it is over a
    /// panel): the game ignores that device then.
    bool wantsKeyboard() const;
    bool wantsMouse() const;
    /// Vertices in the last drawn frame (0 = nothing drawn): the tests' proof the HUD rendered.
    long long lastVertexCount() const { return mVertices; }

private:
    void flightWindow(const GameState& gs, const World& world);
    void frameWindow(const GameState& gs, int w);
    void settingsWindow(GameState& gs, int h);
    void overlays(const GameState& gs, const World& world, int w, int h);

    bool mReady = false, mWindowed = false;
    long long mVertices = 0;
    float mWind = 12.0f;
    bool mWindEditing = false;
};

} // namespace pacifica::game
