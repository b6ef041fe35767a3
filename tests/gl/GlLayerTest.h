// GlLayerTest: what the GL layer's tests share (test_gl_*.cpp, one binary): one headless context for the
// whole binary (GlEnvironment), the engine's log captured, the GlTest fixture that fails a test leaving a GL
// error or an unexpected KHR_debug error behind, and small helpers (a full-screen program, a timed draw).
#pragma once

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

namespace pacifica::gltest {

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

/// Registered once per binary (an inline variable): every test file of the binary shares the context.
inline ::testing::Environment* const gEnvironment = ::testing::AddGlobalTestEnvironment(new GlEnvironment);

/// Base for tests that need GL: the context is current, and the test must leave no GL error behind.
/// GlTestOf<::testing::TestWithParam<T>> for parameterised tests.
template <class Base = ::testing::Test>
class GlTestOf : public Base {
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

using GlTest = GlTestOf<>;

// ---------------------------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------------------------

/// Runs fn, expecting Exception; returns its what() (and records a failure when nothing is thrown).
template <typename Exception, typename Fn>
inline std::string messageOf(Fn&& fn) {
    try {
        fn();
    } catch (const Exception& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an exception, none was thrown";
    return {};
}

/// True when text contains "name:line" not followed by another digit ("broken.frag:3", not ":30").
inline bool hasLocation(const std::string& text, const std::string& name, int line) {
    const std::string needle = name + ":" + std::to_string(line);
    for (size_t p = text.find(needle); p != std::string::npos; p = text.find(needle, p + 1)) {
        const size_t after = p + needle.size();
        if (after == text.size() || !std::isdigit(static_cast<unsigned char>(text[after])))
            return true;
    }
    return false;
}

inline bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

inline GLint getInt(GLenum name) {
    GLint v = 0;
    glGetIntegerv(name, &v);
    return v;
}

// A triangle that covers the whole viewport (vertices from gl_VertexID, no attributes), in a fixed colour.
inline const char* const FULLSCREEN_VERT =
    R"(const vec2 CORNERS[3] = vec2[](vec2(-1.0, -1.0), vec2(3.0, -1.0), vec2(-1.0, 3.0));
void main() { gl_Position = vec4(CORNERS[gl_VertexID], 0.0, 1.0); })";
inline const char* const SOLID_FRAG = R"(out vec4 fragColor;
void main() { fragColor = vec4(0.5, 0.25, 1.0, 1.0); })";

inline gl::Program buildSolidProgram(const std::string& name) {
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

} // namespace pacifica::gltest
