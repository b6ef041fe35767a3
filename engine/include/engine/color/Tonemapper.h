// Tonemapper: the GL pass that turns the renderer's scene-linear HDR frame into display code values with
// the OCIO processor a ColorPipeline selected. One fullscreen triangle (gl_VertexID, no vertex buffer); the
// fragment shader is OCIO's GLSL for the selected (display, view) followed by a main() that texelFetch-es
// the scene-linear texture at the fragment's pixel, applies the OCIO function to RGB and passes alpha
// through. The LUT textures OCIO asks for are uploaded once, at construction.
//
// STEP BY STEP
//   1. ColorPipeline pipeline = ColorPipeline::fromEnvironmentOr(path); pipeline.select(display, view);
//   2. Tonemapper tonemap(pipeline);                        // a GL 4.5 context must be current
//   3. tonemap.run(sceneLinear, displayTarget, width, height);   // every frame
//   4. after pipeline.select(...) changes the selection: tonemap = Tonemapper(pipeline);
#pragma once

#include "engine/gl/GlObjects.h"

#include <memory>
#include <string>

namespace pacifica::color {

class ColorPipeline;

class Tonemapper {
public:
    /// Builds the program and uploads the LUTs for the pipeline's current selection. The Tonemapper is a
    /// snapshot: it does not follow later ColorPipeline::select() calls, so create a new one when the
    /// selection changes (display() / view() tell which selection it was built for). Needs a current GL
    /// 4.5 context; throws gl::ShaderError when OCIO's GLSL fails to compile (the log names the source
    /// "ocio:<display>/<view>") and ColorError when the pipeline cannot produce its GPU shader.
    /// Construction uses direct state access and leaves the host's bindings and pixel-unpack state as
    /// they were.
    explicit Tonemapper(const ColorPipeline& pipeline);
    Tonemapper(Tonemapper&& other) noexcept;
    Tonemapper& operator=(Tonemapper&& other) noexcept;
    Tonemapper(const Tonemapper&) = delete;
    Tonemapper& operator=(const Tonemapper&) = delete;
    /// Deletes the program, vertex array and LUT textures: the context must be current.
    ~Tonemapper();

    /// Draws pixels [0, width) x [0, height) of displayTarget (owned, or a host's wrapped with
    /// gl::Framebuffer::wrap(); 0 = the default framebuffer) from the same pixels of sceneLinear (a 2D
    /// RGBA16F/RGBA32F texture, read with texelFetch, so at least width x height, no filtering or mip
    /// levels involved). Writes display RGB as OCIO produces it, unclamped (clamp before 8-bit encoding),
    /// and alpha unchanged. An empty sceneLinear or a non-positive size is a programmer error
    /// (std::logic_error).
    ///
    /// GL state: the viewport, draw and read framebuffer bindings, program, vertex array, active texture
    /// unit, clear colour, blend function and the depth-test, blend, cull-face and scissor-test enables
    /// are saved and restored (gl::StateGuard); the stencil-test and GL_FRAMEBUFFER_SRGB enables and the
    /// colour write mask of draw buffer 0 are disabled / opened for the draw and restored too. Left
    /// changed: the texture bindings of units 0 .. lutCount() (unit 0: sceneLinear, then the LUTs).
    /// The output goes to fragment output 0, i.e. whatever draw buffer 0 of displayTarget is.
    void run(const gl::Texture& sceneLinear, const gl::Framebuffer& displayTarget, int width, int height);

    /// The selection this pass was built for.
    const std::string& display() const;
    const std::string& view() const;
    /// Number of LUT textures the OCIO shader samples (0 for the embedded config's views).
    int lutCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

} // namespace pacifica::color
