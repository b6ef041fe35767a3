// GL tests of the engine's GL layer under headless EGL (llvmpipe in CI): the move-only RAII wrappers
// (ownership, moves, wrap/adopt/release, range checks) and StateGuard's save/restore. The binary's files
// share one context and the GlTest fixture (GlLayerTest.h).
#include "GlLayerTest.h"

namespace {

using namespace pacifica::gltest;

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

// liveObjects(): every kind goes up by one per created or adopted object and back down when it is deleted,
// released or moved-from-and-destroyed; borrowed (wrap) objects are not counted.
TEST_F(GlObjectsTest, LiveObjectsCountCreatesAndDeletesByKind) {
    using gl::ObjectKind;
    const gl::LiveObjects before = gl::liveObjects();
    auto delta = [&](ObjectKind k) { return gl::liveObjects().of(k) - before.of(k); };
    GLuint hostTexture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &hostTexture);
    {
        gl::Buffer b = gl::Buffer::create(16, nullptr);
        gl::Texture t = gl::Texture::create2D(GL_RGBA8, 2, 2);
        gl::Texture borrowed = gl::Texture::wrap(hostTexture, GL_TEXTURE_2D);
        gl::Framebuffer f = gl::Framebuffer::create();
        gl::VertexArray v = gl::VertexArray::create();
        gl::Query q = gl::Query::create(GL_TIME_ELAPSED);
        gl::Program p = buildSolidProgram("live objects");
        EXPECT_EQ(delta(ObjectKind::Buffer), 1);
        EXPECT_EQ(delta(ObjectKind::Texture), 1) << "a wrapped host texture is not counted";
        EXPECT_EQ(delta(ObjectKind::Framebuffer), 1);
        EXPECT_EQ(delta(ObjectKind::VertexArray), 1);
        EXPECT_EQ(delta(ObjectKind::Query), 1);
        EXPECT_EQ(delta(ObjectKind::Program), 1);
        EXPECT_EQ(gl::liveObjects().total() - before.total(), 6);
        gl::Texture moved = std::move(t);
        EXPECT_EQ(delta(ObjectKind::Texture), 1) << "a move transfers, it creates nothing";
        const GLuint id = moved.release();
        EXPECT_EQ(delta(ObjectKind::Texture), 0) << "a released object is the caller's";
        gl::Texture adopted = gl::Texture::adopt(id, GL_TEXTURE_2D);
        EXPECT_EQ(delta(ObjectKind::Texture), 1);
    }
    EXPECT_EQ(gl::liveObjects().total(), before.total());
    glDeleteTextures(1, &hostTexture);
    EXPECT_STREQ(gl::toString(ObjectKind::VertexArray), "vertex_array");
    EXPECT_STREQ(gl::toString(ObjectKind::Sync), "sync");
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

TEST_F(GlObjectsTest, BufferUploadRangeCheckCannotOverflowAndMovedFromIsEmpty) {
    const float data[4] = {1, 2, 3, 4};
    gl::Buffer b = gl::Buffer::create(sizeof data, data, GL_DYNAMIC_STORAGE_BIT);
    EXPECT_THROW(b.upload(SIZE_MAX, 2, data), std::logic_error);
    gl::Buffer moved(std::move(b));
    EXPECT_EQ(b.size(), 0u);
    EXPECT_EQ(moved.size(), sizeof data);
    EXPECT_THROW(b.upload(0, 4, data), std::logic_error);
}

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

} // namespace
