// GlContext common part: context info and the KHR_debug message route into the log.
#include "engine/gl/GlContext.h"

#include "engine/Log.h"

#include <epoxy/gl.h>

#include <string>

#if defined(__SANITIZE_ADDRESS__)
#define PACIFICA_LEAK_CHECKS 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define PACIFICA_LEAK_CHECKS 1
#endif
#endif
#ifdef PACIFICA_LEAK_CHECKS
#include <cstdio>
#include <cstring>
#include <dlfcn.h>
#include <link.h>
#endif

namespace pacifica::gl {
namespace {

const char* str(GLenum name) {
    const GLubyte* s = glGetString(name);
    return s ? reinterpret_cast<const char*>(s) : "(null)";
}

void GLAPIENTRY debugCallback(GLenum /*source*/, GLenum type, GLuint id, GLenum severity, GLsizei length,
                              const GLchar* message, const void* /*user*/) {
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION)
        return;
    std::string text = "GL debug (id " + std::to_string(id) + "): " + std::string(message, length);
    if (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH)
        logError(text);
    else
        logWarning(text);
}

} // namespace

bool isSoftwareRenderer(std::string_view renderer) {
    return renderer.find("llvmpipe") != std::string_view::npos ||
           renderer.find("softpipe") != std::string_view::npos;
}

void keepDriverLoadedForLeakChecks() noexcept {
#ifdef PACIFICA_LEAK_CHECKS
    // Mesa's drivers live in .../dri/*_dri.so (swrast_dri.so for llvmpipe). dlopen of a loaded module with
    // RTLD_NOLOAD | RTLD_NODELETE loads nothing and marks it never to be unloaded.
    dl_iterate_phdr(
        [](dl_phdr_info* info, size_t, void*) {
            if (info->dlpi_name && std::strstr(info->dlpi_name, "/dri/"))
                (void)dlopen(info->dlpi_name, RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE);
            return 0;
        },
        nullptr);
#endif
}

namespace {

/// GL_DEVICE_UUID_EXT of the current context in nvidia-smi's form (ContextInfo::uuid), "" without it.
std::string deviceUuid() {
    if (!epoxy_has_gl_extension("GL_EXT_memory_object"))
        return "";
    GLint devices = 0;
    glGetIntegerv(GL_NUM_DEVICE_UUIDS_EXT, &devices);
    if (devices < 1)
        return "";
    GLubyte uuid[GL_UUID_SIZE_EXT] = {};
    glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid);
    std::string text = "GPU-";
    char byte[3];
    for (int i = 0; i < GL_UUID_SIZE_EXT; ++i) {
        if (i == 4 || i == 6 || i == 8 || i == 10)
            text += '-';
        std::snprintf(byte, sizeof byte, "%02x", uuid[i]);
        text += byte;
    }
    return text;
}

} // namespace

void GlContext::initialiseInfo(const std::string& platform, bool debug) {
    keepDriverLoadedForLeakChecks();
    mInfo.vendor = str(GL_VENDOR);
    mInfo.renderer = str(GL_RENDERER);
    mInfo.version = str(GL_VERSION);
    mInfo.platform = platform;
    mInfo.uuid = deviceUuid();
    mInfo.software = isSoftwareRenderer(mInfo.renderer);
    logInfo("GL context (" + platform + "): GL_VENDOR=" + mInfo.vendor + ", GL_RENDERER=" + mInfo.renderer +
            ", GL_VERSION=" + mInfo.version);
    if (debug && epoxy_has_gl_extension("GL_KHR_debug")) {
        glEnable(GL_DEBUG_OUTPUT);
        glDebugMessageCallback(debugCallback, nullptr);
    }
}

} // namespace pacifica::gl
