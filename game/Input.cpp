// Input: devices -> controls (Input.h).
#include "Input.h"

#include <engine/gl/GlContext.h>

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

namespace pacifica::game {

namespace {
constexpr double DEADZONE = 0.12;
double dead(double v) {
    return std::abs(v) < DEADZONE ? 0.0 : (v - std::copysign(DEADZONE, v)) / (1.0 - DEADZONE);
}
enum Edge {
    E_BOMB,
    E_CAMERA,
    E_PAUSE,
    E_SLOW,
    E_HUD,
    E_RESTART,
    E_PAD_BOMB,
    E_PAD_CAMERA,
    E_PAD_PAUSE,
    E_PAD_SLOW
};
} // namespace

Input::Input(gl::GlContext& ctx) : mCtx(ctx) {
    // Sticky keys: a key pressed and released between two polls still reads as pressed once, so a tap is
    // never lost on a slow frame (llvmpipe: ~0.3 s).
    if (auto* window = static_cast<GLFWwindow*>(mCtx.nativeWindow()))
        glfwSetInputMode(window, GLFW_STICKY_KEYS, GLFW_TRUE);
}

InputState Input::poll(bool uiKeyboard, bool uiMouse) {
    InputState in;
    auto* window = static_cast<GLFWwindow*>(mCtx.nativeWindow());
    const double now = glfwGetTime();
    const double dt = mLastTime < 0.0 ? 0.0 : std::min(now - mLastTime, 0.25); // as the simulation's cap
    mLastTime = now;
    auto edge = [&](int slot, bool down) {
        const bool pressed = down && !mWas[slot];
        mWas[slot] = down;
        return pressed;
    };
    auto key = [&](int k) { return !uiKeyboard && mCtx.keyDown(k); };
    auto axis = [&](int plus, int minus) { return (key(plus) ? 1.0 : 0.0) - (key(minus) ? 1.0 : 0.0); };

    in.controls.pitch =
        std::clamp(axis(GLFW_KEY_S, GLFW_KEY_W) + axis(GLFW_KEY_DOWN, GLFW_KEY_UP), -1.0, 1.0);
    in.controls.roll =
        std::clamp(axis(GLFW_KEY_D, GLFW_KEY_A) + axis(GLFW_KEY_RIGHT, GLFW_KEY_LEFT), -1.0, 1.0);
    in.controls.yaw = axis(GLFW_KEY_E, GLFW_KEY_Q);
    double throttleRate =
        0.6 * (axis(GLFW_KEY_R, GLFW_KEY_F) + axis(GLFW_KEY_LEFT_SHIFT, GLFW_KEY_LEFT_CONTROL));
    in.bomb = edge(E_BOMB, key(GLFW_KEY_B));
    in.rocket = key(GLFW_KEY_SPACE);
    in.nextCamera = edge(E_CAMERA, key(GLFW_KEY_C));
    in.pause = edge(E_PAUSE, key(GLFW_KEY_P));
    in.slowMotion = edge(E_SLOW, key(GLFW_KEY_T));
    in.toggleHud = edge(E_HUD, mCtx.keyDown(GLFW_KEY_F1));
    in.restart = edge(E_RESTART, key(GLFW_KEY_BACKSPACE));
    in.quit = mCtx.keyDown(GLFW_KEY_ESCAPE);

    // Mouse flight: right button held, the cursor's motion moves a virtual stick (full deflection at 300 px).
    if (window) {
        double mx = 0.0, my = 0.0;
        glfwGetCursorPos(window, &mx, &my);
        const bool held = !uiMouse && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        if (held && mMouseFlying) {
            mStickX = std::clamp(mStickX + (mx - mMouseX) / 300.0, -1.0, 1.0);
            mStickY = std::clamp(mStickY + (my - mMouseY) / 300.0, -1.0, 1.0);
        } else if (!held) {
            mStickX = mStickY = 0.0;
        }
        mMouseFlying = held;
        mMouseX = mx;
        mMouseY = my;
        if (held) {
            in.controls.roll = std::clamp(in.controls.roll + mStickX, -1.0, 1.0);
            in.controls.pitch = std::clamp(in.controls.pitch + mStickY, -1.0, 1.0); // pull back = nose up
        }
    }

    // The first joystick with a gamepad mapping; none present is fine (keyboard and mouse only).
    mGamepad.clear();
    for (int jid = GLFW_JOYSTICK_1; jid <= GLFW_JOYSTICK_LAST; ++jid) {
        GLFWgamepadstate pad;
        if (!glfwJoystickIsGamepad(jid) || !glfwGetGamepadState(jid, &pad))
            continue;
        const char* name = glfwGetGamepadName(jid);
        mGamepad = name ? name : "gamepad";
        in.controls.roll = std::clamp(in.controls.roll + dead(pad.axes[GLFW_GAMEPAD_AXIS_LEFT_X]), -1.0, 1.0);
        in.controls.pitch =
            std::clamp(in.controls.pitch + dead(pad.axes[GLFW_GAMEPAD_AXIS_LEFT_Y]), -1.0, 1.0);
        in.controls.yaw = std::clamp(in.controls.yaw + dead(pad.axes[GLFW_GAMEPAD_AXIS_RIGHT_X]), -1.0, 1.0);
        // Triggers rest at -1.
        throttleRate += 0.6 * (0.5 * (pad.axes[GLFW_GAMEPAD_AXIS_RIGHT_TRIGGER] + 1.0) -
                               0.5 * (pad.axes[GLFW_GAMEPAD_AXIS_LEFT_TRIGGER] + 1.0));
        in.bomb = in.bomb || edge(E_PAD_BOMB, pad.buttons[GLFW_GAMEPAD_BUTTON_A] == GLFW_PRESS);
        in.rocket = in.rocket || pad.buttons[GLFW_GAMEPAD_BUTTON_X] == GLFW_PRESS;
        in.nextCamera = in.nextCamera || edge(E_PAD_CAMERA, pad.buttons[GLFW_GAMEPAD_BUTTON_Y] == GLFW_PRESS);
        in.pause = in.pause || edge(E_PAD_PAUSE, pad.buttons[GLFW_GAMEPAD_BUTTON_START] == GLFW_PRESS);
        in.slowMotion =
            in.slowMotion || edge(E_PAD_SLOW, pad.buttons[GLFW_GAMEPAD_BUTTON_BACK] == GLFW_PRESS);
        break;
    }
    mThrottle = std::clamp(mThrottle + throttleRate * dt, 0.0, 1.0);
    in.controls.throttle = mThrottle;
    return in;
}

} // namespace pacifica::game
