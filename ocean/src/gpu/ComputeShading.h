// ComputeShading (internal): the resources of OceanDesc::computeShading. The sea's grids are drawn with the
// host's own depth attachment and a thin G-buffer (ocean_gbuffer.frag): the quad's derivatives of the grid
// point (RGBA16F) and, for models that move the surface sideways, the grid point's offset (RG16F). Effects
// need no layer: the shading reads the effects field at the surface point. One compute pass
// (ocean_shade.comp) then rebuilds each pixel's surface point from the depth, lights it and writes the host's
// colour texture through an image binding. The graphics pipe -- on the H100 only 4 of 132 SMs run it --
// writes 8 bytes a pixel besides the depth, and all the lighting runs on the compute units. Units: the host's
// depth on texture unit 15 (with a sampler object: no depth comparison), the derivatives on 16, the offset on
// 17, the host's colour on image unit 1.
//
// It needs a host framebuffer whose draw buffer 0 is a single-sample 2D texture of a format images can
// store (RGBA16F, RGBA32F, RGBA8, RGB10_A2, R11F_G11F_B10F) and whose depth attachment is a 2D texture of
// 32-bit float depth (GL_DEPTH_COMPONENT32F or GL_DEPTH32F_STENCIL8: the surface point is rebuilt from it,
// to 6e-8 of its distance); with anything else (the default framebuffer, renderbuffers, 24-bit depth,
// sRGB, multisampling) attach() says no and the renderer shades forward, as without the option.
//
// Tiles (OceanDesc::shadeTiles): a first pass (ocean_shade_tiles.comp) sorts the viewport's 8x8 tiles by
// what they hold -- sea only, open sky only, sky and the sea beyond the grid, or an edge between sea and
// sky -- into lists in a storage buffer (binding TILE_BINDING), and each kind is lit by a program compiled
// for it alone, one glDispatchComputeIndirect per kind. For renderers that run both sides of every branch
// (llvmpipe); a GPU skips the side no thread of a warp takes anyway.
#pragma once

#include "engine/gl/GlObjects.h"
#include "gpu/GpuInterface.h"

#include <array>
#include <string>

namespace pacifica::ocean {

class ComputeShading {
public:
    static constexpr int DEPTH_UNIT = 15, GEOMETRY_UNIT = 16, OFFSET_UNIT = 17,
                         OUTPUT_IMAGE_UNIT = SHADE_OUTPUT_IMAGE_UNIT, TILE_BINDING = SHADE_TILE_BINDING,
                         TILE_SIZE = 8;
    /// Kinds of tile (shade_pixels.glsl): an edge between sea and sky (the whole program), sea only, open sky
    /// only, sky with the sea beyond the grid.
    enum TileKind { TILE_MIXED, TILE_SEA, TILE_SKY, TILE_BEYOND, TILE_KINDS };
    /// The #defines the shading programs take these from (SHADE_TILE_SIZE, the kinds; the binding is
    /// SHADE_TILE_BINDING of shaderConstantDefines()).
    static std::string tileDefines();
    static bool skyOnly(int kind) { return kind == TILE_SKY || kind == TILE_BEYOND; }

    ComputeShading() = default;
    ~ComputeShading();
    ComputeShading(const ComputeShading&) = delete;
    ComputeShading& operator=(const ComputeShading&) = delete;

    /// Checks the host framebuffer `hostFbo` (bound for drawing) and (re)builds the G-buffer for a
    /// width x height viewport: with the horizontal displacement when `displaced` (Gerstner, FFT). False:
    /// shade forward this frame.
    bool attach(unsigned hostFbo, int width, int height, bool displaced);
    /// GLSL image format of the host's colour texture ("rgba16f"), after a successful attach().
    const char* outputFormat() const { return mFormatName; }
    /// Binds the G-buffer for drawing (the geometry is read only where the depth says a grid was drawn).
    void beginGeometry();
    /// Lights every pixel with `program` (ocean_shade.comp, uniforms other than the G-buffer's set by the
    /// caller) into the host's colour texture; a barrier makes the result visible to what the host does next.
    void shade(unsigned program, bool drawSky);
    /// The same with tiles: `sortProgram` (ocean_shade_tiles.comp) fills the lists, then kindPrograms[k]
    /// (ocean_shade.comp with SHADE_TILE_KIND k, uniforms set by the caller) lights the tiles of kind k.
    void shadeTiles(unsigned sortProgram, const unsigned (&kindPrograms)[TILE_KINDS], bool drawSky);
    /// The tiles of each kind the last shadeTiles() lit (mixed, sea, sky, beyond: shade_pixels.glsl); reads
    /// the GPU's counts back, so it waits for the frame. For tests and reports.
    std::array<int, TILE_KINDS> tileCounts() const;

private:
    void bindTextures();
    void setInputUniforms(unsigned program, bool drawSky);
    void barrierAfterShading();
    struct Key {
        unsigned color = 0, depth = 0;
        int colorLevel = 0, depthLevel = 0, format = 0, width = 0, height = 0;
        bool displaced = false;
    };
    Key mKey;
    const char* mFormatName = "";
    gl::Texture mGeometry, mOffset;
    gl::Buffer mTiles;     // per kind (tiles, 1, 1) for glDispatchComputeIndirect, then the kinds' tile lists
    gl::Buffer mTileReset; // the header a frame starts from
    int mTileCapacity = 0;
    gl::Framebuffer mFbo;
    unsigned mDepthSampler = 0;
};

} // namespace pacifica::ocean
