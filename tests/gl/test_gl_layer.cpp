// GL tests for the engine's GL layer under headless EGL (llvmpipe in CI): the context and its info, the
// move-only RAII wrappers (ownership, moves, wrap/adopt/release), program building with compile errors
// mapped back to source names and lines, GpuTimer in both clocks, StateGuard's save/restore, and
// FrameTargets' top-down float readbacks. The whole binary shares one headless context (GlEnvironment);
// every GL test checks that it raised no GL error and no KHR_debug error it did not expect.
#include <epoxy/gl.h>

#include "engine/Log.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"
#include "engine/gl/GpuTimer.h"
#include "engine/gl/PassTimer.h"
#include "engine/gl/Shader.h"

#include <gtest/gtest.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace {

namespace gl = pacifica::gl;

// ---------------------------------------------------------------------------------------------------------
// Shared context and log capture
// ---------------------------------------------------------------------------------------------------------

/// Every message the engine logs, so tests can see the context's start-up line and KHR_debug errors.
class LogCapture {
public:
    void add(pacifica::LogLevel level, std::string_view message) {
        std::lock_guard lock(mMutex);
        mEntries.push_back({level, std::string(message)});
        std::fprintf(stderr, "[engine log] %.*s\n", static_cast<int>(message.size()), message.data());
    }
    /// Error-level messages that came from the KHR_debug callback ("GL debug ..."), from index `from` on.
    std::vector<std::string> glDebugErrors(size_t from = 0) const {
        std::lock_guard lock(mMutex);
        std::vector<std::string> out;
        for (size_t i = from; i < mEntries.size(); ++i)
            if (mEntries[i].level == pacifica::LogLevel::Error && mEntries[i].text.starts_with("GL debug"))
                out.push_back(mEntries[i].text);
        return out;
    }
    size_t size() const {
        std::lock_guard lock(mMutex);
        return mEntries.size();
    }
    std::vector<std::string> texts() const {
        std::lock_guard lock(mMutex);
        std::vector<std::string> out;
        for (const auto& e : mEntries)
            out.push_back(e.text);
        return out;
    }

private:
    struct Entry {
        pacifica::LogLevel level;
        std::string text;
    };
    mutable std::mutex mMutex;
    std::vector<Entry> mEntries;
};

class GlEnvironment : public ::testing::Environment {
public:
    void SetUp() override {
        pacifica::setLogSink([](pacifica::LogLevel level, std::string_view m) { sLog.add(level, m); });
        try {
            sContext = gl::createHeadlessContext();
        } catch (const gl::ContextError& e) {
            FAIL() << "no headless GL 4.5 context: " << e.what();
        }
        std::printf("[ info ] GL_RENDERER: %s (%s)\n", sContext->info().renderer.c_str(),
                    sContext->info().platform.c_str());
    }
    void TearDown() override {
        sContext.reset();
        pacifica::setLogSink(nullptr);
    }
    static gl::GlContext* context() { return sContext.get(); }
    static LogCapture& log() { return sLog; }

private:
    static inline std::unique_ptr<gl::GlContext> sContext;
    static inline LogCapture sLog;
};

[[maybe_unused]] ::testing::Environment* const gEnvironment =
    ::testing::AddGlobalTestEnvironment(new GlEnvironment);

/// Base for tests that need GL: the context is current, and the test must leave no GL error behind.
class GlTest : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_NE(GlEnvironment::context(), nullptr) << "the shared headless context was not created";
        while (glGetError() != GL_NO_ERROR) {
        }
        mLogStart = GlEnvironment::log().size();
    }
    void TearDown() override {
        if (!GlEnvironment::context())
            return;
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << "the test left a GL error behind";
        if (!mExpectGlDebugErrors) {
            const std::vector<std::string> errors = GlEnvironment::log().glDebugErrors(mLogStart);
            EXPECT_TRUE(errors.empty())
                << "unexpected KHR_debug error: " << (errors.empty() ? "" : errors.front());
        }
    }
    const gl::ContextInfo& info() const { return GlEnvironment::context()->info(); }

    /// Shader compile failures are reported through KHR_debug as errors too (Mesa does).
    bool mExpectGlDebugErrors = false;

private:
    size_t mLogStart = 0;
};

// ---------------------------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------------------------

/// Runs fn, expecting Exception; returns its what() (and records a failure when nothing is thrown).
template <typename Exception, typename Fn>
std::string messageOf(Fn&& fn) {
    try {
        fn();
    } catch (const Exception& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an exception, none was thrown";
    return {};
}

/// True when text contains "name:line" not followed by another digit ("broken.frag:3", not ":30").
bool hasLocation(const std::string& text, const std::string& name, int line) {
    const std::string needle = name + ":" + std::to_string(line);
    for (size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) {
        const size_t after = p + needle.size();
        if (after == text.size() || !std::isdigit(static_cast<unsigned char>(text[after])))
            return true;
    }
    return false;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

GLint getInt(GLenum name) {
    GLint v = 0;
    glGetIntegerv(name, &v);
    return v;
}

// A triangle that covers the whole viewport (vertices from gl_VertexID, no attributes), in a fixed colour.
const char* FULLSCREEN_VERT =
    R"(const vec2 CORNERS[3] = vec2[](vec2(-1.0, -1.0), vec2(3.0, -1.0), vec2(-1.0, 3.0));
void main() { gl_Position = vec4(CORNERS[gl_VertexID], 0.0, 1.0); })";
const char* SOLID_FRAG = R"(out vec4 fragColor;
void main() { fragColor = vec4(0.5, 0.25, 1.0, 1.0); })";

gl::Program buildSolidProgram(const std::string& name) {
    return gl::buildProgram({{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
                             {gl::ShaderStage::Fragment, {{"solid.frag", SOLID_FRAG}}}},
                            name);
}

/// A small draw to time: one full-viewport triangle into a 16x16 FrameTargets, host state kept.
struct SmallDraw {
    gl::FrameTargets targets{16, 16};
    gl::Program program = buildSolidProgram("small draw");
    gl::VertexArray vao = gl::VertexArray::create();

    void draw() const {
        gl::StateGuard guard;
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, targets.sceneFramebuffer().id());
        glViewport(0, 0, targets.width(), targets.height());
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glUseProgram(program.id());
        glBindVertexArray(vao.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
};

// ---------------------------------------------------------------------------------------------------------
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

// ---------------------------------------------------------------------------------------------------------
// RAII wrappers
// ---------------------------------------------------------------------------------------------------------

using GlObjectsTest = GlTest;

TEST_F(GlObjectsTest, DefaultConstructedIsEmpty) {
    gl::Texture t;
    EXPECT_EQ(t.id(), 0u);
    EXPECT_FALSE(t.owned());
    EXPECT_FALSE(static_cast<bool>(t));
    gl::Buffer b;
    EXPECT_EQ(b.id(), 0u);
    EXPECT_EQ(b.size(), 0u);
}

TEST_F(GlObjectsTest, TextureDestructionDeletesTheObject) {
    GLuint id = 0;
    {
        gl::Texture t = gl::Texture::create2D(GL_RGBA8, 4, 2);
        id = t.id();
        ASSERT_NE(id, 0u);
        EXPECT_TRUE(t.owned());
        EXPECT_TRUE(static_cast<bool>(t));
        EXPECT_EQ(t.target(), static_cast<unsigned>(GL_TEXTURE_2D));
        EXPECT_EQ(t.width(), 4);
        EXPECT_EQ(t.height(), 2);
        EXPECT_TRUE(glIsTexture(id));
        GLint w = 0;
        glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_WIDTH, &w);
        EXPECT_EQ(w, 4);
    }
    EXPECT_FALSE(glIsTexture(id));
}

TEST_F(GlObjectsTest, EveryWrapperDeletesItsObject) {
    GLuint buffer = 0, framebuffer = 0, vao = 0, query = 0, program = 0;
    {
        const float data[4] = {1.f, 2.f, 3.f, 4.f};
        gl::Buffer b = gl::Buffer::create(sizeof data, data);
        gl::Framebuffer f = gl::Framebuffer::create();
        gl::VertexArray v = gl::VertexArray::create();
        gl::Query q = gl::Query::create(GL_TIME_ELAPSED);
        gl::Program p = buildSolidProgram("wrapper lifetime");
        buffer = b.id(), framebuffer = f.id(), vao = v.id(), query = q.id(), program = p.id();
        EXPECT_TRUE(glIsBuffer(buffer));
        EXPECT_TRUE(glIsFramebuffer(framebuffer));
        EXPECT_TRUE(glIsVertexArray(vao));
        EXPECT_TRUE(glIsQuery(query));
        EXPECT_TRUE(glIsProgram(program));
    }
    EXPECT_FALSE(glIsBuffer(buffer));
    EXPECT_FALSE(glIsFramebuffer(framebuffer));
    EXPECT_FALSE(glIsVertexArray(vao));
    EXPECT_FALSE(glIsQuery(query));
    EXPECT_FALSE(glIsProgram(program));
}

TEST_F(GlObjectsTest, MoveConstructionTransfersOwnership) {
    gl::Texture a = gl::Texture::create2D(GL_RGBA8, 2, 2);
    const GLuint id = a.id();
    ASSERT_NE(id, 0u);
    {
        gl::Texture b(std::move(a));
        EXPECT_EQ(a.id(), 0u); // NOLINT(bugprone-use-after-move): the empty state is the contract
        EXPECT_FALSE(a.owned());
        EXPECT_FALSE(static_cast<bool>(a));
        EXPECT_EQ(b.id(), id);
        EXPECT_TRUE(b.owned());
        EXPECT_EQ(b.width(), 2);
        a.reset(); // destroying/resetting the moved-from wrapper must not delete b's texture
        EXPECT_TRUE(glIsTexture(id));
    }
    EXPECT_FALSE(glIsTexture(id)) << "the move target's destruction must delete the texture";
}

TEST_F(GlObjectsTest, MovedFromObjectGoingOutOfScopeDoesNotDelete) {
    GLuint id = 0;
    {
        gl::Texture target;
        {
            gl::Texture source = gl::Texture::create2D(GL_RGBA8, 2, 2);
            id = source.id();
            target = std::move(source);
            EXPECT_EQ(source.id(), 0u); // NOLINT(bugprone-use-after-move)
            EXPECT_FALSE(source.owned());
        } // source destroyed here
        EXPECT_TRUE(glIsTexture(id));
        EXPECT_EQ(target.id(), id);
        EXPECT_TRUE(target.owned());
    }
    EXPECT_FALSE(glIsTexture(id));
}

TEST_F(GlObjectsTest, MoveAssignmentDeletesTheOverwrittenObject) {
    gl::Texture a = gl::Texture::create2D(GL_RGBA8, 2, 2);
    gl::Texture b = gl::Texture::create2D(GL_RGBA8, 2, 2);
    const GLuint idA = a.id(), idB = b.id();
    ASSERT_NE(idA, idB);
    b = std::move(a);
    EXPECT_FALSE(glIsTexture(idB)) << "b's previous texture must be deleted when b is overwritten";
    EXPECT_TRUE(glIsTexture(idA));
    EXPECT_EQ(b.id(), idA);
    EXPECT_TRUE(b.owned());
    EXPECT_EQ(a.id(), 0u); // NOLINT(bugprone-use-after-move)

    gl::Texture& alias = b;
    b = std::move(alias); // self-move keeps the object
    EXPECT_EQ(b.id(), idA);
    EXPECT_TRUE(b.owned());
    EXPECT_TRUE(glIsTexture(idA));
}

TEST_F(GlObjectsTest, WrappedHostTextureIsNotDeleted) {
    GLuint host = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &host);
    glTextureStorage2D(host, 1, GL_RGBA8, 2, 2);
    ASSERT_TRUE(glIsTexture(host));
    {
        gl::Texture wrapped = gl::Texture::wrap(host, GL_TEXTURE_2D);
        EXPECT_EQ(wrapped.id(), host);
        EXPECT_FALSE(wrapped.owned());
        EXPECT_TRUE(static_cast<bool>(wrapped));
        EXPECT_EQ(wrapped.target(), static_cast<unsigned>(GL_TEXTURE_2D));
        gl::Texture moved = std::move(wrapped); // moving a borrowed handle keeps it borrowed
        EXPECT_FALSE(moved.owned());
    }
    EXPECT_TRUE(glIsTexture(host)) << "a wrapped host texture must survive the wrapper";
    glDeleteTextures(1, &host);
    EXPECT_FALSE(glIsTexture(host));
}

TEST_F(GlObjectsTest, ReleaseHandsOverTheIdAndAdoptTakesItBack) {
    GLuint id = 0, released = 0;
    {
        gl::Texture t = gl::Texture::create2D(GL_RGBA8, 2, 2);
        id = t.id();
        released = t.release();
        EXPECT_EQ(t.id(), 0u);
        EXPECT_FALSE(t.owned());
        EXPECT_FALSE(static_cast<bool>(t));
    }
    EXPECT_EQ(released, id);
    EXPECT_TRUE(glIsTexture(id)) << "a released texture must survive its former wrapper";
    {
        gl::Texture adopted = gl::Texture::adopt(id, GL_TEXTURE_2D);
        EXPECT_TRUE(adopted.owned());
    }
    EXPECT_FALSE(glIsTexture(id)) << "an adopted texture is deleted with its wrapper";
}

TEST_F(GlObjectsTest, BufferCreatedWithDataReadsBack) {
    const std::vector<float> data = {0.5f, -1.f, 3.25f, 1e6f, 7.f, 0.f, -0.f, 42.f};
    const size_t bytes = data.size() * sizeof(float);
    gl::Buffer b = gl::Buffer::create(bytes, data.data(), GL_DYNAMIC_STORAGE_BIT);
    ASSERT_NE(b.id(), 0u);
    EXPECT_EQ(b.size(), bytes);
    GLint64 glSize = 0;
    glGetNamedBufferParameteri64v(b.id(), GL_BUFFER_SIZE, &glSize);
    EXPECT_EQ(glSize, static_cast<GLint64>(bytes));

    std::vector<float> back(data.size(), -9.f);
    glGetNamedBufferSubData(b.id(), 0, static_cast<GLsizeiptr>(bytes), back.data());
    EXPECT_EQ(back, data);

    // upload() at an offset replaces exactly that range, and a range ending at size() is allowed.
    const float patch[2] = {11.f, 12.f};
    b.upload(6 * sizeof(float), sizeof patch, patch);
    glGetNamedBufferSubData(b.id(), 0, static_cast<GLsizeiptr>(bytes), back.data());
    std::vector<float> expected = data;
    expected[6] = 11.f;
    expected[7] = 12.f;
    EXPECT_EQ(back, expected);
}

TEST_F(GlObjectsTest, BufferUploadOutOfRangeThrows) {
    std::vector<unsigned char> bytes(64, 7);
    gl::Buffer b = gl::Buffer::create(bytes.size(), bytes.data(), GL_DYNAMIC_STORAGE_BIT);
    const std::string m1 = messageOf<std::logic_error>([&] { b.upload(60, 8, bytes.data()); });
    EXPECT_TRUE(m1.starts_with("Buffer::upload()")) << m1;
    EXPECT_TRUE(contains(m1, "60+8")) << m1;
    EXPECT_TRUE(contains(m1, "64")) << m1;
    const std::string m2 = messageOf<std::logic_error>([&] { b.upload(0, 65, bytes.data()); });
    EXPECT_TRUE(m2.starts_with("Buffer::upload()")) << m2;
    // Nothing was written by the rejected calls.
    std::vector<unsigned char> back(64, 0);
    glGetNamedBufferSubData(b.id(), 0, 64, back.data());
    EXPECT_EQ(back, bytes);
}

TEST_F(GlObjectsTest, IncompleteFramebufferThrowsNamingWhatAndStatus) {
    gl::Framebuffer empty = gl::Framebuffer::create();
    const std::string message =
        messageOf<std::runtime_error>([&] { empty.checkComplete("the attachment-less test FBO"); });
    EXPECT_TRUE(message.starts_with("Framebuffer::checkComplete()")) << message;
    EXPECT_TRUE(contains(message, "the attachment-less test FBO")) << message;
    // GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT, printed as "0x%04X".
    EXPECT_TRUE(contains(message, "0x8CD7")) << message;

    gl::Texture color = gl::Texture::create2D(GL_RGBA8, 4, 4);
    gl::Framebuffer complete = gl::Framebuffer::create();
    complete.attachColor(0, color);
    EXPECT_NO_THROW(complete.checkComplete("a colour-only FBO"));
}

// ---------------------------------------------------------------------------------------------------------
// Shader building
// ---------------------------------------------------------------------------------------------------------

using ShaderTest = GlTest;

TEST_F(ShaderTest, VertexFragmentPairBuilds) {
    gl::Program p =
        gl::buildProgram({{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
                          {gl::ShaderStage::Fragment,
                           {{"tint.frag", "uniform vec4 uTint;\nout vec4 c;\nvoid main() { c = uTint; }"}}}},
                         "tint");
    ASSERT_NE(p.id(), 0u);
    EXPECT_TRUE(p.owned());
    EXPECT_TRUE(glIsProgram(p.id()));
    GLint linked = 0;
    glGetProgramiv(p.id(), GL_LINK_STATUS, &linked);
    EXPECT_EQ(linked, GL_TRUE);
    EXPECT_GE(p.uniformLocation("uTint"), 0);
    EXPECT_EQ(p.uniformLocation("uNoSuchUniform"), -1);
}

TEST_F(ShaderTest, ComputeProgramBuilds) {
    gl::Program p = gl::buildProgram(
        {{gl::ShaderStage::Compute,
          {{"<defines>", "#define N 4"}, {"fill.comp", "layout(local_size_x = N) in;\nvoid main() {}"}}}},
        "fill");
    ASSERT_NE(p.id(), 0u);
    GLint size[3] = {};
    glGetProgramiv(p.id(), GL_COMPUTE_WORK_GROUP_SIZE, size);
    EXPECT_EQ(size[0], 4) << "the <defines> source must be compiled before fill.comp";
}

// Semantic errors (undeclared identifiers, type errors) are the common kind. Mesa reports them with source
// string 0 whatever `#line L N` said (its parser's YYLLOC_DEFAULT resets the source number; only token-level
// syntax and preprocessor errors keep N), so a mapping that trusts N alone names "<source 0>" here.
TEST_F(ShaderTest, CompileErrorNamesTheFileAndLine) {
    mExpectGlDebugErrors = true;
    const std::string brokenFrag = "out vec4 fragColor;\n"                         // line 1
                                   "void main() {\n"                               // line 2
                                   "    fragColor = vec4(undeclaredThing, 1.0);\n" // line 3
                                   "}\n";
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram({{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
                                {gl::ShaderStage::Fragment, {{"broken.frag", brokenFrag}}}},
                               "brokenProgram");
    });
    EXPECT_TRUE(hasLocation(message, "broken.frag", 3)) << message;
    EXPECT_TRUE(message.starts_with("brokenProgram: fragment shader failed to compile")) << message;
    EXPECT_TRUE(contains(message, "undeclaredThing")) << message;
}

TEST_F(ShaderTest, ErrorInTheSecondSourceIsAttributedToIt) {
    mExpectGlDebugErrors = true;
    // Three lines of defines: a location counted across the concatenation would say line 5, not 2.
    const std::string defines = "#define GAIN 2.0\n#define BIAS 0.5\n#define UNUSED 1\n";
    const std::string second = "out vec4 fragColor;\n"                                // line 1
                               "void main() { fragColor = vec4(GAIN * missing); }\n"; // line 2
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
             {gl::ShaderStage::Fragment, {{"<defines>", defines}, {"second.frag", second}}}},
            "twoSources");
    });
    EXPECT_TRUE(hasLocation(message, "second.frag", 2)) << message;
    EXPECT_FALSE(contains(message, "<defines>:")) << message;
    EXPECT_TRUE(contains(message, "twoSources")) << message;
}

// Syntax errors are located at a token, and Mesa keeps the `#line` source number for those.
TEST_F(ShaderTest, SyntaxErrorInTheSecondSourceIsAttributedToIt) {
    mExpectGlDebugErrors = true;
    const std::string defines = "#define GAIN 2.0\n#define BIAS 0.5\n#define UNUSED 1\n";
    const std::string second = "out vec4 fragColor;\n"            // line 1
                               "void main() {\n"                  // line 2
                               "    fragColor = vec4(GAIN) + ;\n" // line 3
                               "}\n";
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
             {gl::ShaderStage::Fragment, {{"<defines>", defines}, {"syntax.frag", second}}}},
            "syntaxError");
    });
    EXPECT_TRUE(hasLocation(message, "syntax.frag", 3)) << message;
    EXPECT_FALSE(contains(message, "<defines>:")) << message;
    EXPECT_FALSE(contains(message, "<source")) << message;
}

TEST_F(ShaderTest, ErrorInAVertexShaderNamesTheVertexStage) {
    mExpectGlDebugErrors = true;
    const std::string message = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"bad.vert", "void main() {\n  gl_Position = vec4(1.0) + ;\n}"}}},
             {gl::ShaderStage::Fragment, {{"solid.frag", SOLID_FRAG}}}},
            "badVertex");
    });
    EXPECT_TRUE(message.starts_with("badVertex: vertex shader failed to compile")) << message;
    EXPECT_TRUE(hasLocation(message, "bad.vert", 2)) << message;
}

TEST_F(ShaderTest, LinkErrorsSayLink) {
    mExpectGlDebugErrors = true;
    // Interface mismatch: the vertex stage writes a vec3, the fragment stage reads a vec4.
    const std::string mismatch = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex,
              {{"out3.vert", "out vec3 vColor;\nvoid main() { vColor = vec3(1.0); "
                             "gl_Position = vec4(0.0); }"}}},
             {gl::ShaderStage::Fragment,
              {{"in4.frag", "in vec4 vColor;\nout vec4 c;\nvoid main() { c = vColor; }"}}}},
            "mismatchedVaryings");
    });
    EXPECT_TRUE(contains(mismatch, "link")) << mismatch;
    EXPECT_TRUE(mismatch.starts_with("mismatchedVaryings: link failed")) << mismatch;

    // A fragment stage without main() compiles but cannot link.
    const std::string noMain = messageOf<gl::ShaderError>([&] {
        (void)gl::buildProgram(
            {{gl::ShaderStage::Vertex, {{"fullscreen.vert", FULLSCREEN_VERT}}},
             {gl::ShaderStage::Fragment, {{"nomain.frag", "out vec4 c;\nvoid notMain() {}"}}}},
            "missingMain");
    });
    EXPECT_TRUE(noMain.starts_with("missingMain: link failed")) << noMain;
}

// mapShaderLog needs no context: pure string rewriting. Source index 0 is the "#version" line that
// buildProgram prepends, so sources[k] is driver string k+1.
const std::vector<gl::ShaderSource> AB = {{"a", ""}, {"b", ""}};

TEST(MapShaderLogTest, MesaLocationsBecomeNameLineColumn) {
    EXPECT_EQ(gl::mapShaderLog("1:12(5): error: x", AB), "a:12:5: error: x");
    EXPECT_EQ(gl::mapShaderLog("2:3(17): warning: y", AB), "b:3:17: warning: y");
}

TEST(MapShaderLogTest, MesaMultiLineLogMapsEveryLine) {
    EXPECT_EQ(gl::mapShaderLog("1:2(3): error: p\n2:40(5): error: q\n", AB),
              "a:2:3: error: p\nb:40:5: error: q\n");
}

TEST(MapShaderLogTest, IndicesOutsideTheSourcesAreNamedByNumber) {
    // Index 0 is the builder's own "#version" line; 3 is past the two sources.
    EXPECT_EQ(gl::mapShaderLog("0:1(10): error: v", AB), "<source 0>:1:10: error: v");
    EXPECT_EQ(gl::mapShaderLog("3:7(1): error: w", AB), "<source 3>:7:1: error: w");
}

TEST(MapShaderLogTest, NvidiaLocationsBecomeNameLine) {
    EXPECT_EQ(gl::mapShaderLog("2(7) : error C1008: undefined variable \"foo\"", AB),
              "b:7 : error C1008: undefined variable \"foo\"");
    EXPECT_EQ(gl::mapShaderLog("1(3) : error C0000: syntax error\n2(9) : warning C7022: z", AB),
              "a:3 : error C0000: syntax error\nb:9 : warning C7022: z");
}

TEST(MapShaderLogTest, TextWithoutLineStartLocationsIsUnchanged) {
    EXPECT_EQ(gl::mapShaderLog("error: linking failed", AB), "error: linking failed");
    EXPECT_EQ(gl::mapShaderLog("error: see 1:2(3) above", AB), "error: see 1:2(3) above");
    EXPECT_EQ(gl::mapShaderLog("", AB), "");
}

// ---------------------------------------------------------------------------------------------------------
// GpuTimer
// ---------------------------------------------------------------------------------------------------------

using GpuTimerTest = GlTest;

TEST_F(GpuTimerTest, WallClockTimesOneSpan) {
    SmallDraw scene;
    gl::GpuTimer timer(gl::GpuTimer::Clock::WallAroundFinish);
    EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::WallAroundFinish);
    EXPECT_TRUE(contains(timer.clockName(), "glFinish")) << timer.clockName();
    timer.begin();
    scene.draw();
    timer.end();
    ASSERT_EQ(timer.samples().size(), 1u);
    const double ms = timer.samples()[0];
    EXPECT_TRUE(std::isfinite(ms)) << ms;
    EXPECT_GT(ms, 0.0);
    EXPECT_LT(ms, 60'000.0) << "a 16x16 triangle cannot take a minute";
    const std::optional<double> latest = timer.poll();
    ASSERT_TRUE(latest.has_value());
    EXPECT_EQ(*latest, ms);
    EXPECT_FALSE(timer.poll().has_value()) << "poll() hands out each measurement once";

    // The draw really happened: the whole scene is the solid colour.
    std::vector<float> rgba;
    scene.targets.readScene(rgba);
    ASSERT_EQ(rgba.size(), 16u * 16u * 4u);
    EXPECT_EQ(rgba[0], 0.5f);
    EXPECT_EQ(rgba[rgba.size() - 2], 1.0f);
}

TEST_F(GpuTimerTest, MisuseThrowsLogicError) {
    gl::GpuTimer timer(gl::GpuTimer::Clock::WallAroundFinish);
    const std::string endFirst = messageOf<std::logic_error>([&] { timer.end(); });
    EXPECT_TRUE(endFirst.starts_with("GpuTimer::end()")) << endFirst;
    timer.begin();
    const std::string twice = messageOf<std::logic_error>([&] { timer.begin(); });
    EXPECT_TRUE(twice.starts_with("GpuTimer::begin()")) << twice;
    timer.end(); // the span opened by the first begin() is still the open one
    EXPECT_EQ(timer.samples().size(), 1u);
    EXPECT_THROW(timer.end(), std::logic_error);

    gl::GpuTimer queries(gl::GpuTimer::Clock::TimerQuery);
    EXPECT_THROW(queries.end(), std::logic_error);
    queries.begin();
    EXPECT_THROW(queries.begin(), std::logic_error);
    queries.end();
    glFinish();

    EXPECT_THROW(gl::GpuTimer(gl::GpuTimer::Clock::WallAroundFinish, 0), std::logic_error);
}

TEST_F(GpuTimerTest, ContextChoosesWallClockOnSoftwareRenderers) {
    gl::GpuTimer timer(info());
    // docs/PLATFORM.md: GL_TIME_ELAPSED is wrong on llvmpipe, right on hardware drivers.
    if (info().software)
        EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::WallAroundFinish) << info().renderer;
    else
        EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::TimerQuery) << info().renderer;
}

TEST_F(GpuTimerTest, TimerQueryRingSurvivesMoreSpansThanSlots) {
    SmallDraw scene;
    gl::GpuTimer timer(gl::GpuTimer::Clock::TimerQuery, 4);
    EXPECT_EQ(timer.clock(), gl::GpuTimer::Clock::TimerQuery);
    EXPECT_TRUE(contains(timer.clockName(), "GL_TIME_ELAPSED")) << timer.clockName();
    for (int i = 0; i < 6; ++i) {
        EXPECT_NO_THROW(timer.begin());
        scene.draw();
        EXPECT_NO_THROW(timer.end());
    }
    glFinish();
    (void)timer.poll();
    // Spans 5 and 6 had to wait for spans 1 and 2; after glFinish the other four are available (llvmpipe's
    // values are wrong, docs/PLATFORM.md, so only their sanity is checked).
    ASSERT_GE(timer.samples().size(), 1u);
    EXPECT_EQ(timer.samples().size(), 6u);
    for (double ms : timer.samples()) {
        EXPECT_TRUE(std::isfinite(ms)) << ms;
        EXPECT_GE(ms, 0.0);
    }
}

// ---------------------------------------------------------------------------------------------------------
// PassTimer
// ---------------------------------------------------------------------------------------------------------

using PassTimerTest = GlTest;

TEST_F(PassTimerTest, WallClockAttributesEachSpanToTheMarkedPass) {
    SmallDraw scene;
    gl::PassTimer timer(gl::GpuTimer::Clock::WallAroundFinish, 3);
    EXPECT_TRUE(contains(timer.clockName(), "glFinish")) << timer.clockName();
    EXPECT_FALSE(timer.poll().has_value()) << "no frame yet";
    timer.beginFrame();
    scene.draw();
    timer.mark(0);
    std::this_thread::sleep_for(std::chrono::milliseconds(30)); // pass 2's span: 30 ms of nothing
    timer.mark(2);
    scene.draw();
    timer.mark(0); // a pass marked twice sums its spans
    timer.endFrame();
    const auto ms = timer.poll();
    ASSERT_TRUE(ms.has_value());
    ASSERT_EQ(ms->size(), 3u);
    EXPECT_GT((*ms)[0], 0.0);
    EXPECT_EQ((*ms)[1], 0.0) << "pass 1 was never marked";
    EXPECT_GE((*ms)[2], 29.0);
    EXPECT_LT((*ms)[2], 5000.0);
    EXPECT_FALSE(timer.poll().has_value()) << "poll() hands out each frame once";
}

TEST_F(PassTimerTest, MisuseThrowsLogicError) {
    for (gl::GpuTimer::Clock clock :
         {gl::GpuTimer::Clock::WallAroundFinish, gl::GpuTimer::Clock::TimerQuery}) {
        gl::PassTimer timer(clock, 2);
        const std::string markFirst = messageOf<std::logic_error>([&] { timer.mark(0); });
        EXPECT_TRUE(markFirst.starts_with("PassTimer::mark()")) << markFirst;
        EXPECT_THROW(timer.endFrame(), std::logic_error);
        timer.beginFrame();
        EXPECT_THROW(timer.beginFrame(), std::logic_error);
        const std::string outside = messageOf<std::logic_error>([&] { timer.mark(2); });
        EXPECT_TRUE(contains(outside, "pass 2 outside [0, 2)")) << outside;
        timer.mark(1);
        timer.endFrame();
        glFinish();
        timer.drain();
    }
    EXPECT_THROW(gl::PassTimer(gl::GpuTimer::Clock::WallAroundFinish, 0), std::logic_error);
    EXPECT_THROW(gl::PassTimer(gl::GpuTimer::Clock::TimerQuery, 1, 0), std::logic_error);
}

TEST_F(PassTimerTest, TimestampRingSurvivesMoreFramesThanSlots) {
    SmallDraw scene;
    gl::PassTimer timer(gl::GpuTimer::Clock::TimerQuery, 2, 3);
    EXPECT_TRUE(contains(timer.clockName(), "GL_TIMESTAMP")) << timer.clockName();
    // A GpuTimer span around the frames: glQueryCounter is allowed inside GL_TIME_ELAPSED (they nest).
    gl::GpuTimer outer(gl::GpuTimer::Clock::TimerQuery);
    outer.begin();
    int frames = 0;
    for (int i = 0; i < 7; ++i) {
        timer.beginFrame(); // frames 4..7 have to wait for frames 1..4's timestamps
        scene.draw();
        timer.mark(0);
        scene.draw();
        timer.mark(1);
        timer.endFrame();
        frames += timer.poll().has_value() ? 1 : 0;
    }
    outer.end();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    glFinish();
    timer.drain();
    const auto last = timer.poll();
    ASSERT_TRUE(last.has_value()) << "drain() leaves the newest frame for poll()";
    ASSERT_EQ(last->size(), 2u);
    for (double ms : *last) { // llvmpipe's timestamps are not meaningful (docs/PLATFORM.md): sanity only
        EXPECT_TRUE(std::isfinite(ms)) << ms;
        EXPECT_GE(ms, 0.0);
    }
    EXPECT_LE(frames, 7);
}

// ---------------------------------------------------------------------------------------------------------
// StateGuard
// ---------------------------------------------------------------------------------------------------------

using StateGuardTest = GlTest;

TEST_F(StateGuardTest, RestoresEverySavedState) {
    gl::Texture colorA = gl::Texture::create2D(GL_RGBA8, 4, 4),
                colorB = gl::Texture::create2D(GL_RGBA8, 4, 4);
    gl::Framebuffer fboA = gl::Framebuffer::create(), fboB = gl::Framebuffer::create();
    fboA.attachColor(0, colorA);
    fboB.attachColor(0, colorB);
    gl::Program programA = buildSolidProgram("host program"), programB = buildSolidProgram("our program");
    gl::VertexArray vaoA = gl::VertexArray::create(), vaoB = gl::VertexArray::create();
    GLint initialViewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, initialViewport);

    // The host's distinctive state.
    glViewport(1, 2, 3, 4);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glEnable(GL_CULL_FACE);
    glEnable(GL_SCISSOR_TEST);
    glClearColor(0.1f, 0.2f, 0.3f, 0.4f);
    glClearDepth(0.25);
    glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_CLIP_DISTANCE1); // the host's clip planes: 1 and 6 on, the rest off
    glEnable(GL_CLIP_DISTANCE6);
    glBindFramebuffer(GL_FRAMEBUFFER, fboA.id());
    glUseProgram(programA.id());
    glBindVertexArray(vaoA.id());
    glActiveTexture(GL_TEXTURE3);
    {
        gl::StateGuard guard;
        glViewport(0, 0, 16, 16);
        glDisable(GL_DEPTH_TEST);
        glDepthFunc(GL_GREATER);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glDisable(GL_CULL_FACE);
        glDisable(GL_SCISSOR_TEST);
        glClearColor(1.f, 1.f, 1.f, 1.f);
        glClearDepth(1.0);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        glDisable(GL_CLIP_DISTANCE1);
        glEnable(GL_CLIP_DISTANCE2);
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fboB.id());
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glUseProgram(programB.id());
        glBindVertexArray(vaoB.id());
        glActiveTexture(GL_TEXTURE0);
        // Sanity: the changes took effect before the guard goes.
        ASSERT_EQ(getInt(GL_DRAW_FRAMEBUFFER_BINDING), static_cast<GLint>(fboB.id()));
        ASSERT_FALSE(glIsEnabled(GL_DEPTH_TEST));
    }
    GLint viewport[4] = {};
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(viewport[0], 1);
    EXPECT_EQ(viewport[1], 2);
    EXPECT_EQ(viewport[2], 3);
    EXPECT_EQ(viewport[3], 4);
    EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
    for (int i = 0; i < 8; ++i)
        EXPECT_EQ(glIsEnabled(GLenum(GL_CLIP_DISTANCE0 + i)), i == 1 || i == 6 ? GL_TRUE : GL_FALSE) << i;
    EXPECT_EQ(getInt(GL_DEPTH_FUNC), GL_LEQUAL);
    GLboolean depthMask = GL_TRUE;
    glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
    EXPECT_EQ(depthMask, GL_FALSE);
    EXPECT_TRUE(glIsEnabled(GL_BLEND));
    EXPECT_EQ(getInt(GL_BLEND_SRC_RGB), GL_ONE);
    EXPECT_EQ(getInt(GL_BLEND_DST_RGB), GL_ONE);
    EXPECT_TRUE(glIsEnabled(GL_CULL_FACE));
    EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
    GLfloat clear[4] = {};
    glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
    EXPECT_FLOAT_EQ(clear[0], 0.1f);
    EXPECT_FLOAT_EQ(clear[1], 0.2f);
    EXPECT_FLOAT_EQ(clear[2], 0.3f);
    EXPECT_FLOAT_EQ(clear[3], 0.4f);
    GLdouble clearDepth = 0.0;
    glGetDoublev(GL_DEPTH_CLEAR_VALUE, &clearDepth);
    EXPECT_DOUBLE_EQ(clearDepth, 0.25);
    EXPECT_EQ(getInt(GL_CLIP_ORIGIN), GL_UPPER_LEFT);
    EXPECT_EQ(getInt(GL_CLIP_DEPTH_MODE), GL_ZERO_TO_ONE);
    EXPECT_EQ(getInt(GL_DRAW_FRAMEBUFFER_BINDING), static_cast<GLint>(fboA.id()));
    EXPECT_EQ(getInt(GL_READ_FRAMEBUFFER_BINDING), static_cast<GLint>(fboA.id()));
    EXPECT_EQ(getInt(GL_CURRENT_PROGRAM), static_cast<GLint>(programA.id()));
    EXPECT_EQ(getInt(GL_VERTEX_ARRAY_BINDING), static_cast<GLint>(vaoA.id()));
    EXPECT_EQ(getInt(GL_ACTIVE_TEXTURE), GL_TEXTURE3);

    // Back to the defaults for the tests that follow.
    glViewport(initialViewport[0], initialViewport[1], initialViewport[2], initialViewport[3]);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(0.f, 0.f, 0.f, 0.f);
    glClearDepth(1.0);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glBindVertexArray(0);
    glActiveTexture(GL_TEXTURE0);
}

// ---------------------------------------------------------------------------------------------------------
// FrameTargets
// ---------------------------------------------------------------------------------------------------------

using FrameTargetsTest = GlTest;

TEST_F(FrameTargetsTest, AllocatesTheDocumentedFormats) {
    gl::FrameTargets targets(8, 4);
    EXPECT_EQ(targets.width(), 8);
    EXPECT_EQ(targets.height(), 4);
    GLint format = 0;
    glGetTextureLevelParameteriv(targets.sceneColor().id(), 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
    EXPECT_EQ(format, GL_RGBA16F);
    GLint depthType = GL_NONE;
    glGetNamedFramebufferAttachmentParameteriv(targets.sceneFramebuffer().id(), GL_DEPTH_ATTACHMENT,
                                               GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &depthType);
    EXPECT_EQ(depthType, GL_TEXTURE) << "the scene framebuffer needs a depth attachment";
    EXPECT_EQ(glCheckNamedFramebufferStatus(targets.displayFramebuffer().id(), GL_DRAW_FRAMEBUFFER),
              static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));
}

TEST_F(FrameTargetsTest, ClearedSceneAndDisplayReadBack) {
    gl::FrameTargets targets(8, 4);
    // Values exactly representable in half precision (the scene is RGBA16F).
    const GLfloat scene[4] = {0.5f, 2.0f, -1.0f, 0.25f};
    glClearNamedFramebufferfv(targets.sceneFramebuffer().id(), GL_COLOR, 0, scene);
    std::vector<float> rgba;
    targets.readScene(rgba);
    ASSERT_EQ(rgba.size(), 8u * 4u * 4u);
    for (size_t i = 0; i < rgba.size(); ++i)
        ASSERT_EQ(rgba[i], scene[i % 4]) << "component " << i;

    // The display target is RGBA32F: any float survives.
    const GLfloat display[4] = {0.1f, 1e4f, -3.75f, 1.0f};
    glClearNamedFramebufferfv(targets.displayFramebuffer().id(), GL_COLOR, 0, display);
    targets.readDisplay(rgba);
    ASSERT_EQ(rgba.size(), 8u * 4u * 4u);
    for (size_t i = 0; i < rgba.size(); ++i)
        ASSERT_EQ(rgba[i], display[i % 4]) << "component " << i;
}

TEST_F(FrameTargetsTest, ReadbackRowsAreTopDown) {
    constexpr int W = 8, H = 4;
    gl::FrameTargets targets(W, H);
    // Every pixel gets R = its column and G = its GL row (row 0 = bottom), one scissored clear each.
    GLint savedScissor[4] = {};
    glGetIntegerv(GL_SCISSOR_BOX, savedScissor);
    glEnable(GL_SCISSOR_TEST);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            glScissor(x, y, 1, 1);
            const GLfloat value[4] = {static_cast<float>(x), static_cast<float>(y), 0.5f, 1.0f};
            glClearNamedFramebufferfv(targets.sceneFramebuffer().id(), GL_COLOR, 0, value);
        }
    glDisable(GL_SCISSOR_TEST);
    glScissor(savedScissor[0], savedScissor[1], savedScissor[2], savedScissor[3]);

    std::vector<float> rgba;
    targets.readScene(rgba);
    ASSERT_EQ(rgba.size(), static_cast<size_t>(W * H * 4));
    // The first row returned is the top of the image, GL's last row.
    EXPECT_EQ(rgba[1], static_cast<float>(H - 1));
    EXPECT_EQ(rgba[static_cast<size_t>((H - 1) * W * 4) + 1], 0.f);
    for (int r = 0; r < H; ++r)
        for (int x = 0; x < W; ++x) {
            const float* px = &rgba[static_cast<size_t>((r * W + x) * 4)];
            EXPECT_EQ(px[0], static_cast<float>(x)) << "row " << r << " column " << x;
            EXPECT_EQ(px[1], static_cast<float>(H - 1 - r)) << "row " << r << " column " << x;
        }
}

TEST_F(FrameTargetsTest, InvalidSizesThrow) {
    const std::string message = messageOf<std::invalid_argument>([] { gl::FrameTargets(0, 4); });
    EXPECT_TRUE(contains(message, "0x4")) << message;
    EXPECT_THROW(gl::FrameTargets(4, 0), std::invalid_argument);
    EXPECT_THROW(gl::FrameTargets(-1, 4), std::invalid_argument);
    EXPECT_THROW(gl::FrameTargets(16385, 1), std::invalid_argument);
    EXPECT_NO_THROW(gl::FrameTargets(1, 1));
}

} // namespace

// Regressions for the GL-layer bugs this suite found (each test fails on the code before its fix).

TEST_F(StateGuardTest, RestoresSeparateBlendFactorsAndPolygonOffset) {
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 2.0f);
    {
        gl::StateGuard guard;
        glBlendFunc(GL_ONE, GL_ONE);
        glDisable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(0.0f, 0.0f);
    }
    GLint srcAlpha = 0, dstAlpha = 0;
    GLfloat factor = 0.0f, units = 0.0f;
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &srcAlpha);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &dstAlpha);
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &factor);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &units);
    EXPECT_EQ(srcAlpha, GL_ONE);
    EXPECT_EQ(dstAlpha, GL_ZERO);
    EXPECT_TRUE(glIsEnabled(GL_POLYGON_OFFSET_FILL));
    EXPECT_EQ(factor, 1.0f);
    EXPECT_EQ(units, 2.0f);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, 0.0f);
    glBlendFunc(GL_ONE, GL_ZERO);
}

TEST_F(GlObjectsTest, BufferUploadRangeCheckCannotOverflowAndMovedFromIsEmpty) {
    const float data[4] = {1, 2, 3, 4};
    gl::Buffer b = gl::Buffer::create(sizeof data, data, GL_DYNAMIC_STORAGE_BIT);
    EXPECT_THROW(b.upload(SIZE_MAX, 2, data), std::logic_error);
    gl::Buffer moved(std::move(b));
    EXPECT_EQ(b.size(), 0u);
    EXPECT_EQ(moved.size(), sizeof data);
    EXPECT_THROW(b.upload(0, 4, data), std::logic_error);
}

TEST_F(FrameTargetsTest, ReadbackIgnoresAndKeepsTheHostsPackState) {
    gl::FrameTargets t(8, 4);
    const float c[4] = {0.5f, 2.0f, 0.25f, 1.0f};
    glClearNamedFramebufferfv(t.sceneFramebuffer().id(), GL_COLOR, 0, c);
    glPixelStorei(GL_PACK_ROW_LENGTH, 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 8);
    std::vector<float> rgba;
    t.readScene(rgba);
    ASSERT_EQ(rgba.size(), 8u * 4u * 4u);
    for (size_t i = 0; i < rgba.size(); ++i)
        ASSERT_EQ(rgba[i], c[i % 4]) << "float " << i;
    GLint rowLength = 0, alignment = 0;
    glGetIntegerv(GL_PACK_ROW_LENGTH, &rowLength);
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    EXPECT_EQ(rowLength, 3);
    EXPECT_EQ(alignment, 8);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
}

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
