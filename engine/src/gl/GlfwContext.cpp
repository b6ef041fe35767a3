// Windowed OpenGL 4.5 core context through GLFW 3.3 (needs an X display; under CI, xvfb-run).
#include "engine/gl/GlContext.h"

#include <epoxy/gl.h>
// epoxy must come before GLFW (docs/PLATFORM.md).
#include <GLFW/glfw3.h>

#include <string>

namespace pacifica::gl {
namespace {

std::string gGlfwError;

void glfwErrorCallback(int code, const char* description) {
    gGlfwError = "GLFW error " + std::to_string(code) + ": " + (description ? description : "");
}

class GlfwContext final : public GlContext {
public:
    explicit GlfwContext(const ContextDesc& desc) {
        glfwSetErrorCallback(glfwErrorCallback);
        if (!glfwInit())
            throw ContextError("cannot open a window: glfwInit failed (" + gGlfwError +
                               "); is DISPLAY set? Under CI use xvfb-run");
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, desc.debug ? GLFW_TRUE : GLFW_FALSE);
        glfwWindowHint(GLFW_VISIBLE, desc.showAtFirstSwap ? GLFW_FALSE : GLFW_TRUE);
        mHidden = desc.showAtFirstSwap;
        mWindow = glfwCreateWindow(desc.width, desc.height, desc.title.c_str(), nullptr, nullptr);
        if (!mWindow) {
            glfwTerminate();
            throw ContextError("cannot create a GL 4.5 core window: " + gGlfwError);
        }
        makeCurrent();
        glfwSwapInterval(desc.vsync ? 1 : 0);
        initialiseInfo("glfw", desc.debug);
    }
    ~GlfwContext() override {
        glfwDestroyWindow(mWindow);
        glfwTerminate();
    }
    void makeCurrent() override { glfwMakeContextCurrent(mWindow); }
    bool windowed() const override { return true; }
    void* nativeWindow() const override { return mWindow; }
    void swapBuffers() override {
        glfwSwapBuffers(mWindow);
        if (mHidden) {
            glfwShowWindow(mWindow);
            mHidden = false;
        }
    }
    void pollEvents() override { glfwPollEvents(); }
    bool shouldClose() const override { return glfwWindowShouldClose(mWindow); }
    bool keyDown(int key) const override { return glfwGetKey(mWindow, key) == GLFW_PRESS; }
    glm::ivec2 framebufferSize() const override {
        int w = 0, h = 0;
        glfwGetFramebufferSize(mWindow, &w, &h);
        return {w, h};
    }

private:
    GLFWwindow* mWindow = nullptr;
    bool mHidden = false; ///< created unmapped; shown at the first swapBuffers (ContextDesc::showAtFirstSwap)
};

} // namespace

std::unique_ptr<GlContext> createWindowContext(const ContextDesc& desc) {
    return std::make_unique<GlfwContext>(desc);
}

} // namespace pacifica::gl
