// GL tests of what the game draws around the ocean (headless EGL):
//  - host state: a host draws its own geometry with its own GL state, lends a framebuffer to the ocean and
//    draws objects with gl::ObjectRenderer, tonemaps, then draws its geometry again without re-binding
//    anything -- every piece of its state is as it left it and its pixels are bit-identical;
//  - waterline: a ship drawn into the framebuffer the ocean rendered shows its hull above the water and the
//    sea where the hull is below the waterline (depth-tested against the sea).
#include <epoxy/gl.h>

#include "engine/Space.h"
#include "engine/color/ColorPipeline.h"
#include "engine/color/Tonemapper.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"
#include "engine/gl/ObjectRenderer.h"
#include "engine/gl/Shader.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanHost.h"

#include "GlLayerTest.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

using namespace pacifica;

namespace {

constexpr int W = 320, H = 180;

class GameGl : public gltest::GlTest {};

/// Everything of the host's state the test's host relies on.
struct HostState {
    std::array<GLint, 32> ints{};
    std::array<GLfloat, 8> floats{};
    std::array<GLboolean, 8> bools{};
    bool operator==(const HostState&) const = default;
};

HostState snapshot() {
    HostState s;
    const GLenum ints[] = {GL_CURRENT_PROGRAM,
                           GL_VERTEX_ARRAY_BINDING,
                           GL_ARRAY_BUFFER_BINDING,
                           GL_DRAW_FRAMEBUFFER_BINDING,
                           GL_READ_FRAMEBUFFER_BINDING,
                           GL_DEPTH_FUNC,
                           GL_BLEND_SRC_RGB,
                           GL_BLEND_DST_RGB,
                           GL_BLEND_EQUATION_RGB,
                           GL_CULL_FACE_MODE,
                           GL_FRONT_FACE,
                           GL_ACTIVE_TEXTURE,
                           GL_CLIP_ORIGIN,
                           GL_CLIP_DEPTH_MODE,
                           GL_UNPACK_ALIGNMENT,
                           GL_PACK_ALIGNMENT};
    int k = 0;
    for (GLenum e : ints)
        glGetIntegerv(e, &s.ints[k++]);
    glGetIntegerv(GL_VIEWPORT, &s.ints[k]);
    k += 4;
    glGetIntegerv(GL_SCISSOR_BOX, &s.ints[k]);
    k += 4;
    // The host's texture on unit 6 (the ocean documents units 0..model-1 and 12..14 as changed).
    glActiveTexture(GL_TEXTURE6);
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &s.ints[k++]);
    glActiveTexture(static_cast<GLenum>(s.ints[11]));
    glGetFloatv(GL_COLOR_CLEAR_VALUE, &s.floats[0]);
    const GLenum caps[] = {GL_DEPTH_TEST, GL_BLEND, GL_CULL_FACE, GL_SCISSOR_TEST, GL_POLYGON_OFFSET_FILL};
    int b = 0;
    for (GLenum e : caps)
        s.bools[b++] = glIsEnabled(e);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s.bools[b++]);
    return s;
}

constexpr const char* HOST_VERT = R"(layout(location = 0) in vec2 aPos;
void main() { gl_Position = vec4(aPos, 0.5, 1.0); }
)";
constexpr const char* HOST_FRAG = R"(layout(location = 0) out vec4 oColor;
uniform vec4 uColor;
void main() { oColor = uColor; }
)";

/// A scene with an ocean of small waves (the octave preset's heights x 0.1: well under a metre).
struct OceanScene {
    ecs::Registry registry;
    ecs::Entity e;
    OceanScene() {
        e = registry.create();
        ocean::OceanDesc d;
        for (ocean::OctaveDesc& o : d.octaves.octaves)
            o.amplitude *= 0.1;
        registry.emplace<ocean::OceanComponent>(e, ocean::makeOcean(d));
    }
};

std::vector<float> readRgba(const gl::FrameTargets& t) {
    std::vector<float> px;
    t.readScene(px);
    return px;
}

} // namespace

TEST_F(GameGl, OceanAndObjectsLeaveTheHostsStateAndPixelsAlone) {
    // The host's own framebuffer, program, VAO, buffer, texture and fixed-function state.
    gl::Texture hostColor = gl::Texture::create2D(GL_RGBA8, W, H);
    gl::Framebuffer hostFbo = gl::Framebuffer::create();
    glNamedFramebufferTexture(hostFbo.id(), GL_COLOR_ATTACHMENT0, hostColor.id(), 0);
    gl::Texture hostTex = gl::Texture::create2D(GL_RGBA8, 4, 4);
    gl::Program prog = gl::buildProgram({{gl::ShaderStage::Vertex, {{"host.vert", HOST_VERT}}},
                                         {gl::ShaderStage::Fragment, {{"host.frag", HOST_FRAG}}}},
                                        "host");
    const float tri[] = {-0.8f, -0.8f, 0.8f, -0.7f, 0.0f, 0.85f};
    gl::Buffer vbo = gl::Buffer::create(sizeof tri, tri);
    gl::VertexArray vao = gl::VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, vbo.id(), 0, 2 * sizeof(float));
    glEnableVertexArrayAttrib(vao.id(), 0);
    glVertexArrayAttribFormat(vao.id(), 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);

    glBindFramebuffer(GL_FRAMEBUFFER, hostFbo.id());
    glUseProgram(prog.id());
    glUniform4f(glGetUniformLocation(prog.id(), "uColor"), 0.9f, 0.3f, 0.1f, 0.6f);
    glBindVertexArray(vao.id());
    glBindBuffer(GL_ARRAY_BUFFER, vbo.id());
    glActiveTexture(GL_TEXTURE6);
    glBindTexture(GL_TEXTURE_2D, hostTex.id());
    glActiveTexture(GL_TEXTURE3);
    glViewport(8, 6, W - 20, H - 14);
    glScissor(4, 4, W - 8, H - 8);
    glEnable(GL_SCISSOR_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glBlendEquation(GL_FUNC_ADD);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glFrontFace(GL_CW);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glClearColor(0.1f, 0.2f, 0.3f, 1.0f);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);

    auto drawHost = [&] {
        glClear(GL_COLOR_BUFFER_BIT);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        std::vector<unsigned char> px(static_cast<size_t>(W) * H * 4);
        glReadPixels(0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
        return px;
    };
    const std::vector<unsigned char> before = drawHost();
    ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    const HostState s0 = snapshot();

    // A game frame in between: the ocean into the lent scene framebuffer, the game's objects, the tonemap.
    OceanScene scene;
    ocean::OceanRenderer renderer;
    gl::FrameTargets targets(W, H);
    gl::ObjectRenderer objects;
    color::ColorPipeline colour = color::ColorPipeline::createDefault();
    colour.select("", "");
    color::Tonemapper tonemapper(colour);
    Pose cam;
    cam.position = {1.0e6, -2.0e6, 30.0};
    cam.headingDeg = 80.0;
    cam.pitchDeg = -5.0;
    const ocean::OceanFrame f = ocean::makeOceanFrame(cam, 1.0f, W, H, 12.5, targets.sceneFramebuffer().id());
    for (int frame = 0; frame < 2; ++frame) {
        render(renderer, scene.registry, f);
        gl::DrawnObject ship;
        ship.shape = gl::ObjectShape::Carrier;
        ship.length = 330.0;
        ship.pose.position = cam.position + glm::dvec3(600.0, 100.0, -30.0);
        EXPECT_EQ(
            objects.draw({ship}, f.camera, f.targetFramebuffer, W, H, {0.3, 0.5, 0.8}, ocean::EARTH_RADIUS),
            1);
        tonemapper.run(targets.sceneColor(), targets.displayFramebuffer(), W, H);
    }
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

    const HostState s1 = snapshot();
    for (size_t i = 0; i < s0.ints.size(); ++i)
        EXPECT_EQ(s0.ints[i], s1.ints[i]) << "integer state #" << i;
    for (size_t i = 0; i < s0.floats.size(); ++i)
        EXPECT_EQ(s0.floats[i], s1.floats[i]) << "float state #" << i;
    for (size_t i = 0; i < s0.bools.size(); ++i)
        EXPECT_EQ(s0.bools[i], s1.bools[i]) << "boolean state #" << i;
    // The host draws again without touching any state: the same pixels.
    const std::vector<unsigned char> after = drawHost();
    EXPECT_EQ(before, after);
    // And it did draw something (the triangle, blended over the clear colour) in the first place.
    size_t tinted = 0;
    for (size_t i = 0; i < before.size(); i += 4)
        tinted += before[i] > 120; // 0.9 x 0.6 + 0.1 x 0.4 = 0.58 -> 148 over the clear colour (26)
    EXPECT_GT(tinted, static_cast<size_t>(W * H / 5));
    // Leave the shared context as a fresh one for the next test (this test's objects are deleted next).
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
}

TEST_F(GameGl, AShipsHullBelowTheWaterlineIsHiddenBySea) {
    OceanScene scene;
    ocean::OceanRenderer renderer;
    gl::ObjectRenderer objects;
    gl::FrameTargets withSea(W, H), seaOnly(W, H), shipOnly(W, H);
    // Broadside view of a 120 m warship 150 m away, eye 4 m above the sea.
    Pose cam;
    cam.position = {1.0e6, -2.0e6 - 150.0, 4.0};
    cam.headingDeg = 0.0;
    gl::DrawnObject ship;
    ship.shape = gl::ObjectShape::Ship;
    ship.length = 120.0;
    ship.pose.position = {1.0e6, -2.0e6, 0.0};
    ship.pose.headingDeg = 90.0;
    ocean::OceanFrame f;
    f.camera = makeCameraFrame(cam, 0.8f, float(W) / H, 0.05f);
    f.time = 3.0;
    f.width = W;
    f.height = H;
    const glm::dvec3 sun(0.3, -0.6, 0.74);

    f.targetFramebuffer = seaOnly.sceneFramebuffer().id();
    render(renderer, scene.registry, f);
    f.targetFramebuffer = withSea.sceneFramebuffer().id();
    render(renderer, scene.registry, f);
    ASSERT_EQ(objects.draw({ship}, f.camera, f.targetFramebuffer, W, H, sun, ocean::EARTH_RADIUS), 1);
    // The ship alone: reverse-Z depth cleared to 0 (the far plane), nothing else drawn.
    glClearNamedFramebufferfv(shipOnly.sceneFramebuffer().id(), GL_COLOR, 0, std::array<float, 4>{}.data());
    const float zero = 0.0f;
    glClearNamedFramebufferfv(shipOnly.sceneFramebuffer().id(), GL_DEPTH, 0, &zero);
    ASSERT_EQ(
        objects.draw({ship}, f.camera, shipOnly.sceneFramebuffer().id(), W, H, sun, ocean::EARTH_RADIUS), 1);
    const std::vector<float> a = readRgba(withSea), s = readRgba(seaOnly), o = readRgba(shipOnly);

    // Pixels of points on the hull's side (y = -half beam), above (z = +2.5 m) and below (z = -3 m) the
    // waterline, along the middle 60 m of the hull.
    auto pixelOf = [&](const glm::dvec3& world) {
        const glm::dvec3 rel = world - f.camera.origin;
        const glm::vec4 clip = f.camera.viewProj * glm::vec4(glm::vec3(rel), 1.0f);
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        const int x = static_cast<int>((ndc.x * 0.5f + 0.5f) * W),
                  y = static_cast<int>((0.5f - ndc.y * 0.5f) * H);
        return static_cast<size_t>(y * W + x) * 4;
    };
    auto diff = [](const std::vector<float>& p, const std::vector<float>& q, size_t i) {
        return std::abs(p[i] - q[i]) + std::abs(p[i + 1] - q[i + 1]) + std::abs(p[i + 2] - q[i + 2]);
    };
    int above = 0, below = 0, samples = 0;
    for (double x = -30.0; x <= 30.0; x += 5.0, ++samples) {
        const size_t up = pixelOf({1.0e6 + x, -2.0e6 - 7.8, 2.5}),
                     down = pixelOf({1.0e6 + x, -2.0e6 - 7.8, -3.0});
        ASSERT_GT(o[up + 3] + o[up], 0.0f) << "the hull is not where the test projects it";
        ASSERT_GT(diff(o, s, down), 0.05f) << "the hull alone would show below the waterline";
        above += diff(a, o, up) < 1e-6 && diff(a, s, up) > 0.05; // the hull, not the sea
        below += diff(a, s, down) < 1e-6;                        // the sea, not the hull
    }
    EXPECT_EQ(above, samples);
    EXPECT_EQ(below, samples);
}

TEST_F(GameGl, AProgramTheHostDeletedWhileCurrentIsNotRestored) {
    auto make = [] {
        return gl::buildProgram({{gl::ShaderStage::Vertex, {{"host.vert", HOST_VERT}}},
                                 {gl::ShaderStage::Fragment, {{"host.frag", HOST_FRAG}}}},
                                "host");
    };
    gl::Program other = make();
    GLuint deleted = 0;
    {
        gl::Program doomed = make();
        deleted = doomed.id();
        glUseProgram(deleted);
    } // deleted while current: GL frees it once another program is used
    while (glGetError() != GL_NO_ERROR) {
    }
    {
        gl::StateGuard guard;     // what the ocean does around its passes
        glUseProgram(other.id()); // ... its own program: the doomed one is freed now
    }
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    GLint current = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    EXPECT_EQ(current, 0);
    EXPECT_FALSE(glIsProgram(deleted));
}
