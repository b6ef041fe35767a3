// Ocean: the public entry point of the Pacifica ocean component. Exception-free and ECS-free: a host built
// with -fno-exceptions -fno-rtti, on any entity system, embeds it through this header alone.
//
// STEP BY STEP (a host engine embedding the ocean)
//   1. Own a GL 4.5 core context and make it current.
//   2. pacifica::ocean::OceanComponent ocean;
//      if (Status s = makeOcean({}, ocean); !s) { log(s.message); }   // names the bad field
//   3. pacifica::ocean::OceanRenderer renderer;                     // after the context is current
//   4. each frame: build an OceanFrame from the camera's double-precision pose (makeOceanFrame), list what
//      to draw (OceanScene: the oceans under ids the host chooses, the explosions and ship wakes as plain
//      spans) and call
//        Status s = renderer.render(scene, frame);
//      It draws sky + sea into the host's framebuffer (scene-linear HDR, e.g. RGBA16F with a depth
//      attachment; reverse-Z: it clears depth to 0 and tests GL_GREATER) and restores the host's GL state
//      (gl::StateGuard), except texture bindings: units 0..(model units - 1) and 12..14 (lighting) are left
//      changed, image unit 0 when the octave combine pass runs, and units 15..18 under compute shading.
//   5. CPU queries (physics, buoyancy, cameras): SeaQuery (ocean/SeaQuery.h: heights, normals, velocities
//      of many points a call, threaded, allocation-free) or heightsAt(ocean, effects, points, time,
//      heights) for a few; the heights the GPU drew exactly, a frame later: queueHeights/takeHeights below.
//
// ERRORS are values (Status) across this boundary: every function here is noexcept; bad input (a description
// out of range, a frame with no pixels, a non-finite time or camera) and GPU failures (a shader the driver
// rejects) come back as a Status naming the field or the stage, the host's GL state restored, nothing
// aborted. OceanHost.h adds, for hosts built with exceptions and Pacifica's own ECS (ecs::Registry), a
// registry adapter and throwing wrappers; OceanDebug.h the tests' hooks.
//
// An ocean id the scene no longer lists has its GPU resources freed by the next render().
#pragma once

#include "engine/Space.h"
#include "ocean/EffectTypes.h"
#include "ocean/FftOcean.h"
#include "ocean/GerstnerWaves.h"
#include "ocean/HeightOctaves.h"
#include "ocean/Lighting.h"
#include "ocean/ProjectedGrid.h"
#include "ocean/RadialGrid.h"
#include "ocean/SurfaceModel.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

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

/// What went wrong, by kind (Status::code); Status::message says where and why.
enum class ErrorCode {
    None,            ///< success
    InvalidArgument, ///< a description, frame or query out of range, NaN or missing (the message names it)
    GpuFailure,      ///< the driver refused something (a shader did not compile or link, a resource)
    OutOfMemory,     ///< an allocation failed
    Internal,        ///< anything else (a bug: please report the message)
};

/// The result of a call across the component boundary: success, or an error code and a message naming the
/// field, file or stage. Converts to true on success.
struct Status {
    ErrorCode code = ErrorCode::None;
    std::string message;
    bool ok() const noexcept { return code == ErrorCode::None; }
    explicit operator bool() const noexcept { return ok(); }
};

/// Validates the description and builds the CPU surface into `out` (left unchanged on error). The message
/// names the field, e.g. "OceanDesc.effectGrids.wakeRings must be in [1, 1024], got 0".
Status makeOcean(const OceanDesc& desc, OceanComponent& out) noexcept;

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
                          unsigned framebuffer, float nearPlane = 0.05f) noexcept;

/// One ocean of a scene: a host-chosen id, stable while the ocean lives (its GPU resources are kept under
/// it), and its component (the host's, read during render()).
struct OceanInstance {
    std::uint64_t id = 0;
    const OceanComponent* ocean = nullptr;
};

/// What render() draws: the oceans (usually one) and every effect on them, as plain spans the host owns
/// for the duration of the call. An absent effect costs nothing: no pass, no draw, no upload.
struct OceanScene {
    std::span<const OceanInstance> oceans;
    EffectsView effects;
    /// Spot lights on the sea this frame (Lighting.h); the first MAX_SPOT_LIGHTS light it, the rest are left
    /// out and counted (OceanStats::spotsDropped). None: no shader variant, uniform or cost.
    std::span<const SpotLight> spots;
    /// Spot lights the host left out of `spots` as invalid (the registry adapter's count, render() in
    /// OceanHost.h), reported in OceanStats::spotsRejected.
    int spotsRejected = 0;
};

/// Heights of the sea at `points` (world metres) at time t: the ocean's surface (SurfaceModel::heightAt)
/// plus the effects' analytic field (effectsAt). `heights` must have points.size() elements. A non-finite
/// point or time, or a size mismatch, is an InvalidArgument (heights unchanged).
Status heightsAt(const OceanComponent& ocean, const EffectsView& effects, std::span<const glm::dvec2> points,
                 double t, std::span<double> heights) noexcept;

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
    int cleared = 0; ///< of `tiles`, those only cleared: written by the frame before, no effect in reach now
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
    int spots = 0;            ///< spot lights that lit the sea (OceanScene::spots, at most MAX_SPOT_LIGHTS)
    int spotsDropped = 0;     ///< spot lights beyond MAX_SPOT_LIGHTS, left out
    int spotsRejected = 0;    ///< invalid spot lights the host left out (OceanScene::spotsRejected)
    OceanPassTimes passTimes; ///< only with OceanRenderer::setPassTiming()
};

/// The effects field's layout for a frame (EffectTypes.h): around the camera, its finest level no finer than
/// a pixel's footprint on the sea straight below (the pixel's angle times the camera's height).
EffectFieldLayout effectFieldLayout(const EffectFieldDesc& desc, const OceanFrame& frame);

/// The clock of per-pass timing (OceanRenderer::setPassTiming): GL_TIMESTAMP queries on hardware, or the
/// wall clock after a glFinish between passes (llvmpipe, whose timer queries are wrong).
enum class PassClock { TimerQuery, WallAroundFinish };

/// Batches of asynchronous GPU height queries an OceanRenderer holds at once (OceanRenderer::queueHeights).
inline constexpr size_t GPU_QUERY_RING = 4;

/// Points through the asynchronous GPU height queries since the renderer was made.
struct GpuQueryCounters {
    std::uint64_t queued = 0;    ///< points queued
    std::uint64_t evaluated = 0; ///< points a render() evaluated
    std::uint64_t answered = 0;  ///< points takeHeights() returned
    std::uint64_t dropped = 0;   ///< points of batches a full ring overwrote before they were taken
    std::uint64_t notReady = 0;  ///< takeHeights() calls that found the answers not ready yet
};

/// The ocean render system: draws the oceans of a scene into a framebuffer the host lends.
class OceanRenderer {
public:
    OceanRenderer() noexcept; ///< GL resources are made by the first render() (a current context needed then)
    ~OceanRenderer();
    OceanRenderer(const OceanRenderer&) = delete;
    OceanRenderer& operator=(const OceanRenderer&) = delete;

    /// Draws every ocean of the scene with its effects (module comment). On error the frame may be partly
    /// drawn; the host's GL state is restored either way.
    Status render(const OceanScene& scene, const OceanFrame& frame) noexcept;
    const OceanStats& lastStats() const noexcept;

    /// Per-pass GPU timing into lastStats().passTimes (docs/PERFORMANCE.md). Off by default: then no query
    /// is issued and nothing waits. On llvmpipe use PassClock::WallAroundFinish (a glFinish between
    /// passes: the passes no longer overlap, so the sum can exceed an untimed frame); std::nullopt turns it
    /// off. passTimingClock(): the clock's name for reports, "" when off.
    void setPassTiming(std::optional<PassClock> clock) noexcept;
    const char* passTimingClock() const noexcept;

    /// Asynchronous GPU height queries: the heights the GPU draws (the surface model's GLSL at the frame's
    /// time and camera, plus the effects field), answered from a readback without a stall.
    ///   std::uint64_t ticket; renderer.queueHeights(oceanId, points, ticket);  // copies the points
    ///   renderer.render(scene, frame);       // the next frame listing oceanId evaluates them: one pass
    ///   bool ready; renderer.takeHeights(ticket, heights, ready);   // a frame later: ready once the GPU is
    ///                                                               // done (else call again next frame)
    /// Latency: one frame when the host takes them before its next render(), as the GPU finishes the frame;
    /// never a wait. A ring of GPU_QUERY_RING batches: queueing into a full ring drops the oldest batch not
    /// taken (counted). Points far from the camera lose float precision like the drawn sea (1 mm at 10 km);
    /// the heights are in the local flat frame, as the CPU queries (no Earth curvature). takeHeights reads
    /// back: the context must be current. A point that is not finite is refused (InvalidArgument naming it).
    Status queueHeights(std::uint64_t oceanId, std::span<const glm::dvec2> points,
                        std::uint64_t& ticket) noexcept;
    Status takeHeights(std::uint64_t ticket, std::span<double> heights, bool& ready) noexcept;
    const GpuQueryCounters& gpuQueryCounters() const noexcept;

    struct Impl; ///< implementation detail (OceanRenderer.cpp; OceanDebug.h's hooks reach it)
    Impl& impl() noexcept { return *mImpl; }

private:
    std::unique_ptr<Impl> mImpl;
};

} // namespace pacifica::ocean
