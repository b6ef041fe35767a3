// EffectsGpu (internal): the GPU side of the effects (ocean/include/ocean/Effects.h) for one frame. It packs
// every active explosion and trail into shader-storage buffers (effects.glsl layout), bins them into the
// 8 x 8 tiles of the effects field they touch, evaluates those tiles in one compute pass
// (effects_field.comp), and picks the effects that also get a secondary radial grid (in view and large on
// screen). Every grid then reads the field (effects_sample.glsl). Nothing is created, uploaded or dispatched
// for a scene without effects, and a kind the scene does not have compiles out.
#pragma once

#include "engine/Space.h"
#include "engine/gl/GlObjects.h"
#include "gpu/GridMesh.h"
#include "ocean/EffectTypes.h"
#include "ocean/Ocean.h"
#include "ocean/RadialGrid.h"

#include <string>
#include <vector>

namespace pacifica::ocean {

/// Where a frame's readers of the field can sample it (EffectFieldDesc::viewCull): every point within `guard`
/// metres of the horizontal sector (camera-relative azimuths), plus the discs of the secondary grids drawn.
/// The default, the whole circle, evaluates every tile an effect touches.
struct FieldReads {
    ViewSector sector;
    double guard = 0.0;
};

class EffectsGpu {
public:
    /// Collects `effects` at frame.time, uploads them and their tile lists, and chooses the
    /// grids to draw (bounding sphere of each disc, raised by `heightBound`, against the camera; the
    /// largest on screen first, EffectGridDesc's limits). Only the tiles `reads` can reach are evaluated.
    void prepare(const EffectsView& effects, const OceanFrame& frame, double heightBound,
                 const EffectGridDesc& grids, const EffectFieldDesc& field, const FieldReads& reads = {});
    bool any() const { return mExplosionCount + mWakeCount > 0; }
    bool has(EffectKind kind) const { return count(kind) > 0; }
    int count(EffectKind kind) const { return kind == EffectKind::Explosion ? mExplosionCount : mWakeCount; }
    int drawn(EffectKind kind) const {
        return kind == EffectKind::Explosion ? mExplosionsDrawn : mWakesDrawn;
    }
    /// "#define EFFECTS_EXPLOSIONS" / "#define EFFECTS_WAKES" for the kinds present (the field pass's
    /// variant).
    std::string defines() const;
    /// Buffer uploads of one kind made by the last prepare() (its data; its grid mesh when first built).
    int uploads(EffectKind kind) const {
        return kind == EffectKind::Explosion ? mExplosionUploads : mWakeUploads;
    }
    const EffectFieldStats& fieldStats() const { return mFieldStats; }

    /// The field pass with `program` (effects_field.comp with defines()): evaluates this frame's tiles and
    /// makes the field visible to the grids. Does nothing when no tile is to be written.
    void computeField(unsigned program);
    /// Binds the field and the drawn grids' list for a program that includes effects_sample.glsl.
    void bindField(unsigned program) const;
    /// Draws the chosen grids of one kind with `program` (bound, uniforms set). Returns vertices processed.
    long long draw(unsigned program, EffectKind kind, unsigned mode = 0x0004 /* GL_TRIANGLES */);
    /// Surface vertices per instance of a kind (the skirt left out).
    long long gridVertices(EffectKind kind) const;
    /// The layout of the last prepare()'s field (tests compare the GPU with sampleEffectField()).
    const EffectFieldLayout& layout() const { return mLayout; }
    /// World centres of the grids drawn, explosions' then wakes' (instance order).
    const std::vector<glm::dvec2>& gridCentres() const { return mGridCentres; }

private:
    struct Mesh : GridMesh {
        int skirtCount = 0; ///< the last vertices: the rim's skirt (not part of the surface)
        int rings = 0, segments = 0;
    };
    void ensureMesh(Mesh& mesh, int rings, int segments, double exponent, int& uploads);
    void upload(gl::Buffer& buffer, size_t& capacity, const void* data, size_t bytes, int& uploads);
    void ensureField(const EffectFieldDesc& field);
    struct Footprint; // where an effect can be non-zero, camera-relative (EffectsGpu.cpp)
    /// `grids`: the drawn secondary grids' discs (camera-relative centre, radius), which read the field too.
    void binTiles(const std::vector<Footprint>& footprints, int explosions, const FieldReads& reads,
                  const std::vector<glm::vec4>& grids);

    Mesh mExplosionMesh, mWakeMesh;
    gl::Buffer mExplosionBuffer, mWakeBuffer, mWakePointBuffer, mTileBuffer, mListBuffer, mGridBuffer;
    size_t mExplosionCapacity = 0, mWakeCapacity = 0, mWakePointCapacity = 0, mTileCapacity = 0,
           mListCapacity = 0, mGridCapacity = 0;
    int mExplosionCount = 0, mWakeCount = 0, mExplosionsDrawn = 0, mWakesDrawn = 0;
    int mExplosionUploads = 0, mWakeUploads = 0;

    // The field: a texture array (a level per layer), the layout of this frame, the tiles written.
    EffectFieldLayout mLayout{EffectFieldDesc{}, glm::dvec2(0.0)};
    gl::Texture mField;
    EffectFieldDesc mFieldDesc;
    std::vector<uint8_t> mWritten; ///< per level and tile: written by the last field pass (to be cleared)
    int mTileCount = 0;            ///< tiles to write this frame (the records uploaded)
    EffectFieldStats mFieldStats;
    glm::dvec2 mCamera{0.0}; ///< the camera of the last prepare() (world)
    std::vector<glm::dvec2> mGridCentres;
    /// Per level, camera-relative (min x, min y, max x, max y) of the texel centres of its tiles with effects
    /// this frame (empty: min > max): effects_sample.glsl reads 0 outside without a fetch.
    std::vector<glm::vec4> mLevelBoxes;
    static constexpr int FIELD_TEXTURE_UNIT = 18; ///< the field for the grids and the shading (after theirs)
};

} // namespace pacifica::ocean
