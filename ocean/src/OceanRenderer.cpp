// OceanRenderer: the ocean render system — per OceanComponent GPU resources (radial grid buffers and the
// surface model's GPU twin), shader programs compiled per surface model (a model the scene doesn't use
// costs no shader work), and the frame's passes: the sea, its effects, then the sky (optional) where no sea
// was drawn, into a framebuffer the host lends.
#include "ocean/Ocean.h"
#include "ocean/OceanDebug.h"
#include "ocean/OceanHost.h"

#include "Guarded.h"
#include "engine/Log.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"
#include "engine/gl/PassTimer.h"
#include "engine/gl/Shader.h"
#include "gpu/ComputeShading.h"
#include "gpu/EffectsGpu.h"
#include "gpu/GpuQueries.h"
#include "gpu/GridMesh.h"
#include "gpu/LightingGpu.h"
#include "gpu/SurfaceGpuFactory.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"
#include "ocean/SurfaceModels.h"

#include <epoxy/gl.h>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <new>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_map>
#include <vector>

namespace pacifica::ocean {

OceanFrame makeOceanFrame(const Pose& pose, float fovYRadians, int width, int height, double time,
                          unsigned framebuffer, float nearPlane) noexcept {
    OceanFrame f;
    f.camera =
        makeCameraFrame(pose, fovYRadians, static_cast<float>(width) / static_cast<float>(height), nearPlane);
    f.time = time;
    f.targetFramebuffer = framebuffer;
    f.width = width;
    f.height = height;
    return f;
}

EffectFieldLayout effectFieldLayout(const EffectFieldDesc& desc, const OceanFrame& frame) {
    const double focal = std::abs(static_cast<double>(frame.camera.proj[1][1])); // 1 / tan(fovY / 2)
    const double pixelAngle = focal > 0.0 && frame.height > 0 ? 2.0 / (focal * frame.height) : 0.0;
    return EffectFieldLayout(desc, glm::dvec2(frame.camera.origin),
                             pixelAngle * std::max(std::abs(frame.camera.origin.z), 1.0));
}

namespace {

/// What render() needs of its inputs: pixels to draw, a finite time and camera, and no null in the spans.
void validateScene(const OceanScene& scene, const OceanFrame& frame) {
    if (frame.width <= 0 || frame.height <= 0)
        throw std::invalid_argument("OceanFrame.width and .height must be > 0, got " +
                                    std::to_string(frame.width) + "x" + std::to_string(frame.height));
    requireFinite(std::isfinite(frame.time), "OceanFrame.time");
    const glm::dvec3 o = frame.camera.origin;
    requireFinite(std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z), "OceanFrame.camera.origin");
    for (size_t i = 0; i < scene.oceans.size(); ++i)
        if (!scene.oceans[i].ocean)
            throw std::invalid_argument("OceanScene.oceans[" + std::to_string(i) + "].ocean is null");
    for (size_t i = 0; i < scene.effects.explosions.size(); ++i) {
        const Explosion& e = scene.effects.explosions[i];
        requireFinite(std::isfinite(e.center.x) && std::isfinite(e.center.y) && std::isfinite(e.startTime),
                      "OceanScene.effects.explosions[" + std::to_string(i) + "] centre and startTime");
    }
    for (size_t i = 0; i < scene.effects.wakes.size(); ++i) {
        const WakeRef& w = scene.effects.wakes[i];
        if (!w.ship || !w.trail)
            throw std::invalid_argument("OceanScene.effects.wakes[" + std::to_string(i) +
                                        "]: ship and trail must not be null");
        requireFinite(std::isfinite(w.ship->position.x) && std::isfinite(w.ship->position.y),
                      "OceanScene.effects.wakes[" + std::to_string(i) + "].ship->position");
    }
    for (size_t i = 0; i < scene.spots.size(); ++i) {
        try {
            validateSpotLight(scene.spots[i], i);
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(std::string("OceanScene.") + e.what());
        }
    }
}

/// The spot lights' uniforms (spot.glsl, SPOT_LIGHTS) for a program lighting the sea: positions relative to
/// the camera (in double, then float), unit axes, half-angles, colour times intensity, ranges; the daylight
/// the water body is relative to; the beams' quadrature and phase.
void setSpotUniforms(GLuint prog, std::span<const SpotLight> spots, const OceanFrame& frame,
                     const LightingDesc& lighting) {
    glm::vec3 position[MAX_SPOT_LIGHTS];
    glm::vec4 axis[MAX_SPOT_LIGHTS], light[MAX_SPOT_LIGHTS];
    const int n = static_cast<int>(std::min<size_t>(spots.size(), MAX_SPOT_LIGHTS));
    for (int i = 0; i < n; ++i) {
        const SpotLight& s = spots[static_cast<size_t>(i)];
        position[i] = glm::vec3(s.position - frame.camera.origin);
        axis[i] = glm::vec4(glm::vec3(glm::normalize(s.direction)),
                            static_cast<float>(s.frustumDeg * std::numbers::pi / 180.0));
        light[i] = glm::vec4(s.color * s.intensity, static_cast<float>(s.range));
    }
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uSpotCount"), n);
    glProgramUniform3fv(prog, glGetUniformLocation(prog, "uSpotPosition"), n, glm::value_ptr(position[0]));
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "uSpotAxis"), n, glm::value_ptr(axis[0]));
    glProgramUniform4fv(prog, glGetUniformLocation(prog, "uSpotLight"), n, glm::value_ptr(light[0]));
    const LightingDesc defaults;
    const float sunZ = static_cast<float>(glm::normalize(defaults.sunDirection).z);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "uDaylightSun"),
                       SUN_DIFFUSE_SCALE * defaults.sunIntensity * sunZ, sunZ);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uSpotScatterSamples"), lighting.spotScatterSamples);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uSpotFogPhaseG"),
                       static_cast<float>(SPOT_FOG_PHASE_G));
}

} // namespace

namespace detail {

struct Programs {
    std::map<std::string, gl::Program> sea;         // per surface model's GLSL set
    std::map<std::string, gl::Program> seaFeedback; // vertex stage only, captures vRel
    std::map<std::string, gl::Program> effectField; // per kinds present: the effects field's compute pass
    std::map<std::string, gl::Program> effects;     // per model: secondary grids
    std::map<std::string, gl::Program> effectsFeedback;
    std::map<std::string, gl::Program> seaGeometry; // compute shading: the grids into the G-buffer
    std::map<std::string, gl::Program> effectsGeometry;
    std::map<std::string, gl::Program> shade; // compute shading: per model, effects, output format, tile kind
    std::map<std::string, gl::Program> seaQuery; // the GPU height queries: per model, with effects or not
    gl::Program shadeTileSort;                   // compute shading's tile sorting (ocean_shade_tiles.comp)
    int softwareRenderer = -1; // GL_RENDERER names a software rasteriser (1), not (0), unknown
    gl::Program sky;           // built on first use
    gl::Program skySpots;      // ... with the spots' beams (SPOT_LIGHTS)
    gl::VertexArray emptyVao;  // the sky's fullscreen triangle needs a bound VAO in core profile
    gl::Texture feedbackColor; // a 1x1 target: drawing needs a complete framebuffer even with discard
    gl::Framebuffer feedbackFbo;
};

struct OceanGpu {
    std::shared_ptr<const SurfaceModel> surface; // the model these resources were built from
    std::unique_ptr<SurfaceGpu> model;
    std::string programKey;
    GridKind gridKind = GridKind::Radial;
    RadialGridDesc gridDesc;
    std::unique_ptr<ProjectedGrid> projected; // when gridKind == Projected
    std::unique_ptr<RadialGrid> radial;       // when gridKind == Radial
    GridMesh mesh; // the grid's vertices (RadialGrid or ProjectedGrid), uploaded when the grid changes
    // Ring thinning (RadialGridDesc::minRingPixels): the rings drawn and their index buffer, rebuilt when
    // the (quantised) view changes the selection.
    std::vector<int> thinRings;
    gl::Buffer thinIndices;
    int thinIndexCount = 0;
    bool thinBound = false; // the VAO's element buffer is thinIndices (else mesh.indices)
};

} // namespace detail

using detail::OceanGpu;
using detail::Programs;

/// Everything the renderer keeps between frames (Ocean.h shows only the pointer).
struct OceanRenderer::Impl {
    std::unique_ptr<Programs> mPrograms = std::make_unique<Programs>();
    std::unique_ptr<LightingGpu> mLighting = std::make_unique<LightingGpu>();
    std::unique_ptr<EffectsGpu> mEffects = std::make_unique<EffectsGpu>();
    std::unique_ptr<ComputeShading> mCompute =
        std::make_unique<ComputeShading>();                            // computeShading's G-buffer
    std::unordered_map<std::uint64_t, std::unique_ptr<OceanGpu>> mGpu; // by OceanInstance::id
    OceanStats mStats;
    GpuQueries mQueries; // the asynchronous GPU height queries (queueHeights)
    std::unique_ptr<gl::PassTimer> mPassTimer;
    OceanPassTimes mPassTimes; // the newest measured frame's

    void render(const OceanScene& scene, const OceanFrame& frame);
    void renderPasses(const OceanScene& scene, const OceanFrame& frame);
    OceanGpu& prepare(std::uint64_t id, const OceanComponent& ocean);
    /// The secondary-grid program for this ocean's model and the effect kinds of the frame (built once):
    /// lit, transform feedback (tests), or into the G-buffer (compute shading).
    /// `lit`: the forward variant's extra defines (spotDefines()).
    unsigned effectProgram(OceanGpu& gpu, bool feedback, bool geometry, const std::string& lit = {});
    unsigned effectFieldProgram();
};

namespace {

/// Texture units: the surface model binds from 0, the lighting (environment map, foam) from here.
constexpr int LIGHTING_FIRST_UNIT = 12;

/// The 1x1 target the transform-feedback captures draw into (a draw needs a complete framebuffer).
void ensureFeedbackTarget(Programs& programs) {
    if (programs.feedbackFbo)
        return;
    programs.feedbackColor = gl::Texture::create2D(GL_RGBA8, 1, 1);
    programs.feedbackFbo = gl::Framebuffer::create();
    programs.feedbackFbo.attachColor(0, programs.feedbackColor);
}

/// Steps of sea_query.comp's solve (Broyden's method) for the grid point under a query point: at most 16,
/// ending once a step moves the point less than SEA_QUERY_TOLERANCE (0.1 mm; the height then errs by the
/// slope times that).
constexpr int SEA_QUERY_ITERATIONS = 16;
constexpr double SEA_QUERY_TOLERANCE = 1e-4;

/// The shader sources: constants, then the variant's #defines (feature set), then the files.
std::vector<gl::ShaderSource> sources(const std::vector<std::string>& names,
                                      const std::string& defines = {}) {
    std::vector<gl::ShaderSource> out;
    out.push_back({"<ocean constants>", shaderConstantDefines()});
    if (!defines.empty())
        out.push_back({"<variant defines>", effectConstantDefines() + defines});
    for (const std::string& n : names)
        out.push_back({n, std::string(shaderText(n))});
    return out;
}

std::vector<std::string> concat(std::vector<std::string> a, std::initializer_list<const char*> b) {
    for (const char* s : b)
        a.emplace_back(s);
    return a;
}

std::string joined(const std::vector<std::string>& files) {
    std::string key;
    for (const std::string& f : files)
        key += f + ";";
    return key;
}

bool sameGrid(const RadialGridDesc& a, const RadialGridDesc& b) {
    return a.rings == b.rings && a.segments == b.segments && a.rMin == b.rMin && a.rMax == b.rMax &&
           a.skirtRadius == b.skirtRadius;
}

bool sameProjected(const ProjectedGridDesc& a, const ProjectedGridDesc& b) {
    return a.resolutionX == b.resolutionX && a.resolutionY == b.resolutionY &&
           a.maxDisplacement == b.maxDisplacement && a.guardBand == b.guardBand;
}

void buildGrid(OceanGpu& gpu, const OceanDesc& desc) {
    gpu.gridKind = desc.gridKind;
    gpu.gridDesc = desc.grid;
    // One kind at a time: a radial grid left beside a projected one would give the projected mesh the radial
    // grid's index ranges (seaIndices) and the radial grid's field reads (fieldReads).
    gpu.thinRings.clear();
    gpu.thinIndices = {};
    gpu.thinIndexCount = 0;
    gpu.thinBound = false;
    if (desc.gridKind == GridKind::Projected) {
        gpu.radial.reset();
        gpu.projected = std::make_unique<ProjectedGrid>(desc.projectedGrid);
        gpu.mesh = GridMesh::upload(gpu.projected->vertices(), gpu.projected->indices());
        return;
    }
    gpu.projected.reset();
    gpu.radial = std::make_unique<RadialGrid>(desc.grid);
    gpu.mesh = GridMesh::upload(gpu.radial->vertices(), gpu.radial->indices());
}

/// Rounds v > 0 up to the ladder 2^(k/8) (steps of 9%), so the thinning selection changes only when the
/// camera's height or the screen changes by that much, not every frame.
double ladderUp(double v) {
    return std::exp2(std::ceil(8.0 * std::log2(v)) / 8.0);
}

/// Horizontal displacement bound of the model: 2 Hs for Gerstner and FFT, 0 for the octaves (vertical only).
double horizontalGuard(const OceanComponent& ocean) {
    return ocean.surface->kind() == SurfaceKind::Octaves ? 0.0 : 2.0 * ocean.surface->significantWaveHeight();
}

/// How far above mean sea level the displaced surface can reach, for leaving out hidden rings: 2 Hs (the cull
/// test's bound), or the octaves' exact bound when larger (the displaced maps' peak texels times their
/// amplitudes; with many displaced octaves it can exceed 2 Hs). Gerstner: sum A_i <= sqrt(N) |A| <= 2 Hs for
/// N <= 32 waves; the FFT's peaks lie near 4.5 sigma, 1.1 Hs.
double verticalReach(const OceanComponent& ocean) {
    double reach = 2.0 * ocean.surface->significantWaveHeight();
    if (const auto* octaves = dynamic_cast<const HeightOctaves*>(ocean.surface.get()))
        reach = std::max(reach, octaves->maxDisplacement());
    return reach;
}

/// The sea's index ranges for this frame: every triangle of the grid, or with ring thinning only those
/// joining the rings drawn (rebuilt and uploaded when the selection changes; counted in `stats`), less the
/// inner rings no part of which can be in view (OceanDesc::skipHiddenRings: hiddenDiscRadius()). Binds the
/// matching element buffer to the grid's VAO. `vertices` = vertices shaded.
std::vector<RadialGrid::IndexRange> seaIndices(OceanGpu& gpu, const OceanComponent& ocean,
                                               const OceanFrame& frame, OceanStats& stats,
                                               long long& vertices) {
    if (!gpu.radial) {
        vertices = gpu.mesh.vertexCount;
        return {{0, static_cast<size_t>(gpu.mesh.indexCount)}};
    }
    const double minPixels = ocean.desc.grid.minRingPixels;
    const bool thin = minPixels > 0.0 && frame.height > 0;
    size_t ringsDrawn = static_cast<size_t>(gpu.radial->ringCount());
    auto ringAt = [&](size_t k) { return thin ? gpu.thinRings[k] : static_cast<int>(k); };
    if (!thin) {
        if (gpu.thinBound) {
            glVertexArrayElementBuffer(gpu.mesh.vao.id(), gpu.mesh.indices.id());
            gpu.thinBound = false;
        }
    } else {
        RingView view;
        view.height = ladderUp(std::max(std::abs(frame.camera.origin.z), 0.01) +
                               2.0 * ocean.surface->significantWaveHeight());
        view.pixelsPerRadian = ladderUp(std::abs(frame.camera.proj[1][1]) * 0.5 * frame.height);
        view.earthRadius = ocean.desc.earthCurvature ? EARTH_RADIUS : 0.0;
        std::vector<int> rings = gpu.radial->ringsFor(view, minPixels);
        if (rings != gpu.thinRings || !gpu.thinIndices) {
            const std::vector<uint32_t> indices = gpu.radial->indicesFor(rings);
            gpu.thinIndices = gl::Buffer::create(indices.size() * sizeof(uint32_t), indices.data());
            gpu.thinIndexCount = static_cast<int>(indices.size());
            gpu.thinRings = std::move(rings);
            gpu.thinBound = false;
            stats.uploads += 1;
        }
        if (!gpu.thinBound) {
            glVertexArrayElementBuffer(gpu.mesh.vao.id(), gpu.thinIndices.id());
            gpu.thinBound = true;
        }
        ringsDrawn = gpu.thinRings.size();
    }
    // Ring pair k (rings k, k + 1 of those drawn) is hidden when its outer ring, moved by the horizontal
    // displacement bound, stays inside the hidden disc.
    size_t firstPair = 0;
    if (ocean.desc.skipHiddenRings) {
        const double hidden = hiddenDiscRadius(frame.camera, verticalReach(ocean)) - horizontalGuard(ocean);
        while (firstPair + 1 < ringsDrawn && gpu.radial->ringRadius(ringAt(firstPair + 1)) < hidden)
            ++firstPair;
    }
    const long long columns = ocean.desc.grid.segments + 1;
    vertices = firstPair == 0 ? 1 + static_cast<long long>(ringsDrawn) * columns
                              : static_cast<long long>(ringsDrawn - firstPair) * columns;
    return gpu.radial->rangesFrom(ringsDrawn, firstPair);
}

/// The uniforms every displaced-grid vertex stage shares (ocean.vert, ocean_projected.vert, effects.vert):
/// the model's (wrapped in double), the camera-relative transform, the camera height, the displaced radius,
/// the curvature drop.
void setSurfaceUniforms(GLuint prog, const OceanComponent& ocean, OceanGpu& gpu, const OceanFrame& frame) {
    gpu.model->bind(prog, 0, frame.time, frame.camera.origin);
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "uViewProj"), 1, GL_FALSE,
                              glm::value_ptr(frame.camera.viewProj));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uCameraHeight"),
                       static_cast<float>(frame.camera.origin.z));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uDisplaceRadius"),
                       static_cast<float>(ocean.desc.grid.rMax * 1.0001));
    // ocean.frag's crest height for the light scattered out of crests: Hs / 2 of the model.
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uCrestHeight"),
                       static_cast<float>(0.5 * ocean.surface->significantWaveHeight()));
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uCurvature"),
                       ocean.desc.earthCurvature ? static_cast<float>(1.0 / (2.0 * EARTH_RADIUS)) : 0.0f);
}

/// §18.2.5's per-vertex frustum test (uCull of ocean.vert and effects.vert): displace only if |clip.xy| <
/// clip.w C0 + C1, the guard C1 from the vertical `reach` of the displaced surface plus the horizontal guard.
void setCullUniform(GLuint prog, const OceanComponent& ocean, const OceanFrame& frame, double reach) {
    const double c0 = 1.0 + ocean.desc.cullGuardNdc;
    const double bound = reach + horizontalGuard(ocean);
    const double scale = std::max(std::abs(frame.camera.proj[0][0]), std::abs(frame.camera.proj[1][1]));
    glProgramUniform3f(prog, glGetUniformLocation(prog, "uCull"), ocean.desc.cullVertices ? 1.0f : 0.0f,
                       static_cast<float>(c0), static_cast<float>(bound * (scale + c0)));
}

/// Per-frame uniforms of the sea's vertex stage: setSurfaceUniforms(), the view sector and the cull test.
/// Returns false when the sea is not in view at all (projected grid: nothing of the wave volume on screen).
bool setSeaUniforms(GLuint prog, const OceanComponent& ocean, OceanGpu& gpu, const OceanFrame& frame) {
    setSurfaceUniforms(prog, ocean, gpu, frame);
    // Horizontal displacement (Gerstner, FFT) can move a vertex from outside the sector into view: widen the
    // sector near the camera by asin(guard / r) (whole circle within guard), guard = 2 Hs, and the cull test
    // by the displacement bound.
    const ViewSector sector =
        ocean.desc.viewSector
            ? computeViewSector(frame.camera, ocean.desc.sectorGuardDeg * std::numbers::pi / 180.0)
            : ViewSector{};
    glProgramUniform3f(prog, glGetUniformLocation(prog, "uSector"), static_cast<float>(sector.center),
                       static_cast<float>(sector.halfWidth), static_cast<float>(horizontalGuard(ocean)));
    setCullUniform(prog, ocean, frame, 2.0 * ocean.surface->significantWaveHeight());
    if (gpu.projected) {
        const ProjectedGrid::Frame f =
            gpu.projected->frame(frame.camera, ocean.desc.earthCurvature ? EARTH_RADIUS : 0.0);
        const auto corners = f.cornerUniforms();
        glProgramUniform4fv(prog, glGetUniformLocation(prog, "uCorners"), 4, glm::value_ptr(corners[0]));
        return f.visible;
    }
    return true;
}

/// The clip distances the grids' vertex stages write where secondary grids are drawn (effects_sample.glsl
/// clipEffectGrids), on or off; off outside those draws (a host's enables are restored by the StateGuard).
void enableGridClips(bool on) {
    for (int i = 0; i < EFFECT_GRID_CLIPS; ++i)
        on ? glEnable(GLenum(GL_CLIP_DISTANCE0 + i)) : glDisable(GLenum(GL_CLIP_DISTANCE0 + i));
}

/// How far above or below its disc an effect grid's surface can reach: the base surface (2 Hs) plus the
/// saturated effect field.
double effectHeightBound(const OceanComponent& ocean) {
    return 2.0 * ocean.surface->significantWaveHeight() + EFFECT_HEIGHT_LIMIT;
}

void countEffectUploads(const EffectsGpu& fx, OceanStats& stats) {
    stats.effectField = fx.fieldStats();
    stats.uploads += stats.effectField.uploads;
    stats.explosions.active = fx.count(EffectKind::Explosion);
    stats.explosions.drawn = fx.drawn(EffectKind::Explosion);
    stats.explosions.uploads = fx.uploads(EffectKind::Explosion);
    stats.wakes.active = fx.count(EffectKind::Wake);
    stats.wakes.drawn = fx.drawn(EffectKind::Wake);
    stats.wakes.uploads = fx.uploads(EffectKind::Wake);
    stats.uploads += stats.explosions.uploads + stats.wakes.uploads;
}

} // namespace

OceanRenderer::OceanRenderer() noexcept : mImpl(std::make_unique<Impl>()) {}

OceanRenderer::~OceanRenderer() = default;

OceanGpu& OceanRenderer::Impl::prepare(std::uint64_t id, const OceanComponent& ocean) {
    std::unique_ptr<OceanGpu>& gpu = mGpu[id];
    if (!gpu)
        gpu = std::make_unique<OceanGpu>();
    if (gpu->surface != ocean.surface) {
        gpu->model = makeSurfaceGpu(ocean.surface);
        gpu->surface = ocean.surface;
        gpu->programKey = joined(gpu->model->glslFiles());
    }
    const bool gridChanged = !gpu->mesh.vao || gpu->gridKind != ocean.desc.gridKind ||
                             (ocean.desc.gridKind == GridKind::Radial
                                  ? !sameGrid(gpu->gridDesc, ocean.desc.grid)
                                  : !sameProjected(gpu->projected->desc(), ocean.desc.projectedGrid));
    if (gridChanged)
        buildGrid(*gpu, ocean.desc);
    return *gpu;
}

unsigned OceanRenderer::Impl::effectProgram(OceanGpu& gpu, bool feedback, bool geometry,
                                            const std::string& lit) {
    gl::Program& program = (feedback   ? mPrograms->effectsFeedback
                            : geometry ? mPrograms->effectsGeometry
                                       : mPrograms->effects)[gpu.programKey + lit];
    if (!program) {
        ++mStats.programsBuilt;
        const std::vector<std::string> model = gpu.model->glslFiles();
        const std::string name = "ocean effect grids (" + gpu.programKey + ")";
        const std::string field = "#define EFFECT_FIELD\n";
        auto vertex = sources(concat(model, {"effects_sample.glsl", "effects.vert"}),
                              field + "#define EFFECT_GRID_CLIP\n");
        if (geometry)
            program = gl::buildProgram({{gl::ShaderStage::Vertex, vertex},
                                        {gl::ShaderStage::Fragment, sources({"ocean_gbuffer.frag"})}},
                                       name + " geometry");
        else if (feedback)
            program =
                gl::buildProgram({{gl::ShaderStage::Vertex, vertex}}, name + " feedback", {"vRel", "vLocal"});
        else
            program = gl::buildProgram(
                {{gl::ShaderStage::Vertex, vertex},
                 {gl::ShaderStage::Fragment,
                  sources(concat(model, {"effects_sample.glsl", "sky.glsl", "spot.glsl", "ocean.frag"}),
                          field + lit)}},
                name);
    }
    return program.id();
}

unsigned OceanRenderer::Impl::effectFieldProgram() {
    const std::string kinds = mEffects->defines();
    gl::Program& program = mPrograms->effectField[kinds];
    if (!program) {
        ++mStats.programsBuilt;
        program = gl::buildProgram(
            {{gl::ShaderStage::Compute, sources({"effects.glsl", "effects_field.comp"}, kinds)}},
            "ocean effects field");
    }
    return program.id();
}

namespace {
enum TimedPass { PassCompute, PassSky, PassSea, PassEffects, PassShade, PassCount };
} // namespace

void OceanRenderer::setPassTiming(std::optional<PassClock> clock) noexcept {
    Impl& r = *mImpl;
    r.mPassTimes = {};
    if (!clock)
        r.mPassTimer.reset();
    else
        r.mPassTimer = std::make_unique<gl::PassTimer>(*clock == PassClock::TimerQuery
                                                           ? gl::GpuTimer::Clock::TimerQuery
                                                           : gl::GpuTimer::Clock::WallAroundFinish,
                                                       PassCount);
}

const char* OceanRenderer::passTimingClock() const noexcept {
    return mImpl->mPassTimer ? mImpl->mPassTimer->clockName() : "";
}

const OceanStats& OceanRenderer::lastStats() const noexcept {
    return mImpl->mStats;
}

Status OceanRenderer::render(const OceanScene& scene, const OceanFrame& frame) noexcept {
    gl::keepDriverLoadedForLeakChecks(); // the host's context: sanitizer builds only (engine/gl/GlContext.h)
    return guarded([&] { mImpl->render(scene, frame); });
}

Status OceanRenderer::queueHeights(std::uint64_t oceanId, std::span<const glm::dvec2> points,
                                   std::uint64_t& ticket) noexcept {
    return guarded([&] { ticket = mImpl->mQueries.queue(oceanId, points); });
}

Status OceanRenderer::takeHeights(std::uint64_t ticket, std::span<double> heights, bool& ready) noexcept {
    ready = false;
    return guarded([&] { ready = mImpl->mQueries.take(ticket, heights); });
}

const GpuQueryCounters& OceanRenderer::gpuQueryCounters() const noexcept {
    return mImpl->mQueries.counters();
}

void OceanRenderer::Impl::render(const OceanScene& scene, const OceanFrame& frame) {
    mStats = {};
    validateScene(scene, frame);
    mStats.spots = static_cast<int>(std::min<size_t>(scene.spots.size(), MAX_SPOT_LIGHTS));
    mStats.spotsDropped = static_cast<int>(scene.spots.size()) - mStats.spots;
    mStats.spotsRejected = scene.spotsRejected;
    renderPasses(scene, frame);
    if (!mPassTimer)
        return;
    if (auto ms = mPassTimer->poll()) {
        mPassTimes.measured = true;
        mPassTimes.computeMs = (*ms)[PassCompute];
        mPassTimes.skyMs = (*ms)[PassSky];
        mPassTimes.seaMs = (*ms)[PassSea];
        mPassTimes.effectsMs = (*ms)[PassEffects];
        mPassTimes.shadeMs = (*ms)[PassShade];
    }
    mStats.passTimes = mPassTimes;
}

namespace {

/// Pass timing (setPassTiming): a mark at the end of each pass; a pass left out adds ~0 to its slot.
struct FrameMarks {
    gl::PassTimer* timer;
    explicit FrameMarks(gl::PassTimer* t) : timer(t) {
        if (timer)
            timer->beginFrame();
    }
    ~FrameMarks() {
        if (timer)
            timer->endFrame();
    }
    FrameMarks(const FrameMarks&) = delete;
    FrameMarks& operator=(const FrameMarks&) = delete;
    void mark(int pass) const {
        if (timer)
            timer->mark(pass);
    }
};

} // namespace

/// One ocean's frame as a fixed list of passes: compute (the surface model's update and the effects'
/// buffers), sea (the base grid, lit or into the G-buffer), effects (the secondary grids), then shade (the
/// compute pass lights every pixel, the sky's included) or sky. Each pass reads the frame's inputs and the
/// decisions compute() made from here and adds what it did to the renderer's stats.
namespace {

struct FramePasses {
    OceanRenderer::Impl& r;
    const EffectsView& scene; ///< the frame's effects
    const OceanFrame& frame;
    const OceanComponent& ocean;
    OceanGpu& gpu;
    const glm::mat4 invViewProj;
    const FrameMarks& marks;
    const bool queriesWaiting; ///< GPU height queries of this ocean are evaluated after the frame
    const std::span<const SpotLight> spots; ///< the spot lights that light the sea (at most MAX_SPOT_LIGHTS)
    // Decided by compute():
    bool effects = false;   ///< effects in the frame: every grid and the shading read the effects field
    bool holes = false;     ///< ... and secondary grids are drawn: the base grid has holes where they are
    bool displaced = false; ///< the surface moves sideways (Gerstner, FFT)
    bool deferred = false;  ///< compute shading (OceanDesc::computeShading) is attached
    bool tiled = false;     ///< ... by tiles (OceanDesc::shadeTiles)
    std::string fxDefines;

    void compute();
    FieldReads fieldReads() const;
    /// "#define SPOT_LIGHTS" when the frame has spot lights: the variant of every program lighting the sea or
    /// drawing the sky (the beams).
    std::string spotDefines() const { return spots.empty() ? std::string() : "#define SPOT_LIGHTS\n"; }
    /// Sets the spots' uniforms on a program built with spotDefines().
    void bindSpots(GLuint prog) const {
        if (!spots.empty())
            setSpotUniforms(prog, spots, frame, ocean.desc.lighting);
    }
    /// The base grid; false when no sea is in view (nothing drawn).
    bool sea();
    void grids();
    void sky();
    void shade();
    /// The frame's last pass: shade under compute shading, else the sky.
    void last() { deferred ? shade() : sky(); }
    /// The asynchronous GPU height queries queued for this ocean (queueHeights): one compute pass.
    void queries(std::uint64_t oceanId);

private:
    GLuint shadeProgram(int kind);
    gl::Program& seaProgram();
    void drawSeaGrid();
};

} // namespace

void FramePasses::compute() {
    const SurfaceGpuStats work = gpu.model->update(frame.time, frame.camera.origin);
    r.mStats.passes += work.computePasses;
    r.mStats.uploads += work.uploads;
    // Effects (EffectTypes.h): prepared only when the scene has any; otherwise no buffer, no variant.
    int grids = 0; // secondary grids drawn this frame
    if (!scene.empty()) {
        r.mEffects->prepare(scene, frame, effectHeightBound(ocean), ocean.desc.effectGrids,
                            ocean.desc.effectField, fieldReads());
        effects = r.mEffects->any();
        grids = effects ? r.mEffects->drawn(EffectKind::Explosion) + r.mEffects->drawn(EffectKind::Wake) : 0;
        holes = grids > 0;
        if (effects)
            r.mEffects->computeField(r.effectFieldProgram());
        countEffectUploads(*r.mEffects, r.mStats);
        r.mStats.passes += r.mStats.effectField.passes;
    }
    // With at most EFFECT_GRID_CLIPS grids the clipper cuts every hole (effects_sample.glsl clipEffectGrids):
    // the base grid's fragments keep no discard, so the depth test runs before them. What the clip leaves
    // of a hole (slivers between its triangles' chords and the 0.98 R circle) lies under the grid that
    // draws the same surface there.
    fxDefines = std::string(effects ? "#define EFFECT_FIELD\n" : "") +
                (holes ? "#define EFFECT_HOLES\n" : "") +
                (holes && grids <= EFFECT_GRID_CLIPS ? "#define EFFECT_HOLES_CLIPPED\n" : "");
    marks.mark(PassCompute); // the surface model's passes and the effects field's
    // Compute shading: the grids only fill a G-buffer sharing the host's depth (ComputeShading.h).
    displaced = horizontalGuard(ocean) > 0.0;
    deferred = ocean.desc.computeShading &&
               r.mCompute->attach(frame.targetFramebuffer, frame.width, frame.height, displaced);
    r.mStats.computeShaded = deferred;
    // Tiles (OceanDesc::shadeTiles): Auto asks the renderer's name once.
    if (r.mPrograms->softwareRenderer < 0) {
        const auto* name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
        r.mPrograms->softwareRenderer = gl::isSoftwareRenderer(name ? name : "");
    }
    tiled = deferred &&
            (ocean.desc.shadeTiles == OceanDesc::ShadeTiles::On ||
             (ocean.desc.shadeTiles == OceanDesc::ShadeTiles::Auto && r.mPrograms->softwareRenderer == 1));
    r.mStats.shadeTiled = tiled;
}

/// Where this frame reads the effects field (EffectFieldDesc::viewCull). The base grid's vertices lie in the
/// view sector widened by asin(g / r) at radius r (setSeaUniforms, sectorPosition), which is within g of the
/// sector, and each reads the field where it is displaced to, up to g further: 2 g in all (g the horizontal
/// displacement bound). The shading reads only what is on screen, inside the sector. The GPU height queries
/// read anywhere, and a projected grid's vertices are not laid out by the sector: every tile then.
FieldReads FramePasses::fieldReads() const {
    if (!ocean.desc.effectField.viewCull || !ocean.desc.viewSector || !gpu.radial || queriesWaiting)
        return {};
    return {computeViewSector(frame.camera, ocean.desc.sectorGuardDeg * std::numbers::pi / 180.0),
            2.0 * horizontalGuard(ocean)};
}

void FramePasses::queries(std::uint64_t oceanId) {
    Programs& programs = *r.mPrograms;
    const bool sideways = ocean.surface->kind() != SurfaceKind::Octaves;
    gl::Program& program = programs.seaQuery[gpu.programKey + (effects ? "+effects" : "")];
    if (!program) {
        ++r.mStats.programsBuilt;
        std::vector<std::string> files = gpu.model->glslFiles();
        if (effects)
            files.push_back("effects_sample.glsl");
        files.push_back("sea_query.comp");
        const std::string defines = "#define SEA_QUERY_ITERATIONS " +
                                    std::to_string(sideways ? SEA_QUERY_ITERATIONS : 0) +
                                    "\n#define SEA_QUERY_TOLERANCE " + std::to_string(SEA_QUERY_TOLERANCE) +
                                    "\n" + (effects ? "#define EFFECT_FIELD\n" : "");
        program = gl::buildProgram({{gl::ShaderStage::Compute, sources(files, defines)}},
                                   "ocean GPU height queries (" + gpu.programKey + ")");
    }
    const GLuint prog = program.id();
    glUseProgram(prog);
    setSurfaceUniforms(prog, ocean, gpu, frame);
    if (effects)
        r.mEffects->bindField(prog);
    r.mStats.passes += r.mQueries.evaluate(oceanId, frame.camera.origin, prog) > 0 ? 1 : 0;
}

/// The sky after the sea and its effects (no overdraw): its fullscreen triangle lies at depth 0 (infinitely
/// far in reverse-Z) and GL_GEQUAL passes only where nothing nearer was drawn, so the early depth test
/// spares the sky's shading on every sea pixel. (A host's 24-bit depth buffer rounds the skirt's depth to 0
/// beyond ~840 km; there the sky pass draws its own flat distant sea.)
void FramePasses::sky() {
    if (!ocean.desc.drawSky)
        return;
    Programs& programs = *r.mPrograms;
    gl::Program& program = spots.empty() ? programs.sky : programs.skySpots;
    if (!program) {
        ++r.mStats.programsBuilt;
        program = gl::buildProgram(
            {{gl::ShaderStage::Vertex, sources({"sky.vert"})},
             {gl::ShaderStage::Fragment, sources({"sky.glsl", "spot.glsl", "sky.frag"}, spotDefines())}},
            spots.empty() ? "ocean sky" : "ocean sky (spot lights)");
    }
    if (!programs.emptyVao)
        programs.emptyVao = gl::VertexArray::create();
    const GLuint sky = program.id();
    glUseProgram(sky);
    r.mLighting->bind(sky, LIGHTING_FIRST_UNIT, ocean.desc, frame);
    bindSpots(sky);
    glProgramUniformMatrix4fv(sky, glGetUniformLocation(sky, "uInvViewProj"), 1, GL_FALSE,
                              glm::value_ptr(invViewProj));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GEQUAL);
    glDepthMask(GL_FALSE);
    glBindVertexArray(programs.emptyVao.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    r.mStats.passes += 1;
    r.mStats.draws += 1;
    r.mStats.vertices += 3;
    marks.mark(PassSky);
}

/// One lighting program: all of it (untiled, kind < 0), or one kind of tile's part. The sky's kinds need
/// neither the surface model nor the sea's lighting: one program each for every model and effect.
GLuint FramePasses::shadeProgram(int kind) {
    // Every shading program's defines; the sea's add the model's G-buffer layers.
    const std::string base = std::string("#define SHADE_COMPUTE\n#define SHADE_OUTPUT_FORMAT ") +
                             r.mCompute->outputFormat() + "\n" + ComputeShading::tileDefines() +
                             spotDefines();
    const std::string seaDefines =
        base + (effects ? "#define EFFECT_FIELD\n" : "") + (displaced ? "#define GBUFFER_DISPLACED\n" : "");
    const bool skyOnly = ComputeShading::skyOnly(kind);
    const std::string variant =
        (skyOnly ? base : seaDefines) + (kind < 0 ? std::string()
                                                  : "#define SHADE_TILES\n#define SHADE_TILE_ACCESS "
                                                    "readonly\n#define SHADE_TILE_KIND " +
                                                        std::to_string(kind) + "\n");
    const std::string owner = skyOnly ? std::string("sky") : gpu.programKey;
    gl::Program& program = r.mPrograms->shade[owner + variant];
    if (!program) {
        ++r.mStats.programsBuilt;
        std::vector<std::string> files{"shade_compute.glsl"};
        if (!skyOnly)
            for (const std::string& f : gpu.model->glslFiles())
                files.push_back(f);
        if (!skyOnly && effects)
            files.push_back("effects_sample.glsl");
        files.insert(files.end(), {"sky.glsl", "spot.glsl", "sky.frag", "shade_pixels.glsl"});
        if (!skyOnly)
            files.push_back("ocean.frag");
        files.push_back("ocean_shade.comp");
        program =
            gl::buildProgram({{gl::ShaderStage::Compute, sources(files, variant)}},
                             "ocean compute shading (" + owner +
                                 (kind < 0 ? std::string() : ", tile kind " + std::to_string(kind)) + ")");
    }
    const GLuint prog = program.id();
    setSurfaceUniforms(prog, ocean, gpu, frame);
    r.mLighting->bind(prog, LIGHTING_FIRST_UNIT, ocean.desc, frame);
    bindSpots(prog);
    if (effects && !skyOnly)
        r.mEffects->bindField(prog);
    glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "uInvViewProj"), 1, GL_FALSE,
                              glm::value_ptr(invViewProj));
    return prog;
}

/// Compute shading: one pass over every pixel, or the tile sort and one pass per kind of tile.
void FramePasses::shade() {
    Programs& programs = *r.mPrograms;
    if (tiled) {
        if (!programs.shadeTileSort) {
            ++r.mStats.programsBuilt;
            programs.shadeTileSort = gl::buildProgram(
                {{gl::ShaderStage::Compute,
                  sources({"shade_compute.glsl", "sky.glsl", "sky.frag", "shade_pixels.glsl",
                           "ocean_shade_tiles.comp"},
                          ComputeShading::tileDefines() +
                              "#define SHADE_COMPUTE\n#define SHADE_TILES\n#define SHADE_TILE_ACCESS\n")}},
                "ocean compute shading tiles");
        }
        const GLuint sort = programs.shadeTileSort.id();
        glProgramUniformMatrix4fv(sort, glGetUniformLocation(sort, "uInvViewProj"), 1, GL_FALSE,
                                  glm::value_ptr(invViewProj));
        unsigned kinds[ComputeShading::TILE_KINDS];
        for (int k = 0; k < ComputeShading::TILE_KINDS; ++k)
            kinds[k] = shadeProgram(k);
        r.mCompute->shadeTiles(sort, kinds, ocean.desc.drawSky);
        r.mStats.passes += 1 + ComputeShading::TILE_KINDS;
    } else {
        r.mCompute->shade(shadeProgram(-1), ocean.desc.drawSky);
        r.mStats.passes += 1;
    }
    marks.mark(PassShade);
}

/// The base grid's program: lit, or into the G-buffer; with holes where the effect grids draw.
gl::Program& FramePasses::seaProgram() {
    const char* vert = gpu.projected ? "ocean_projected.vert" : "ocean.vert";
    const std::string lit = deferred ? std::string() : spotDefines(); // the G-buffer variant lights nothing
    gl::Program& program =
        (deferred ? r.mPrograms->seaGeometry : r.mPrograms->sea)[gpu.programKey + vert + fxDefines + lit];
    if (!program) {
        ++r.mStats.programsBuilt;
        const std::vector<std::string> model = gpu.model->glslFiles();
        std::vector<std::string> vertex = model;
        std::vector<std::string> frag = deferred ? std::vector<std::string>{} : model;
        // The G-buffer's fragment stage needs the field's file only for the holes.
        const bool fragField = !fxDefines.empty() && (!deferred || holes);
        const std::string fragDefines = (fragField ? fxDefines : std::string()) + lit;
        if (effects)
            vertex.emplace_back("effects_sample.glsl");
        if (fragField)
            frag.emplace_back("effects_sample.glsl");
        vertex.emplace_back(vert);
        program =
            gl::buildProgram({{gl::ShaderStage::Vertex,
                               sources(vertex, fxDefines + (holes ? "#define EFFECT_GRID_CLIP\n" : ""))},
                              {gl::ShaderStage::Fragment,
                               sources(deferred ? concat(frag, {"ocean_gbuffer.frag"})
                                                : concat(frag, {"sky.glsl", "spot.glsl", "ocean.frag"}),
                                       fragDefines)}},
                             std::string(deferred ? "ocean sea geometry (" : "ocean sea (") + gpu.programKey +
                                 (effects ? ", effects field" : "") + (holes ? ", effect holes" : "") + ")");
    }
    return program;
}

bool FramePasses::sea() {
    const GLuint sea = seaProgram().id();
    glUseProgram(sea);
    if (deferred)
        r.mCompute->beginGeometry();
    if (!setSeaUniforms(sea, ocean, gpu, frame))
        return false;
    if (!deferred) {
        r.mLighting->bind(sea, LIGHTING_FIRST_UNIT, ocean.desc, frame);
        bindSpots(sea);
    }
    if (effects) {
        r.mEffects->bindField(sea);
        setCullUniform(sea, ocean, frame, effectHeightBound(ocean)); // the field raises the sea too
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    enableGridClips(holes);
    drawSeaGrid();
    enableGridClips(false);
    marks.mark(PassSea);
    return true;
}

/// The grid's index ranges in view (the view sector, the ring cut), in one draw call.
void FramePasses::drawSeaGrid() {
    long long seaVertices = 0;
    const std::vector<RadialGrid::IndexRange> ranges = seaIndices(gpu, ocean, frame, r.mStats, seaVertices);
    glBindVertexArray(gpu.mesh.vao.id());
    if (ranges.size() == 1) {
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(ranges[0].count), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(ranges[0].first * sizeof(uint32_t)));
    } else if (!ranges.empty()) { // one call for the blocks of columns (RadialGrid::rangesFrom)
        std::vector<GLsizei> counts;
        std::vector<const void*> offsets;
        for (const RadialGrid::IndexRange& range : ranges) {
            counts.push_back(static_cast<GLsizei>(range.count));
            offsets.push_back(reinterpret_cast<const void*>(range.first * sizeof(uint32_t)));
        }
        glMultiDrawElements(GL_TRIANGLES, counts.data(), GL_UNSIGNED_INT, offsets.data(),
                            static_cast<GLsizei>(ranges.size()));
    }
    r.mStats.passes += 1;
    r.mStats.draws += 1;
    r.mStats.vertices += seaVertices;
}

/// The secondary grids, one instanced draw per kind in view (after the base grid: the same depth test).
void FramePasses::grids() {
    const GLuint fx = r.effectProgram(gpu, false, deferred, deferred ? std::string() : spotDefines());
    glUseProgram(fx);
    setSurfaceUniforms(fx, ocean, gpu, frame);
    // The effect grids' guard adds the effect field's reach; the feedback programs (tests) leave the test
    // off: every vertex evaluated.
    setCullUniform(fx, ocean, frame, effectHeightBound(ocean));
    r.mLighting->bind(fx, LIGHTING_FIRST_UNIT, ocean.desc, frame);
    if (!deferred)
        bindSpots(fx);
    r.mEffects->bindField(fx);
    enableGridClips(true);
    for (EffectKind kind : {EffectKind::Explosion, EffectKind::Wake}) {
        EffectKindStats& ks = kind == EffectKind::Explosion ? r.mStats.explosions : r.mStats.wakes;
        const long long vertices = r.mEffects->draw(fx, kind);
        if (vertices == 0)
            continue;
        ks.passes += 1;
        ks.draws += 1;
        ks.vertices += vertices;
        r.mStats.passes += 1;
        r.mStats.draws += 1;
        r.mStats.vertices += vertices;
    }
    enableGridClips(false);
    marks.mark(PassEffects);
}

void OceanRenderer::Impl::renderPasses(const OceanScene& scene, const OceanFrame& frame) {
    // Drop GPU resources of oceans the scene no longer lists.
    for (auto it = mGpu.begin(); it != mGpu.end();) {
        const bool listed = std::any_of(scene.oceans.begin(), scene.oceans.end(),
                                        [&](const OceanInstance& o) { return o.id == it->first; });
        it = listed ? std::next(it) : mGpu.erase(it);
    }
    if (scene.oceans.empty())
        return; // nothing to draw: no pass, no draw, no upload, no shader compiled

    gl::StateGuard guard;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, frame.targetFramebuffer);
    glViewport(0, 0, frame.width, frame.height);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    enableGridClips(false); // a host's clip planes must not cut shaders that write no clip distance
    // Reverse-Z (Space.h perspectiveReverseZInfinite): depth 1 at the near plane, 0 at infinity.
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glClearDepth(0.0);
    glClear(GL_DEPTH_BUFFER_BIT);

    const FrameMarks marks(mPassTimer.get());
    for (const OceanInstance& instance : scene.oceans) {
        const OceanComponent& ocean = *instance.ocean;
        if (!ocean.surface)
            continue;
        FramePasses passes{*this,
                           scene.effects,
                           frame,
                           ocean,
                           prepare(instance.id, ocean),
                           glm::inverse(frame.camera.viewProj),
                           marks,
                           mQueries.waiting(instance.id),
                           scene.spots.first(std::min<size_t>(scene.spots.size(), MAX_SPOT_LIGHTS))};
        passes.compute();
        if (passes.sea() && passes.holes)
            passes.grids();
        passes.last(); // no sea in view: the sky (or the shading pass) alone
        if (mQueries.waiting(instance.id))
            passes.queries(instance.id);
    }
    mStats.uploads += mLighting->uploadsSinceLastCall(); // environment, foam, fog noise: once each
}

// ---- Debug hooks (OceanDebug.h)
// ----------------------------------------------------------------------------

namespace debug {

std::array<int, 4> shadeTileCounts(OceanRenderer& renderer) {
    const OceanRenderer::Impl& r = renderer.impl();
    return r.mStats.shadeTiled ? r.mCompute->tileCounts() : std::array<int, 4>{};
}

namespace {

const OceanComponent& oceanOf(ecs::Registry& registry, ecs::Entity entity, const char* where) {
    const OceanComponent* ocean = registry.tryGet<OceanComponent>(entity);
    if (!ocean || !ocean->surface)
        throw std::invalid_argument(std::string(where) + ": entity " + ecs::toString(entity) +
                                    " has no OceanComponent");
    return *ocean;
}

} // namespace

std::vector<DisplacedVertex> displacedVertices(OceanRenderer& renderer, ecs::Registry& registry,
                                               ecs::Entity entity, const OceanFrame& frame) {
    OceanRenderer::Impl& r = renderer.impl();
    Programs& programs = *r.mPrograms;
    const OceanComponent* ocean = &oceanOf(registry, entity, "debug::displacedVertices()");
    OceanGpu& gpu = r.prepare(oceanId(entity), *ocean);
    const char* vert = gpu.projected ? "ocean_projected.vert" : "ocean.vert";
    gl::Program& program = programs.seaFeedback[gpu.programKey + vert];
    if (!program)
        program =
            gl::buildProgram({{gl::ShaderStage::Vertex, sources(concat(gpu.model->glslFiles(), {vert}))}},
                             "ocean sea feedback (" + gpu.programKey + ")", {"vRel", "vGrid"});
    ensureFeedbackTarget(programs);
    gl::StateGuard guard;
    gpu.model->update(frame.time, frame.camera.origin);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, programs.feedbackFbo.id());
    const GLuint prog = program.id();
    glUseProgram(prog);
    (void)setSeaUniforms(prog, *ocean, gpu, frame);
    const size_t count = static_cast<size_t>(gpu.mesh.vertexCount);
    static_assert(sizeof(DisplacedVertex) == 5 * sizeof(float), "interleaved vRel, vGrid");
    gl::Buffer captured = gl::Buffer::create(count * sizeof(DisplacedVertex), nullptr);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, captured.id());
    glEnable(GL_RASTERIZER_DISCARD);
    glBindVertexArray(gpu.mesh.vao.id());
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(count));
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    std::vector<DisplacedVertex> out(count);
    glGetNamedBufferSubData(captured.id(), 0, static_cast<GLsizeiptr>(count * sizeof(DisplacedVertex)),
                            out.data());
    return out;
}

std::vector<EffectVertex> effectVertices(OceanRenderer& renderer, ecs::Registry& registry, ecs::Entity entity,
                                         const OceanFrame& frame, EffectKind kind) {
    OceanRenderer::Impl& r = renderer.impl();
    Programs& programs = *r.mPrograms;
    EffectsGpu& fx = *r.mEffects;
    const OceanComponent* ocean = &oceanOf(registry, entity, "debug::effectVertices()");
    OceanGpu& gpu = r.prepare(oceanId(entity), *ocean);
    const RegistryEffects effects(registry);
    fx.prepare(effects.view(), frame, effectHeightBound(*ocean), ocean->desc.effectGrids,
               ocean->desc.effectField);
    if (fx.drawn(kind) == 0)
        return {};
    ensureFeedbackTarget(programs);
    gl::StateGuard guard;
    gpu.model->update(frame.time, frame.camera.origin);
    fx.computeField(r.effectFieldProgram());
    const GLuint prog = r.effectProgram(gpu, true, false);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, programs.feedbackFbo.id());
    glUseProgram(prog);
    setSurfaceUniforms(prog, *ocean, gpu, frame);
    fx.bindField(prog);
    const size_t count = static_cast<size_t>(fx.gridVertices(kind) * fx.drawn(kind));
    struct Captured {
        glm::vec3 position;
        glm::vec2 local;
    };
    static_assert(sizeof(Captured) == 5 * sizeof(float), "interleaved vRel, vLocal");
    gl::Buffer captured = gl::Buffer::create(count * sizeof(Captured), nullptr);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, captured.id());
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    fx.draw(prog, kind, GL_POINTS);
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
    std::vector<Captured> raw(count);
    glGetNamedBufferSubData(captured.id(), 0, static_cast<GLsizeiptr>(count * sizeof(Captured)), raw.data());
    const size_t perInstance = static_cast<size_t>(fx.gridVertices(kind));
    const size_t firstGrid =
        kind == EffectKind::Explosion ? 0 : static_cast<size_t>(fx.drawn(EffectKind::Explosion));
    std::vector<EffectVertex> out(count);
    for (size_t i = 0; i < count; ++i)
        out[i] = {raw[i].position, raw[i].local, fx.gridCentres()[firstGrid + i / perInstance]};
    return out;
}

} // namespace debug

} // namespace pacifica::ocean
