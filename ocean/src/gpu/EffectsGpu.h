// EffectsGpu (internal): the GPU side of the effects (ocean/include/ocean/Effects.h) for one frame — packs
// every active explosion and trail into shader-storage buffers (effects.glsl layout), decides which effect
// grids are in view, and draws them as instanced secondary radial grids. Nothing is created, uploaded or
// drawn for a kind the scene does not have.
#pragma once

#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/gl/GlObjects.h"
#include "gpu/GridMesh.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"

#include <string>
#include <vector>

namespace pacifica::ocean {

class EffectsGpu {
public:
    /// Collects the effects of `registry` at frame.time, uploads them, and culls their grids against the
    /// camera (bounding sphere of each disc, raised by `heightBound`). Returns what this frame has.
    void prepare(ecs::Registry& registry, const OceanFrame& frame, double heightBound,
                 const EffectGridDesc& grids);
    bool any() const { return mExplosionCount + mWakeCount > 0; }
    bool has(EffectKind kind) const { return count(kind) > 0; }
    int count(EffectKind kind) const { return kind == EffectKind::Explosion ? mExplosionCount : mWakeCount; }
    int drawn(EffectKind kind) const {
        return kind == EffectKind::Explosion ? mExplosionsDrawn : mWakesDrawn;
    }
    /// "#define EFFECTS_EXPLOSIONS" / "#define EFFECTS_WAKES" for the kinds present (the shader variant).
    std::string defines() const;
    /// Buffer uploads of one kind made by the last prepare() (its data; its grid mesh when first built; the
    /// neighbour lists count with the explosions, or with the wakes when there are no explosions).
    int uploads(EffectKind kind) const {
        return kind == EffectKind::Explosion ? mExplosionUploads : mWakeUploads;
    }

    /// Binds the buffers and sets uExplosionCount / uWakeCount on `program`.
    void bind(unsigned program) const;
    /// Draws the visible grids of one kind with `program` (bound, uniforms set). Returns vertices processed.
    long long draw(unsigned program, EffectKind kind, unsigned mode = 0x0004 /* GL_TRIANGLES */);
    /// Surface vertices per instance of a kind (the skirt left out).
    long long gridVertices(EffectKind kind) const;

private:
    struct Mesh : GridMesh {
        int skirtCount = 0; ///< the last vertices: the rim's skirt (not part of the surface)
        int rings = 0, segments = 0;
    };
    void ensureMesh(Mesh& mesh, int rings, int segments, double exponent, int& uploads);
    void upload(gl::Buffer& buffer, size_t& capacity, const void* data, size_t bytes, int& uploads);

    Mesh mExplosionMesh, mWakeMesh;
    gl::Buffer mExplosionBuffer, mWakeBuffer, mWakePointBuffer, mNeighbourBuffer;
    size_t mExplosionCapacity = 0, mWakeCapacity = 0, mWakePointCapacity = 0, mNeighbourCapacity = 0;
    int mExplosionCount = 0, mWakeCount = 0, mExplosionsDrawn = 0, mWakesDrawn = 0;
    int mExplosionUploads = 0, mWakeUploads = 0;
};

} // namespace pacifica::ocean
