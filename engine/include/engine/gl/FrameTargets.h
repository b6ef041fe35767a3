// FrameTargets: the HDR frame a host renders into — a scene-linear RGBA16F colour + 32-bit float depth
// framebuffer, and an RGBA32F display framebuffer the tonemap pass writes — with top-down readbacks.
#pragma once

#include "engine/gl/GlObjects.h"

#include <vector>

namespace pacifica::gl {

class FrameTargets {
public:
    FrameTargets(int width, int height);

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    const Framebuffer& sceneFramebuffer() const { return mSceneFbo; }
    const Texture& sceneColor() const { return mSceneColor; }
    const Framebuffer& displayFramebuffer() const { return mDisplayFbo; }

    /// RGBA floats, rows top-down (GL reads bottom-up; flipped here).
    void readScene(std::vector<float>& rgba) const;
    void readDisplay(std::vector<float>& rgba) const;

private:
    int mWidth, mHeight;
    Texture mSceneColor, mDepth, mDisplayColor;
    Framebuffer mSceneFbo, mDisplayFbo;
};

} // namespace pacifica::gl
