// GL tests of the engine's GL layer under headless EGL (llvmpipe in CI): the headless context: its info, its
// start-up log line, a bogus forced platform, contexts sharing one EGL display. The binary's files share one
// context and the GlTest fixture (GlLayerTest.h).
#include "GlLayerTest.h"

namespace {

using namespace pacifica::gltest;

// Context
// ---------------------------------------------------------------------------------------------------------

using ContextTest = GlTest;

TEST_F(ContextTest, InfoDescribesA45CoreContext) {
    const gl::ContextInfo& ci = info();
    EXPECT_FALSE(ci.vendor.empty());
    EXPECT_FALSE(ci.renderer.empty());
    EXPECT_FALSE(ci.version.empty());
    EXPECT_TRUE(contains(ci.version, "4.5")) << ci.version;
    EXPECT_EQ(ci.renderer, reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    EXPECT_EQ(ci.vendor, reinterpret_cast<const char*>(glGetString(GL_VENDOR)));

    const GLint major = getInt(GL_MAJOR_VERSION), minor = getInt(GL_MINOR_VERSION);
    EXPECT_TRUE(major > 4 || (major == 4 && minor >= 5)) << major << "." << minor;
    EXPECT_NE(getInt(GL_CONTEXT_PROFILE_MASK) & GL_CONTEXT_CORE_PROFILE_BIT, 0);

    EXPECT_TRUE(ci.platform == "egl-device" || ci.platform == "egl-surfaceless") << ci.platform;
    // The engine treats both Mesa software rasterisers as software; only llvmpipe offers GL 4.5.
    const bool softwareRenderer = contains(ci.renderer, "llvmpipe") || contains(ci.renderer, "softpipe");
    EXPECT_EQ(ci.software, softwareRenderer) << ci.renderer;
}

TEST_F(ContextTest, HeadlessContextHasNoWindowAndDebugOutputIsOn) {
    gl::GlContext& ctx = *GlEnvironment::context();
    EXPECT_FALSE(ctx.windowed());
    EXPECT_FALSE(ctx.shouldClose());
    EXPECT_EQ(ctx.framebufferSize(), glm::ivec2(0, 0));
    EXPECT_NO_THROW(ctx.makeCurrent());
    // ContextDesc::debug defaults to true: a debug context with KHR_debug routed to the log.
    EXPECT_NE(getInt(GL_CONTEXT_FLAGS) & GL_CONTEXT_FLAG_DEBUG_BIT, 0);
    EXPECT_TRUE(glIsEnabled(GL_DEBUG_OUTPUT));
}

TEST_F(ContextTest, CreationLogsTheRendererOnce) {
    const std::string expected = "GL context (" + info().platform + "): GL_VENDOR=" + info().vendor +
                                 ", GL_RENDERER=" + info().renderer + ", GL_VERSION=" + info().version;
    int found = 0;
    for (const std::string& line : GlEnvironment::log().texts())
        found += line == expected ? 1 : 0;
    EXPECT_EQ(found, 1) << "expected the log line: " << expected;
}

TEST_F(ContextTest, BogusForcedPlatformThrowsNamingTheVariable) {
    // The variable is validated before any EGL call, so the shared context is not touched.
    const char* previous = std::getenv("PACIFICA_EGL_PLATFORM");
    const std::optional<std::string> saved = previous ? std::optional<std::string>(previous) : std::nullopt;
    ASSERT_EQ(setenv("PACIFICA_EGL_PLATFORM", "bogus", 1), 0);
    const std::string message = messageOf<gl::ContextError>([] { (void)gl::createHeadlessContext(); });
    if (saved)
        setenv("PACIFICA_EGL_PLATFORM", saved->c_str(), 1);
    else
        unsetenv("PACIFICA_EGL_PLATFORM");

    EXPECT_TRUE(contains(message, "PACIFICA_EGL_PLATFORM")) << message;
    EXPECT_TRUE(contains(message, "'bogus'")) << message;
    // The shared context is still current and usable.
    EXPECT_NO_THROW(GlEnvironment::context()->makeCurrent());
    ASSERT_NE(glGetString(GL_RENDERER), nullptr);
    EXPECT_EQ(info().renderer, reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
}

TEST_F(ContextTest, AMissingEglDeviceIsAnErrorListingTheDevices) {
    const std::string message =
        messageOf<gl::ContextError>([] { (void)gl::createHeadlessContext({.eglDevice = 15}); });
    EXPECT_TRUE(contains(message, "EGL device 15 does not exist: this machine has ")) << message;
    // The shared context is still current and usable.
    EXPECT_NO_THROW(GlEnvironment::context()->makeCurrent());
    EXPECT_EQ(info().renderer, reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
}

TEST_F(ContextTest, ACudaDeviceIsFoundThroughEglNvDeviceCudaOrTheDefaultIsTakenWithANote) {
    // A chunk of a sharded replay renders on the GPU Slurm gave it (CUDA_VISIBLE_DEVICES): the EGL device
    // whose EGL_NV_device_cuda index is that one. Where no EGL device is a CUDA device (Mesa only), the
    // default device is taken and info().device says so; with NVIDIA's EGL, the device named, or an error
    // listing them.
    EXPECT_TRUE(
        contains(messageOf<gl::ContextError>([] { (void)gl::createHeadlessContext({.cudaDevice = "x1"}); }),
                 "CUDA device 'x1': expected an index or GPU-UUID"));
    auto zero = gl::createHeadlessContext({.cudaDevice = "0"});
    const std::string device = zero->info().device;
    if (contains(device, "no EGL device is a CUDA device")) {
        EXPECT_TRUE(device.ends_with(" (CUDA device 0 asked for; no EGL device is a CUDA device)")) << device;
        EXPECT_EQ(device.substr(0, device.find(" (CUDA")), info().device); // the default, as the shared one
    } else {
        EXPECT_TRUE(contains(device, ", CUDA device 0")) << device;
        EXPECT_TRUE(contains(zero->info().vendor, "NVIDIA")) << zero->info().vendor;
        const std::string missing =
            messageOf<gl::ContextError>([] { (void)gl::createHeadlessContext({.cudaDevice = "63"}); });
        EXPECT_TRUE(
            contains(missing, "CUDA device 63 has no EGL device (the CUDA devices EGL lists: EGL device "))
            << missing;
        // The same device by its UUID (GL_DEVICE_UUID_EXT of the context just made).
        auto uuidOf = [](gl::GlContext& c) {
            c.makeCurrent();
            GLubyte uuid[GL_UUID_SIZE_EXT] = {};
            glGetUnsignedBytei_vEXT(GL_DEVICE_UUID_EXT, 0, uuid);
            std::string text = "GPU-";
            char byte[3];
            for (int i = 0; i < GL_UUID_SIZE_EXT; ++i) {
                std::snprintf(byte, sizeof byte, "%02x", uuid[i]);
                text += std::string(byte) + (i == 3 || i == 5 || i == 7 || i == 9 ? "-" : "");
            }
            return text;
        };
        const std::string uuid0 = uuidOf(*zero);
        auto byUuid = gl::createHeadlessContext({.cudaDevice = uuid0});
        EXPECT_TRUE(contains(byUuid->info().device, ", CUDA device 0 (GPU-")) << byUuid->info().device;
        // A second GPU, where there is one, is another device: its own EGL device and UUID.
        if (contains(missing, "= CUDA 1")) {
            auto one = gl::createHeadlessContext({.cudaDevice = "1"});
            EXPECT_TRUE(contains(one->info().device, ", CUDA device 1")) << one->info().device;
            EXPECT_NE(uuidOf(*one), uuid0);
            std::printf("CUDA 0: %s, %s; CUDA 1: %s, %s\n", zero->info().device.c_str(), uuid0.c_str(),
                        one->info().device.c_str(), uuidOf(*one).c_str());
        }
    }
    zero.reset();
    EXPECT_NO_THROW(GlEnvironment::context()->makeCurrent());
    EXPECT_EQ(info().renderer, reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
}

// ---------------------------------------------------------------------------------------------------------

TEST(EglDisplaySharing, DestroyingOneHeadlessContextKeepsAnotherWorking) {
    // Runs after the shared environment context exists: a second and third context share its display.
    auto a = gl::createHeadlessContext();
    {
        auto b = gl::createHeadlessContext();
        b->makeCurrent();
    }
    EXPECT_NO_THROW(a->makeCurrent());
    EXPECT_NE(glGetString(GL_RENDERER), nullptr);
    a.reset();
    ASSERT_NE(GlEnvironment::context(), nullptr);
    EXPECT_NO_THROW(GlEnvironment::context()->makeCurrent());
}

} // namespace
