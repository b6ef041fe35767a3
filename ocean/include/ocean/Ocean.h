// Ocean: the public entry point of the Pacifica ocean component.
//
// STEP BY STEP (a host engine embedding the ocean)
//   1. Own a GL 4.5 core context and an ecs::Registry (engine/Ecs.h).
//   2. auto e = registry.create();
//      registry.emplace<pacifica::ocean::OceanComponent>(e, pacifica::ocean::makeOcean({}));
//   3. pacifica::ocean::OceanRenderer renderer;                  // after the context is current
//   4. each frame: build a CameraFrame (engine/Space.h) from the camera's double-precision pose, then
//        renderer.render(registry, {camera, simTime, hostFbo, width, height});
//      It draws sky + sea into the host's framebuffer (scene-linear HDR, e.g. RGBA16F with a depth
//      attachment; reverse-Z: it clears depth to 0 and tests GL_GREATER) and restores the host's GL state
//      (gl::StateGuard), except texture bindings: units 0..(model units - 1) and 12..14 (lighting) are left
//      changed, image unit 0 when the octave combine pass runs, and units 15..18 under compute shading.
//   5. CPU queries (physics, buoyancy, cameras): component.surface->heightAt({x, y}, simTime) matches what
//      the GPU drew to float precision.
// Entities without an OceanComponent cost nothing; removing the component frees its GPU resources on the
// next render().
#pragma once

#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/gl/PassTimer.h"
#include "ocean/Effects.h"
#include "ocean/FftOcean.h"
#include "ocean/GerstnerWaves.h"
#include "ocean/HeightOctaves.h"
#include "ocean/Lighting.h"
#include "ocean/ProjectedGrid.h"
#include "ocean/RadialGrid.h"
#include "ocean/SurfaceModel.h"

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace pacifica::ocean {

enum class GridKind { Radial, Projected };

/// The secondary radial grids of the effects (Effects.h): unit discs with rings at (i / rings)^exponent,
/// scaled to each effect's radius every frame. They add geometry where an effect is large on screen; every
/// effect, with a grid or not, is in the effects field that all grids read (EffectFieldDesc).
struct EffectGridDesc {
    int explosionRings = 48, explosionSegments = 96;
    double explosionExponent = 1.5;
    int wakeRings = 96, wakeSegments = 192;
    double wakeExponent = 2.0;
    /// Grids drawn per kind at most: the effects in view largest on screen (radius / distance) first. The
    /// field alone draws every effect (the base grid reads it); a grid adds vertices and, on the base grid,
    /// a per-pixel test for its hole: on an H200 at 1080p 64 explosions cost +0.07 ms in the field alone
    /// and +1.9 ms with 16 grids (docs/EFFECTS_BENCH.md), so grids are for the few effects next to the eye.
    int maxExplosionGrids = 4, maxWakeGrids = 2;
    /// A grid is drawn only for an effect whose radius / distance from the camera is at least this.
    double minAngularSize = 0.2;
    /// ... and whose waves are at least this tall on screen: the effect's largest wave amplitude times the
    /// focal length in pixels over its distance from the camera (the ship's for a wake). The base grid reads
    /// the same field at every vertex, so without a grid the surface loses at most the detail between the
    /// base grid's vertices: less than the waves' height on screen. A wake's grid spans its whole trail and
    /// covers much of the view; on an H200 at 1080p it cost ~0.3 ms (docs/EFFECTS_BENCH.md) for waves of
    /// 0.5 m seen from 450 m, about a pixel tall. 0: the angular size alone decides.
    double minAmplitudePixels = 1.5;
};

struct OceanDesc {
    SurfaceKind model = SurfaceKind::Octaves; ///< which surface model displaces and lights the sea
    HeightOctavesDesc octaves;                ///< used when model == Octaves
    GerstnerDesc gerstner;                    ///< used when model == Gerstner
    FftDesc fft;                              ///< used when model == Fft
    GridKind gridKind =
        GridKind::Radial; ///< camera-centred radial grid (§18.2.3) or projected grid (Johanson)
    RadialGridDesc grid;
    ProjectedGridDesc projectedGrid;
    LightingDesc lighting;
    bool drawSky = true; ///< false when the host draws its own sky
    /// Drop the sea by curvatureDrop(d) with distance from the camera, so the horizon is where a spherical
    /// Earth puts it (OceanConstants.h). CPU height queries stay in the local (flat) frame.
    bool earthCurvature = true;
    /// Spread the radial grid over the camera's view sector (+ sectorGuardDeg each side) instead of 360°.
    bool viewSector = true;
    double sectorGuardDeg = 4.0;
    /// §18.2.5: skip the displacement of vertices outside the frustum widened by cullGuardNdc (fraction of
    /// the half screen) plus the surface's displacement bound.
    bool cullVertices = true;
    double cullGuardNdc = 0.1;
    /// Leave out the radial grid's inner rings when their whole disc is outside the frustum (from altitude
    /// the sea under the camera is off screen): hiddenDiscRadius() with the waves' vertical reach (2 Hs, or
    /// the octaves' exact bound when larger), less the horizontal displacement bound. Changes no pixel
    /// (test_compute_shading_gl); saves their vertices and triangles (docs/PERFORMANCE.md).
    bool skipHiddenRings = true;
    EffectGridDesc effectGrids;
    EffectFieldDesc effectField; ///< the effects' clipmap (Effects.h)
    /// Light the sea and sky in one compute pass instead of in the grids' fragment stage: the grids write
    /// only depth and a thin G-buffer (the quad's derivatives of the grid point), and the same lighting code
    /// runs once per pixel on every compute unit, the surface point rebuilt from the depth. On the H100/H200
    /// only 4 of 132 SMs run fragment work: 1080p high preset 2.09 -> 0.85 ms; llvmpipe 640x360 high
    /// -15%, low about equal (docs/PERFORMANCE.md). It writes the host's colour texture through an image
    /// binding, so it needs a host framebuffer whose draw buffer 0 is a 2D texture of RGBA16F, RGBA32F,
    /// RGBA8, RGB10_A2 or R11F_G11F_B10F and whose depth is a 2D 32-bit float texture (as engine's
    /// FrameTargets); with any other target the frame is shaded forward (OceanStats::computeShaded says
    /// which ran). Same depth, same image to within ~1e-5 of mean luminance (the fog noise's footprint
    /// lacks its vertical part; test_compute_shading_gl). On by default; the reference preset shades forward.
    bool computeShading = true;
    /// Compute shading by tiles (ComputeShading.h): a first pass sorts the screen's 8x8 tiles by what they
    /// hold (sea, open sky, sky with the sea beyond the grid, an edge) and each kind is lit by a program with
    /// only its own lighting code. For renderers that run both sides of every branch of a shader for all
    /// pixels of a SIMD vector (Mesa's llvmpipe): there one program lighting sea and sky paid for both at
    /// every pixel. A GPU already skips the side no thread of a warp takes, and pays for the extra passes.
    /// Auto: on where GL_RENDERER names a software rasteriser (llvmpipe, softpipe). Same pixels as untiled
    /// (test_compute_shading_gl); cost in docs/PERFORMANCE.md.
    enum class ShadeTiles { Auto, On, Off };
    ShadeTiles shadeTiles = ShadeTiles::Auto;
};

/// The component: a description plus the CPU surface model built from it (shared, immutable). CPU queries
/// (heightAt, normalAt, displacementAt) go through `surface` and match what the GPU draws.
struct OceanComponent {
    OceanDesc desc;
    std::shared_ptr<const SurfaceModel> surface;
};

/// Validates the description (std::invalid_argument naming the field) and builds the CPU surface.
OceanComponent makeOcean(const OceanDesc& desc);

struct OceanFrame {
    CameraFrame camera;
    double time = 0.0;              ///< simulation time, seconds (double)
    unsigned targetFramebuffer = 0; ///< host framebuffer (lent; 0 = default)
    int width = 0, height = 0;
};

/// The frame every host builds from its camera: `pose` seen through a perspective camera of vertical field
/// of view fovYRadians and the target's aspect (width / height) with its near plane at `nearPlane` metres
/// (makeCameraFrame, engine/Space.h), at simulation time `time`, into `framebuffer` (0 = the default).
OceanFrame makeOceanFrame(const Pose& pose, float fovYRadians, int width, int height, double time,
                          unsigned framebuffer, float nearPlane = 0.05f);

/// What the last render() did for one kind of effect.
struct EffectKindStats {
    int active = 0;         ///< effects of this kind in the frame's buffers (their field is evaluated)
    int drawn = 0;          ///< of those, grids in view and drawn (instances)
    int passes = 0;         ///< render passes for this kind (0 or 1)
    int draws = 0;          ///< draw calls
    int uploads = 0;        ///< buffer uploads (effect data, grid meshes)
    long long vertices = 0; ///< secondary-grid vertices processed
};

/// The effects field's share of a frame (EffectFieldDesc): its compute pass, the 8 x 8 tiles it evaluated
/// (those cleared included) and their texels, and its uploads (tile lists; the texture when first made).
struct EffectFieldStats {
    int passes = 0;
    int tiles = 0;
    long long texels = 0;
    int uploads = 0;
};

/// What the last render() did: render and compute passes, draw calls, buffer/texture uploads, vertices
/// (totals, effects included), and the effects' share per kind.
/// Where a frame's GPU time went, per pass (OceanRenderer::setPassTiming; docs/PERFORMANCE.md). Hardware:
/// GL_TIMESTAMP queries, the newest frame whose results have arrived (a few frames behind); llvmpipe: wall
/// clock after glFinish between passes, this frame. compute: the surface model's update (FFT, octave
/// combine, uploads); sky; sea: the base grid incl. the effects' per-frame uploads; effects: the secondary
/// grids. Absent passes measure ~0.
struct OceanPassTimes {
    bool measured = false; ///< false while timing is off or no frame's results have arrived yet
    /// shade: the compute-shading pass (OceanDesc::computeShading), which also draws the sky (skyMs ~0).
    double computeMs = 0.0, skyMs = 0.0, seaMs = 0.0, effectsMs = 0.0, shadeMs = 0.0;
    double totalMs() const { return computeMs + skyMs + seaMs + effectsMs + shadeMs; }
};

struct OceanStats {
    int passes = 0;
    int draws = 0;
    int uploads = 0;
    long long vertices = 0;
    int programsBuilt = 0; ///< shader programs compiled this frame (a variant is built on first use only)
    bool computeShaded = false; ///< the frame was lit by the compute pass (OceanDesc::computeShading)
    bool shadeTiled = false;    ///< ... sorted into tiles (OceanDesc::shadeTiles)
    EffectKindStats explosions, wakes;
    EffectFieldStats effectField;
    OceanPassTimes passTimes; ///< only with OceanRenderer::setPassTiming()
};

/// The effects field's layout for a frame (Effects.h): around the camera, its finest level no finer than a
/// pixel's footprint on the sea straight below (the pixel's angle times the camera's height).
EffectFieldLayout effectFieldLayout(const EffectFieldDesc& desc, const OceanFrame& frame);

class LightingGpu;    // implementation detail (ocean/src/gpu/LightingGpu.h)
class EffectsGpu;     // implementation detail (ocean/src/gpu/EffectsGpu.h)
class ComputeShading; // implementation detail (ocean/src/gpu/ComputeShading.h)

/// The ocean render system: draws every OceanComponent in a registry.
class OceanRenderer {
public:
    OceanRenderer();
    ~OceanRenderer();
    OceanRenderer(const OceanRenderer&) = delete;
    OceanRenderer& operator=(const OceanRenderer&) = delete;

    void render(ecs::Registry& registry, const OceanFrame& frame);

    /// The camera-relative positions the sea's vertex shader produces for every grid vertex of `ocean`
    /// (transform feedback, nothing drawn), in RadialGrid vertex order. For tests and accuracy reports that
    /// compare the GPU with the CPU's double-precision queries. Throws std::invalid_argument if the entity
    /// has no OceanComponent.
    struct DisplacedVertex {
        glm::vec3 position; ///< camera-relative displaced position (vRel)
        glm::vec2 grid;     ///< camera-relative undisplaced grid point (vGrid)
    };
    std::vector<DisplacedVertex> displacedVertices(ecs::Registry& registry, ecs::Entity ocean,
                                                   const OceanFrame& frame);
    const OceanStats& lastStats() const { return mStats; }
    /// The tiles of each kind the last tiled compute shading lit (OceanDesc::shadeTiles): edge between sea
    /// and sky, sea only, open sky only, sky with the sea beyond the grid. Reads the GPU's counts back, so it
    /// waits for the frame: for tests and reports. All 0 when no frame was shaded by tiles.
    std::array<int, 4> shadeTileCounts() const;

    /// Per-pass GPU timing into lastStats().passTimes (docs/PERFORMANCE.md). Off by default: then no query
    /// is issued and nothing waits. On llvmpipe use GpuTimer::Clock::WallAroundFinish (a glFinish between
    /// passes: the passes no longer overlap, so the sum can exceed an untimed frame); std::nullopt turns it
    /// off. passTimingClock(): the clock's name for reports, "" when off.
    void setPassTiming(std::optional<gl::GpuTimer::Clock> clock);
    const char* passTimingClock() const;

    /// The displaced vertices of every drawn secondary grid of one effect kind (transform feedback, nothing
    /// drawn), instance after instance, each instance in the grid's vertex order. Effects are gathered from
    /// the registry at frame.time as render() does. For tests comparing the GPU with oceanHeightAt().
    struct EffectVertex {
        glm::vec3 position; ///< camera-relative displaced position (vRel)
        glm::vec2 local;    ///< the displaced point relative to its grid's centre (vLocal)
        glm::dvec2 centre;  ///< the world centre of its grid
    };
    std::vector<EffectVertex> effectVertices(ecs::Registry& registry, ecs::Entity ocean,
                                             const OceanFrame& frame, EffectKind kind);

    struct Gpu;      ///< implementation detail: per-ocean GPU resources
    struct Programs; ///< implementation detail: compiled shader programs

private:
    struct FramePasses; ///< one ocean's frame as a fixed list of passes (OceanRenderer.cpp)
    void renderPasses(ecs::Registry& registry, const OceanFrame& frame);
    Gpu& prepare(ecs::Entity e, const OceanComponent& ocean);
    /// The secondary-grid program for this ocean's model and the effect kinds of the frame (built once):
    /// lit, transform feedback (tests), or into the G-buffer (compute shading).
    unsigned effectProgram(Gpu& gpu, bool feedback, bool geometry);
    unsigned effectFieldProgram();
    std::unique_ptr<Programs> mPrograms;
    std::unique_ptr<LightingGpu> mLighting;
    std::unique_ptr<EffectsGpu> mEffects;
    std::unique_ptr<ComputeShading> mCompute; // OceanDesc::computeShading's G-buffer
    std::unordered_map<ecs::Entity, std::unique_ptr<Gpu>> mGpu;
    OceanStats mStats;
    std::unique_ptr<gl::PassTimer> mPassTimer;
    OceanPassTimes mPassTimes; // the newest measured frame's
};

} // namespace pacifica::ocean
