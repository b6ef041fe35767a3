// Input: keyboard, mouse and gamepad (GLFW's gamepad API) -> the player's controls and the game's actions.
// Keyboard: W/S (or Up/Down) pitch, A/D (or Left/Right) roll, Q/E rudder, R/F (or Shift/Ctrl) throttle,
// B bomb, Space rockets, C camera, P pause, T slow motion, F1 HUD, Backspace new sortie, Escape quit.
// Mouse: hold the right button and move to fly (a virtual stick that recentres on release).
// Gamepad (the first joystick with a gamepad mapping; none is fine): left stick pitch/roll, right stick
// rudder, right/left trigger throttle up/down, A bomb, X rockets, Y camera, Start pause, Back slow motion.
#pragma once

#include <game/FlightModel.h>

#include <string>

namespace pacifica::gl {
class GlContext;
}

namespace pacifica::game {

struct InputState {
    FlightControls controls;
    bool bomb = false;   ///< pressed this frame (edge)
    bool rocket = false; ///< held
    bool nextCamera = false, pause = false, slowMotion = false, toggleHud = false, restart = false;
    bool quit = false;
};

class Input {
public:
    explicit Input(gl::GlContext& ctx);
    /// Reads the devices; uiKeyboard / uiMouse: the HUD's widgets have that device (the game ignores it).
    InputState poll(bool uiKeyboard, bool uiMouse);
    /// The gamepad in use ("" = none present).
    const std::string& gamepadName() const { return mGamepad; }

private:
    gl::GlContext& mCtx;
    double mThrottle = 0.0;
    double mLastTime = -1.0;
    double mMouseX = 0.0, mMouseY = 0.0, mStickX = 0.0, mStickY = 0.0;
    bool mMouseFlying = false;
    std::string mGamepad;
    bool mWas[16] = {};
};

} // namespace pacifica::game
