// A host as many game studios build one: -fno-exceptions -fno-rtti, its own GL context (EGL) and its own
// framebuffer, its own entity system (none here): it embeds the ocean through ocean/Ocean.h alone (no
// Pacifica engine header, no registry) and renders a frame with an explosion and a ship's wake. Errors come
// back as values; a bad frame or query is refused without aborting the host.
#include <ocean/Ocean.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#if defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(__GXX_RTTI)
#error "this consumer must be built with -fno-exceptions -fno-rtti"
#endif

namespace oc = pacifica::ocean;

namespace {

int failures = 0;

void check(bool ok, const char* what) {
    if (!ok) {
        std::fprintf(stderr, "consumer_noexcept: FAILED %s\n", what);
        ++failures;
    }
}

bool hasExtension(const char* list, const char* name) {
    return list && std::strstr(list, name) != nullptr;
}

/// The host's context: Mesa's surfaceless platform, else the first EGL device; GL 4.5 core, no surface.
bool makeContext() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    EGLDisplay display = EGL_NO_DISPLAY;
    if (hasExtension(client, "EGL_MESA_platform_surfaceless"))
        display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY && hasExtension(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[4];
        EGLint count = 0;
        if (eglQueryDevicesEXT(4, devices, &count) && count > 0)
            display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
    }
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor) || !eglBindAPI(EGL_OPENGL_API))
        return false;
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
    return context != EGL_NO_CONTEXT && eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context);
}

/// A ship that has sailed east at 10 m/s for 80 s, a wake point every 2 s (newest first).
void sail(oc::Ship& ship, oc::ShipTrail& trail, double t) {
    ship.position = {0.0, 300.0};
    ship.length = 120.0;
    trail.active = true;
    for (int i = 0; i <= 40; ++i)
        trail.history.push_back({ship.position - glm::dvec2(20.0 * i, 0.0), t - 2.0 * i, 10.0});
}

} // namespace

int main() {
    if (!makeContext()) {
        std::fprintf(stderr, "consumer_noexcept: no EGL GL 4.5 context\n");
        return 1;
    }
    // 1. A bad description is refused with the field named, nothing thrown.
    oc::OceanDesc bad;
    bad.effectGrids.wakeRings = 0;
    oc::OceanComponent ocean;
    const oc::Status refused = oc::makeOcean(bad, ocean);
    check(!refused && refused.code == oc::ErrorCode::InvalidArgument, "makeOcean refuses wakeRings = 0");
    check(refused.message.find("effectGrids.wakeRings") != std::string::npos, "the message names the field");
    check(!ocean.surface, "a refused description leaves the component empty");
    check(oc::makeOcean({}, ocean).ok() && ocean.surface, "makeOcean({}) builds the surface");

    // 2. The host's framebuffer: HDR colour and a 32-bit float depth (compute shading writes into it).
    const int w = 96, h = 54;
    GLuint color = 0, depth = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &color);
    glTextureStorage2D(color, 1, GL_RGBA16F, w, h);
    glCreateTextures(GL_TEXTURE_2D, 1, &depth);
    glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, w, h);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    check(glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE, "host FBO");

    // 3. The scene as plain data: one ocean, one explosion, one ship's wake.
    const double t = 500.0;
    oc::Explosion explosion;
    explosion.center = {150.0, 500.0};
    explosion.startTime = t - 6.0;
    oc::Ship ship;
    oc::ShipTrail trail;
    sail(ship, trail, t);
    const oc::OceanInstance oceans[] = {{7, &ocean}};
    const oc::WakeRef wakes[] = {{&ship, &trail}};
    const oc::OceanScene scene{oceans, {{&explosion, 1}, wakes}};
    pacifica::Pose pose;
    pose.position = {0.0, -200.0, 120.0};
    pose.pitchDeg = -20.0;
    oc::OceanFrame frame = oc::makeOceanFrame(pose, 1.0f, w, h, t, fbo);

    // 4. A frame, the host's GL state kept: its blend enable and its bound framebuffer.
    glEnable(GL_BLEND);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    {
        oc::OceanRenderer renderer;
        const oc::Status drawn = renderer.render(scene, frame);
        if (!drawn)
            std::fprintf(stderr, "consumer_noexcept: render: %s\n", drawn.message.c_str());
        check(drawn.ok(), "render() succeeds");
        check(glIsEnabled(GL_BLEND) == GL_TRUE, "the host's GL_BLEND is restored");
        GLint bound = -1;
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &bound);
        check(bound == 0, "the host's framebuffer binding is restored");
        const oc::OceanStats& stats = renderer.lastStats();
        check(stats.explosions.active == 1 && stats.wakes.active == 1,
              "the explosion and the wake are drawn");
        std::vector<float> rgba(static_cast<size_t>(w) * h * 4);
        glGetTextureImage(color, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(float)),
                          rgba.data());
        double sum = 0.0;
        bool finite = true;
        for (float v : rgba) {
            finite = finite && std::isfinite(v) && v >= 0.0f;
            sum += v;
        }
        check(finite, "every pixel is a finite scene-linear value");
        check(sum / static_cast<double>(rgba.size()) > 1e-3, "the frame is not black");

        // 5. Bad frames and queries come back as errors; the renderer goes on.
        oc::OceanFrame nanTime = frame;
        nanTime.time = std::nan("");
        const oc::Status nan = renderer.render(scene, nanTime);
        check(nan.code == oc::ErrorCode::InvalidArgument &&
                  nan.message.find("OceanFrame.time") != std::string::npos,
              "a NaN time is refused, naming OceanFrame.time");
        oc::OceanFrame empty = frame;
        empty.width = 0;
        check(renderer.render(scene, empty).code == oc::ErrorCode::InvalidArgument,
              "a 0-wide frame is refused");
        check(renderer.render(scene, frame).ok(), "the next good frame renders");

        const glm::dvec2 points[] = {{150.0, 500.0}, {-400.0, 300.0}, {1000.0, -2000.0}};
        double heights[3] = {};
        check(oc::heightsAt(ocean, scene.effects, points, t, heights).ok(), "heightsAt()");
        check(std::isfinite(heights[0]) && std::abs(heights[0]) < 20.0, "a finite height at the explosion");
        const glm::dvec2 nanPoint[] = {{std::nan(""), 0.0}};
        double nanHeight[1] = {};
        check(oc::heightsAt(ocean, scene.effects, nanPoint, t, nanHeight).code ==
                  oc::ErrorCode::InvalidArgument,
              "a NaN query point is refused");
        std::printf("consumer_noexcept OK: %d draws, %d passes, height at the explosion %.3f m, %s\n",
                    stats.draws, stats.passes, heights[0],
                    reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    }
    return failures == 0 ? 0 : 1;
}
