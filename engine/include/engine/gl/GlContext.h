// GlContext: one interface over the ways the engine gets an OpenGL 4.5 core context — headless EGL
// (a hardware EGL device if there is one, else Mesa's surfaceless platform) or a GLFW window.
//
// STEP BY STEP
//   1. auto ctx = pacifica::gl::createHeadlessContext();      // or createWindowContext({...})
//   2. ctx->info().renderer                                    // logged at creation too
//   3. render into your own framebuffers (headless contexts have no default framebuffer)
// When no context can be made, ContextError is thrown with the reason; tools turn it into a non-zero exit.
#pragma once

#include <glm/vec2.hpp>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pacifica::gl {

class ContextError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// True when a GL_RENDERER string names a software rasteriser (Mesa's llvmpipe or softpipe): timer
/// queries are wrong there (docs/PLATFORM.md), and it runs both sides of every shader branch.
bool isSoftwareRenderer(std::string_view renderer);

/// In AddressSanitizer builds: keeps the GL driver modules loaded now (RTLD_NODELETE) until the process ends,
/// so LeakSanitizer sees their one-time state as reachable. Mesa keeps such state (made under pthread_once)
/// only in the driver's own data and unloads the driver at eglTerminate / XCloseDisplay: the state then looks
/// leaked, from a module that can no longer be named, which no suppression can match. Other builds: nothing.
/// Called by every engine context and by the ocean's renderer (for a host's own context); thread-safe.
void keepDriverLoadedForLeakChecks() noexcept;

struct ContextInfo {
    std::string vendor;
    std::string renderer;
    std::string version;
    std::string platform; ///< "egl-device", "egl-surfaceless" or "glfw"
    /// Headless: which device, and why (e.g. "EGL device 1, CUDA device 1 (CUDA_VISIBLE_DEVICES=1)").
    std::string device;
    /// GL_DEVICE_UUID_EXT (EXT_memory_object) as nvidia-smi writes a GPU's UUID,
    /// "GPU-xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx"; "" where the driver does not report it.
    std::string uuid;
    bool software = false; ///< llvmpipe/softpipe: GL timer queries are wrong there (docs/PLATFORM.md)
};

struct ContextDesc {
    int width = 1280; ///< window size (windowed contexts only)
    int height = 720;
    std::string title = "Pacifica";
    bool debug = true; ///< request a debug context and route KHR_debug messages to the log
    bool vsync = true;
    /// Windowed only: the window is mapped at the first swapBuffers, so no blank window stands on the screen
    /// while the first frame's programs build (seconds on a software driver), and a script driving the
    /// window (xdotool search --onlyvisible) knows the host is drawing.
    bool showAtFirstSwap = true;
    /// Headless only. -1: the first hardware EGL device that makes a context, else Mesa's surfaceless
    /// platform. N >= 0: exactly device N of eglQueryDevicesEXT's list (Mesa's software device included,
    /// which is not necessarily last), no fallback; a missing device is a ContextError listing those there.
    int eglDevice = -1;
    /// Headless, with eglDevice < 0: the CUDA device to render on -- an index as CUDA numbers the devices
    /// this process sees (CUDA_VISIBLE_DEVICES=1 makes the second GPU device 0; NVIDIA's EGL follows it), or
    /// a GPU-UUID. The EGL device is found through EGL_NV_device_cuda's EGL_CUDA_DEVICE_NV for an index, and
    /// through GL_DEVICE_UUID_EXT of a context on each device for a UUID (NVIDIA's EGL gives no device a CUDA
    /// index when CUDA_VISIBLE_DEVICES holds UUIDs), never by the order of the device list, which
    /// CUDA_VISIBLE_DEVICES does not change. None matching: a ContextError listing the CUDA
    /// devices there are. A machine where no EGL device is a CUDA device (no NVIDIA EGL driver): the default
    /// choice, with a warning and info().device saying so.
    std::string cudaDevice;
};

class GlContext {
public:
    virtual ~GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    virtual void makeCurrent() = 0;
    const ContextInfo& info() const { return mInfo; }

    // Windowed contexts override these; headless ones have no default framebuffer and never close.
    virtual bool windowed() const { return false; }
    virtual void swapBuffers() {}
    virtual void pollEvents() {}
    virtual bool shouldClose() const { return false; }
    virtual bool keyDown(int /*glfwKey*/) const { return false; }
    virtual glm::ivec2 framebufferSize() const { return {0, 0}; }
    /// The window system's handle (a GLFWwindow* for GLFW windows; nullptr headless), for a host that adds
    /// its own input or UI (e.g. Dear ImGui's GLFW backend).
    virtual void* nativeWindow() const { return nullptr; }

protected:
    GlContext() = default;
    /// Reads GL_VENDOR/RENDERER/VERSION into info(), logs them, installs the KHR_debug callback.
    void initialiseInfo(const std::string& platform, bool debug);
    ContextInfo mInfo;
};

/// Headless GL 4.5 core through EGL: EGL device platform first (hardware), then Mesa surfaceless.
/// PACIFICA_EGL_PLATFORM=device|surfaceless forces one. Throws ContextError when neither works.
std::unique_ptr<GlContext> createHeadlessContext(const ContextDesc& desc = {});

/// A GLFW window with a GL 4.5 core context. Throws ContextError without a display or without GLFW.
std::unique_ptr<GlContext> createWindowContext(const ContextDesc& desc = {});

} // namespace pacifica::gl
