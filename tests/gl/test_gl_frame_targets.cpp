// GL tests of the engine's GL layer under headless EGL (llvmpipe in CI): FrameTargets: formats, clears,
// top-down float readbacks that keep the host's pack state. The binary's files share one context and the
// GlTest fixture (GlLayerTest.h).
#include "GlLayerTest.h"

namespace {

using namespace pacifica::gltest;

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

} // namespace
