// Headless OpenGL 4.5 core contexts through EGL. Order: a hardware EGL device (EGL_EXT_platform_device,
// skipping Mesa's software device), then Mesa's surfaceless platform (llvmpipe). No default framebuffer:
// everything renders into FBOs. See docs/PLATFORM.md for the verified behaviour on llvmpipe and NVIDIA.
#include "engine/gl/GlContext.h"

#include "engine/Log.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <map>
#include <string>
#include <vector>

namespace pacifica::gl {
namespace {

std::string eglErrorName(EGLint e) {
    switch (e) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    default:
        return "EGL error 0x" + std::to_string(e);
    }
}

bool hasExtension(const char* list, const char* name) {
    if (!list)
        return false;
    const size_t n = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return true;
    }
    return false;
}

/// eglQueryDevicesEXT is there: EGL_EXT_device_enumeration, or EGL_EXT_device_base (enumeration and query in
/// one), which is what NVIDIA's EGL reports (seen with driver 580: no EGL_EXT_device_enumeration in the
/// list).
bool canListDevices(const char* clientExts) {
    return hasExtension(clientExts, "EGL_EXT_device_enumeration") ||
           hasExtension(clientExts, "EGL_EXT_device_base");
}

/// eglInitialize/eglTerminate act on a display shared by every context of the platform: count our users and
/// terminate only when the last context on a display goes, so destroying one context never breaks another.
std::map<EGLDisplay, int>& displayUsers() {
    static std::map<EGLDisplay, int> users;
    return users;
}

void releaseDisplay(EGLDisplay display) {
    auto it = displayUsers().find(display);
    if (it != displayUsers().end() && --it->second > 0)
        return;
    if (it != displayUsers().end())
        displayUsers().erase(it);
    eglTerminate(display);
}

class EglContext final : public GlContext {
public:
    EglContext(EGLDisplay display, EGLContext context, const std::string& platform, bool debug)
        : mDisplay(display), mContext(context) {
        ++displayUsers()[display];
        makeCurrent();
        initialiseInfo(platform, debug);
    }
    ~EglContext() override {
        eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(mDisplay, mContext);
        releaseDisplay(mDisplay);
    }
    void makeCurrent() override {
        if (!eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, mContext))
            throw ContextError("eglMakeCurrent failed: " + eglErrorName(eglGetError()));
    }
    void setDevice(const std::string& device) { mInfo.device = device; }

private:
    EGLDisplay mDisplay;
    EGLContext mContext;
};

/// Initialises `display` and makes a GL 4.5 core context on it without a config or surface
/// (EGL_KHR_no_config_context + EGL_KHR_surfaceless_context). Returns EGL_NO_CONTEXT and a reason on failure.
EGLContext makeCoreContext(EGLDisplay display, bool debug, std::string& why) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize failed: " + eglErrorName(eglGetError());
        return EGL_NO_CONTEXT;
    }
    const char* exts = eglQueryString(display, EGL_EXTENSIONS);
    if (!hasExtension(exts, "EGL_KHR_surfaceless_context")) {
        why = "EGL display lacks EGL_KHR_surfaceless_context";
        if (!displayUsers().count(display))
            eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "eglBindAPI(EGL_OPENGL_API) failed: " + eglErrorName(eglGetError());
        if (!displayUsers().count(display))
            eglTerminate(display);
        return EGL_NO_CONTEXT;
    }
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(exts, "EGL_KHR_no_config_context")) {
        const EGLint cfgAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_NONE};
        EGLint count = 0;
        if (!eglChooseConfig(display, cfgAttribs, &config, 1, &count) || count == 0) {
            why = "no EGL config with EGL_OPENGL_BIT";
            eglTerminate(display);
            return EGL_NO_CONTEXT;
        }
    }
    const EGLint ctxAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                 4,
                                 EGL_CONTEXT_MINOR_VERSION,
                                 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                 EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_CONTEXT_OPENGL_DEBUG,
                                 debug ? EGL_TRUE : EGL_FALSE,
                                 EGL_NONE};
    EGLContext ctx = eglCreateContext(display, config, EGL_NO_CONTEXT, ctxAttribs);
    if (ctx == EGL_NO_CONTEXT) {
        why = "eglCreateContext(GL 4.5 core) failed: " + eglErrorName(eglGetError());
        if (!displayUsers().count(display))
            eglTerminate(display);
    }
    return ctx;
}

/// "0: /dev/dri/renderD128, 1: software" for an error message.
std::string describeDevices(const EGLDeviceEXT* devices, EGLint count) {
    constexpr EGLint DRM_DEVICE_FILE = 0x3233; // EGL_DRM_DEVICE_FILE_EXT (EGL_EXT_device_drm)
    std::string list;
    for (EGLint i = 0; i < count; ++i) {
        const char* exts = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
        const char* file = hasExtension(exts, "EGL_EXT_device_drm")
                               ? eglQueryDeviceStringEXT(devices[i], DRM_DEVICE_FILE)
                               : nullptr;
        list += (i ? ", " : "") + std::to_string(i) + ": " +
                (hasExtension(exts, "EGL_MESA_device_software") ? std::string("software (llvmpipe)")
                 : file                                         ? std::string(file)
                                                                : std::string("a device with no DRM file"));
    }
    return list.empty() ? "none" : list;
}

/// ContextDesc::eglDevice >= 0: that device or an error naming what there is.
std::unique_ptr<GlContext> chosenDeviceContext(const char* clientExts, const ContextDesc& desc) {
    const std::string asked = "EGL device " + std::to_string(desc.eglDevice);
    if (!canListDevices(clientExts) || !hasExtension(clientExts, "EGL_EXT_platform_device"))
        throw ContextError(asked +
                           " was asked for, but this EGL cannot list devices (no EGL_EXT_device_enumeration "
                           "and EGL_EXT_platform_device)");
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!eglQueryDevicesEXT(16, devices, &count))
        count = 0;
    if (desc.eglDevice >= count)
        throw ContextError(asked + " does not exist: this machine has " + std::to_string(count) + " (" +
                           describeDevices(devices, count) + ")");
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[desc.eglDevice], nullptr);
    if (display == EGL_NO_DISPLAY)
        throw ContextError(asked + " (" + describeDevices(devices + desc.eglDevice, 1).substr(3) +
                           "): no display (" + eglErrorName(eglGetError()) + ")");
    std::string why;
    EGLContext ctx = makeCoreContext(display, desc.debug, why);
    if (ctx == EGL_NO_CONTEXT)
        throw ContextError(asked + ": " + why);
    auto context = std::make_unique<EglContext>(display, ctx, "egl-device", desc.debug);
    context->setDevice("EGL device " + std::to_string(desc.eglDevice));
    return context;
}

/// EGL_NV_device_cuda: each EGL device's CUDA device index, -1 for a device that is not a CUDA device.
std::vector<long> cudaIndices(const EGLDeviceEXT* devices, EGLint count) {
    constexpr EGLint CUDA_DEVICE_NV = 0x323A; // EGL_CUDA_DEVICE_NV
    std::vector<long> ids;
    for (EGLint i = 0; i < count; ++i) {
        EGLAttrib id = -1;
        const bool cuda =
            hasExtension(eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS), "EGL_NV_device_cuda") &&
            eglQueryDeviceAttribEXT(devices[i], CUDA_DEVICE_NV, &id);
        ids.push_back(cuda ? static_cast<long>(id) : -1L);
    }
    return ids;
}

/// "GPU-3f0d7c1a-..." -> the 32 hex digits, lower case ("" when it is not a UUID).
std::string uuidDigits(const std::string& text) {
    std::string hex;
    for (char ch : text.substr(text.rfind("GPU-", 0) == 0 ? 4 : 0))
        if (std::isxdigit(static_cast<unsigned char>(ch)))
            hex += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        else if (ch != '-')
            return "";
    return hex.size() == 32 ? hex : "";
}

/// ContextDesc::cudaDevice: the EGL device of that CUDA device; nullptr when no EGL device is a CUDA device.
std::unique_ptr<GlContext> cudaDeviceContext(const char* clientExts, const ContextDesc& desc) {
    const std::string uuid = uuidDigits(desc.cudaDevice);
    char* end = nullptr;
    const long index = uuid.empty() ? std::strtol(desc.cudaDevice.c_str(), &end, 10) : -1;
    if (uuid.empty() && (desc.cudaDevice.empty() || *end != '\0' || index < 0))
        throw ContextError("CUDA device '" + desc.cudaDevice + "': expected an index or GPU-UUID");
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!canListDevices(clientExts) || !eglQueryDevicesEXT(16, devices, &count))
        count = 0;
    const std::vector<long> ids = cudaIndices(devices, count);
    std::string listed;
    for (EGLint i = 0; i < count; ++i)
        if (ids[i] >= 0)
            listed += (listed.empty() ? "" : ", ") + std::string("EGL device ") + std::to_string(i) +
                      " = CUDA " + std::to_string(ids[i]);
    bool nvidia = false; // NVIDIA's EGL is there, though it may give no device a CUDA index (below)
    for (EGLint i = 0; i < count; ++i)
        nvidia =
            nvidia || hasExtension(eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS), "EGL_NV_device_cuda");
    if (listed.empty() && (uuid.empty() || !nvidia))
        return nullptr;
    // A UUID is looked for on every hardware device: NVIDIA's EGL gives no device a CUDA index when
    // CUDA_VISIBLE_DEVICES holds a GPU-UUID (seen on 2x H200), and the UUID does not depend on it.
    std::string uuids; // what the devices asked said, for the error
    for (EGLint i = 0; i < count; ++i) {
        if (uuid.empty() && ids[i] != index)
            continue;
        if (!uuid.empty() &&
            hasExtension(eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
            continue;
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        std::string why;
        EGLContext ctx =
            display == EGL_NO_DISPLAY ? EGL_NO_CONTEXT : makeCoreContext(display, desc.debug, why);
        if (ctx == EGL_NO_CONTEXT && !uuid.empty())
            continue; // a device that makes no context is not the one asked for
        if (ctx == EGL_NO_CONTEXT)
            throw ContextError("CUDA device " + desc.cudaDevice + " (EGL device " + std::to_string(i) +
                               "): " + why);
        auto context = std::make_unique<EglContext>(display, ctx, "egl-device", desc.debug);
        if (!uuid.empty() && uuidDigits(context->info().uuid) != uuid) {
            uuids += (uuids.empty() ? "" : ", ") + std::string("EGL device ") + std::to_string(i) + " = " +
                     context->info().uuid;
            continue; // not this one: the context goes
        }
        context->setDevice("EGL device " + std::to_string(i) +
                           (ids[i] >= 0 ? ", CUDA device " + std::to_string(ids[i]) : std::string()) +
                           (uuid.empty() ? std::string() : " (GPU-" + uuid + ")"));
        return context;
    }
    if (!uuid.empty())
        throw ContextError("CUDA device " + desc.cudaDevice + " is none of the EGL devices' GPUs (" +
                           (uuids.empty() ? std::string("none made a context") : uuids) + ")");
    // NVIDIA's EGL numbers CUDA devices as CUDA does, after CUDA_VISIBLE_DEVICES: with
    // CUDA_VISIBLE_DEVICES=1 the second GPU is CUDA device 0 and the first has none (seen on 2x H200).
    const char* visible = std::getenv("CUDA_VISIBLE_DEVICES");
    throw ContextError(
        "CUDA device " + desc.cudaDevice + " has no EGL device (the CUDA devices EGL lists: " + listed +
        (visible ? std::string("; CUDA_VISIBLE_DEVICES=") + visible + " numbers the visible GPUs from 0"
                 : std::string()) +
        ")");
}

} // namespace

namespace {

/// The default choice: the first hardware EGL device that makes a context, else Mesa's surfaceless
/// platform (PACIFICA_EGL_PLATFORM may force one). Throws ContextError listing why each failed.
std::unique_ptr<EglContext> defaultHeadlessContext(const char* clientExts, const std::string& forced,
                                                   bool debug) {
    std::vector<std::string> reasons;
    // 1. A hardware EGL device.
    if (forced != "surfaceless" && canListDevices(clientExts) &&
        hasExtension(clientExts, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (eglQueryDevicesEXT(16, devices, &count)) {
            for (EGLint i = 0; i < count; ++i) {
                const char* devExts = eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS);
                if (hasExtension(devExts, "EGL_MESA_device_software") && forced != "device")
                    continue; // llvmpipe: prefer the surfaceless path, same renderer
                EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (display == EGL_NO_DISPLAY)
                    continue;
                std::string why;
                EGLContext ctx = makeCoreContext(display, debug, why);
                if (ctx != EGL_NO_CONTEXT) {
                    auto context = std::make_unique<EglContext>(display, ctx, "egl-device", debug);
                    context->setDevice("EGL device " + std::to_string(i));
                    return context;
                }
                reasons.push_back("device " + std::to_string(i) + ": " + why);
            }
        }
        if (count == 0)
            reasons.push_back("no EGL devices");
    }
    // 2. Mesa surfaceless.
    if (forced != "device" && hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay display =
            eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display != EGL_NO_DISPLAY) {
            std::string why;
            EGLContext ctx = makeCoreContext(display, debug, why);
            if (ctx != EGL_NO_CONTEXT) {
                auto context = std::make_unique<EglContext>(display, ctx, "egl-surfaceless", debug);
                context->setDevice("Mesa surfaceless");
                return context;
            }
            reasons.push_back("surfaceless: " + why);
        } else {
            reasons.push_back("surfaceless: no display (" + eglErrorName(eglGetError()) + ")");
        }
    } else if (forced != "device") {
        reasons.push_back("EGL_MESA_platform_surfaceless not supported");
    }
    std::string message = "no headless OpenGL 4.5 context could be created through EGL";
    for (const std::string& r : reasons)
        message += "; " + r;
    throw ContextError(message);
}

} // namespace

std::unique_ptr<GlContext> createHeadlessContext(const ContextDesc& desc) {
    const char* force = std::getenv("PACIFICA_EGL_PLATFORM");
    const std::string forced = force ? force : "";
    if (!forced.empty() && forced != "device" && forced != "surfaceless")
        throw ContextError("PACIFICA_EGL_PLATFORM must be 'device' or 'surfaceless', got '" + forced + "'");

    // libepoxy loads libEGL on the first EGL call and aborts the process when it cannot: look first.
    if (!dlopen("libEGL.so.1", RTLD_LAZY | RTLD_LOCAL)) { // kept loaded: epoxy opens it next
        const char* err = dlerror();
        throw ContextError(std::string("no EGL library: ") + (err ? err : "libEGL.so.1 cannot be loaded") +
                           "; install libegl1 and a driver (libegl-mesa0)");
    }
    const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!clientExts)
        throw ContextError("no EGL implementation found (eglQueryString(EGL_NO_DISPLAY) failed: " +
                           eglErrorName(eglGetError()) + "); install libegl1 and a driver (libegl-mesa0)");
    if (desc.eglDevice >= 0)
        return chosenDeviceContext(clientExts, desc);
    if (!desc.cudaDevice.empty() && hasExtension(clientExts, "EGL_EXT_platform_device"))
        if (std::unique_ptr<GlContext> c = cudaDeviceContext(clientExts, desc))
            return c;
    if (!hasExtension(clientExts, "EGL_EXT_platform_device") &&
        !hasExtension(clientExts, "EGL_MESA_platform_surfaceless"))
        throw ContextError(
            "no headless OpenGL 4.5 context: EGL found no driver: neither devices (EGL_EXT_platform_device) "
            "nor Mesa's surfaceless "
            "platform are offered, so libglvnd loaded no vendor library; install libegl-mesa0 "
            "(Mesa) or the NVIDIA driver's EGL, and check __EGL_VENDOR_LIBRARY_FILENAMES/_DIRS");
    std::unique_ptr<EglContext> context = defaultHeadlessContext(clientExts, forced, desc.debug);
    if (!desc.cudaDevice.empty()) { // no EGL device is a CUDA device: nothing can match, so the default
        logWarning("CUDA device " + desc.cudaDevice +
                   " asked for, but no EGL device is a CUDA device "
                   "(EGL_NV_device_cuda): rendering on " +
                   context->info().device);
        context->setDevice(context->info().device + " (CUDA device " + desc.cudaDevice +
                           " asked for; no EGL device is a CUDA device)");
    }
    return context;
}

} // namespace pacifica::gl
