// FrameTargets implementation: allocation and flipped float readbacks.
#include "engine/gl/FrameTargets.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pacifica::gl {
namespace {

/// Reads the framebuffer with tightly packed client memory whatever the host's pack state was, and puts
/// that state (pack parameters, pack buffer, read framebuffer) back afterwards.
void readFlipped(const Framebuffer& fbo, int w, int h, std::vector<float>& out) {
    out.resize(static_cast<size_t>(w) * h * 4);
    std::vector<float> tmp(out.size());
    const GLenum packParams[] = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_PACK_SKIP_ROWS,
                                 GL_PACK_SKIP_PIXELS};
    GLint saved[4], readFbo = 0, packBuffer = 0;
    for (int i = 0; i < 4; ++i)
        glGetIntegerv(packParams[i], &saved[i]);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFbo);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer);
    const GLint tight[4] = {4, 0, 0, 0};
    for (int i = 0; i < 4; ++i)
        glPixelStorei(packParams[i], tight[i]);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo.id());
    glReadnPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(tmp.size() * sizeof(float)),
                  tmp.data());
    for (int i = 0; i < 4; ++i)
        glPixelStorei(packParams[i], saved[i]);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(packBuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFbo));
    const size_t row = static_cast<size_t>(w) * 4;
    for (int y = 0; y < h; ++y)
        std::copy_n(&tmp[static_cast<size_t>(h - 1 - y) * row], row, &out[static_cast<size_t>(y) * row]);
}

} // namespace

FrameTargets::FrameTargets(int width, int height) : mWidth(width), mHeight(height) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        throw std::invalid_argument("FrameTargets: size must be within 1..16384, got " +
                                    std::to_string(width) + "x" + std::to_string(height));
    mSceneColor = Texture::create2D(GL_RGBA16F, width, height);
    mDepth = Texture::create2D(GL_DEPTH_COMPONENT32F, width, height);
    mDisplayColor = Texture::create2D(GL_RGBA32F, width, height);
    for (Texture* t : {&mSceneColor, &mDepth, &mDisplayColor})
        t->setSampling(GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
    mSceneFbo = Framebuffer::create();
    mSceneFbo.attachColor(0, mSceneColor);
    mSceneFbo.attachDepth(mDepth);
    mSceneFbo.checkComplete("scene framebuffer (RGBA16F + D32F)");
    mDisplayFbo = Framebuffer::create();
    mDisplayFbo.attachColor(0, mDisplayColor);
    mDisplayFbo.checkComplete("display framebuffer (RGBA32F)");
}

void FrameTargets::readScene(std::vector<float>& rgba) const {
    readFlipped(mSceneFbo, mWidth, mHeight, rgba);
}
void FrameTargets::readDisplay(std::vector<float>& rgba) const {
    readFlipped(mDisplayFbo, mWidth, mHeight, rgba);
}

} // namespace pacifica::gl
