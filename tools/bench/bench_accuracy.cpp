// pacifica-accuracy: sweeps the ocean's quality knobs (surface model, octave counts, vertex filter, combined
// displacement, radial grid density, grid kind, FFT size, culling) one at a time from a per-model baseline,
// plus a few presets, and reports for each setting its error and its cost (docs/ACCURACY.md):
//   - vertex error: the rendered mesh (transform-feedback vertices, culling off) against the surface's
//     continuous double reference SurfaceModel::displacementAt(), at grid vertices and at the midpoints of
//     grid edges (where the piecewise-linear mesh interpolates), within the view frustum and rMax, as RMS
//     height error / Hs of the model's reference setting;
//   - normal angle error: the rendered mesh's normal at interior grid vertices (central differences of the
//     four neighbouring transform-feedback vertices) against the continuous displaced surface's normal at
//     the same grid point (SurfaceModel::normalAt; for octaves the displaced octaves' analytic gradient),
//     mean and 95th percentile in degrees;
//   - image error: RMSE of the scene-linear RGB against the model's highest-quality render, and PSNR with
//     peak 1.0 after clamping both images to [0, 1];
//   - cost: median GPU time of OceanRenderer::render + glFinish (engine GpuTimer; GL_TIME_ELAPSED on
//     hardware, wall clock around glFinish on llvmpipe).
// It links no OpenImageIO (it must run on the H100 machine where only OCIO's libraries can be carried):
// the outputs are CSV and Markdown, plus accuracy.png drawn by gnuplot (a separate process, when it is
// installed: the H100 machine has none, so there the PNG is drawn later from accuracy.gp + accuracy.dat).
#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanDebug.h"
#include "ocean/OceanHost.h"
#include "ocean/RadialGrid.h"

#include "BenchCli.h"
#include "BenchMain.h"
#include "BenchPlot.h"
#include "BenchText.h"
#include <CLI/CLI.hpp>

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace pacifica;

namespace {

using bench::csvQuote;
using bench::num;

constexpr double TIME = 12.3; // the brief's fixed simulation time for the error measurements
constexpr double FOV_Y_DEG = 60.0;

struct Setting {
    std::string knob; // which knob differs from the model's baseline ("baseline", "reference", "preset", ...)
    std::string value; // its value, as text
    ocean::OceanDesc desc;
};

struct Result {
    Setting setting;
    double vertexRms = 0.0; // RMS height error at the vertices / Hs
    double meshRms = 0.0;   // RMS height error at grid-edge midpoints / Hs
    size_t samples = 0;
    double normalMeanDeg = 0.0, normalP95Deg = 0.0; // mesh normal vs the continuous surface's normal
    size_t normalSamples = 0;
    double imageRmse = 0.0;
    double psnrDb = 0.0;
    double msMedian = 0.0;
    long long vertices = 0;
    bool pareto = false;
};

struct View {
    const char* name;
    Pose pose;
};

// The brief's three cameras: low looking toward the horizon, 500 m at -20 deg, 5 km at -35 deg. Positions
// are away from the origin so the float camera-relative path is exercised as in a game.
std::vector<View> views() {
    auto make = [](const char* name, glm::dvec3 p, double pitch) {
        View v{name, {}};
        v.pose.position = p;
        v.pose.headingDeg = 70.0;
        v.pose.pitchDeg = pitch;
        return v;
    };
    return {make("low_20m", {1234.5, -987.6, 20.0}, -3.0), make("mid_500m", {1234.5, -987.6, 500.0}, -20.0),
            make("high_5km", {1234.5, -987.6, 5000.0}, -35.0)};
}

const char* modelName(ocean::SurfaceKind k) {
    return ocean::toString(k);
}

ocean::OceanDesc baselineDesc(ocean::SurfaceKind model) {
    ocean::OceanDesc d;
    d.model = model;
    return d;
}

// Highest quality of a model: 512 x 1024 radial grid, bilinear, no culling, every octave displaced, FFT
// N=256.
ocean::OceanDesc referenceDesc(ocean::SurfaceKind model) {
    ocean::OceanDesc d = baselineDesc(model);
    d.grid.rings = 512;
    d.grid.segments = 1024;
    d.cullVertices = false;
    d.octaves.vertexFilter = ocean::VertexFilter::Bilinear;
    d.octaves.combinedDisplacement = false;
    d.octaves.displacedOctaves = static_cast<int>(d.octaves.octaves.size());
    d.fft.size = 256;
    return d;
}

/// The settings of a sweep, each the model's baseline with one edit.
struct SettingList {
    std::vector<Setting> out;
    template <class Edit>
    void add(ocean::SurfaceKind m, std::string knob, std::string value, Edit&& edit) {
        ocean::OceanDesc d = baselineDesc(m);
        edit(d);
        out.push_back({std::move(knob), std::move(value), d});
    }
    void baseline(ocean::SurfaceKind m) {
        add(m, "baseline", "default", [](ocean::OceanDesc&) {});
    }
    void grid(ocean::SurfaceKind m, int rings, int segments) {
        add(m, "grid", std::to_string(rings) + "x" + std::to_string(segments), [&](ocean::OceanDesc& d) {
            d.grid.rings = rings;
            d.grid.segments = segments;
        });
    }
};

/// The octave sea's own knobs: lighting and displaced octaves, vertex filter, combined displacement, foam.
void octaveKnobs(SettingList& l) {
    const ocean::SurfaceKind m = ocean::SurfaceKind::Octaves;
    for (int n : {2, 3, 4}) // lighting octaves (5 = baseline); displaced = min(3, n)
        l.add(m, "octaves", std::to_string(n), [n](ocean::OceanDesc& d) {
            d.octaves.octaves.resize(static_cast<size_t>(n));
            d.octaves.displacedOctaves = std::min(d.octaves.displacedOctaves, n);
        });
    for (int n : {1, 2, 5}) // displaced octaves (3 = baseline)
        l.add(m, "displaced_octaves", std::to_string(n),
              [n](ocean::OceanDesc& d) { d.octaves.displacedOctaves = n; });
    for (ocean::VertexFilter f : {ocean::VertexFilter::Nearest, ocean::VertexFilter::HardwareBilinear,
                                  ocean::VertexFilter::Packed4Tap, ocean::VertexFilter::Trilinear})
        l.add(m, "vertex_filter", ocean::toString(f),
              [f](ocean::OceanDesc& d) { d.octaves.vertexFilter = f; });
    l.add(m, "combined", "on", [](ocean::OceanDesc& d) { d.octaves.combinedDisplacement = true; });
    l.add(m, "foam_memory", "off", [](ocean::OceanDesc& d) { d.octaves.foamMemory = false; });
}

/// The FFT sea's own knobs: grid size, living whitecaps, the near sea's cascades (4 = baseline) and their
/// aperiodic mix (on), the detail grid.
void fftKnobs(SettingList& l) {
    const ocean::SurfaceKind m = ocean::SurfaceKind::Fft;
    for (int n : {64, 128}) // 256 = baseline
        l.add(m, "fft_size", std::to_string(n), [n](ocean::OceanDesc& d) { d.fft.size = n; });
    // Living whitecaps off: foam on the current crests only.
    l.add(m, "foam_memory", "off", [](ocean::OceanDesc& d) { d.fft.foamMemory = false; });
    for (int n : {1, 2, 3})
        l.add(m, "fft_cascades", std::to_string(n), [n](ocean::OceanDesc& d) { d.fft.cascades = n; });
    l.add(m, "fft_cascades", "1-tile-500m", [](ocean::OceanDesc& d) {
        d.fft.cascades = 1;
        d.fft.aperiodic = false;
        d.fft.tileSize = 500.0;
    });
    l.add(m, "fft_mix", "off", [](ocean::OceanDesc& d) { d.fft.aperiodic = false; });
    l.add(m, "fft_detail_size", "64", [](ocean::OceanDesc& d) { d.fft.detailSize = 64; });
}

/// Knobs every model has, after the grid's: culling, where the lighting runs (one compute pass, the
/// baseline, or the grids' fragment stage), the look features (what switching each off changes in the image,
/// and saves), the sky (the older gradient instead of the physical clear sky: nothing to compute or upload;
/// its image error is the look the physical sky changed) and screen-space ring thinning (0 = baseline).
void sharedKnobs(SettingList& l, ocean::SurfaceKind m) {
    l.add(m, "cull", "off", [](ocean::OceanDesc& d) { d.cullVertices = false; });
    l.add(m, "shading", "forward", [](ocean::OceanDesc& d) { d.computeShading = false; });
    l.add(m, "subsurface", "off", [](ocean::OceanDesc& d) { d.lighting.subsurface = 0.0f; });
    l.add(m, "fog_noise", "off", [](ocean::OceanDesc& d) { d.lighting.fogNoise = 0.0f; });
    l.add(m, "glitter", "blinn-phong",
          [](ocean::OceanDesc& d) { d.lighting.glitter = ocean::LightingDesc::Glitter::BlinnPhong; });
    l.add(m, "sky", "gradient",
          [](ocean::OceanDesc& d) { d.lighting.sky = ocean::LightingDesc::Sky::Gradient; });
    for (double px : {0.5, 1.0, 2.0})
        l.add(m, "min_ring_pixels", bench::num(px), [px](ocean::OceanDesc& d) { d.grid.minRingPixels = px; });
}

/// Presets: a cheap setting per model and a combined-displacement octave sea.
void presets(SettingList& l) {
    using ocean::SurfaceKind;
    l.add(SurfaceKind::Octaves, "preset", "fast", [](ocean::OceanDesc& d) {
        d.grid.rings = 128;
        d.grid.segments = 256;
        d.octaves.octaves.resize(3);
        d.octaves.vertexFilter = ocean::VertexFilter::HardwareBilinear;
    });
    l.add(SurfaceKind::Octaves, "preset", "combined-packed", [](ocean::OceanDesc& d) {
        d.octaves.vertexFilter = ocean::VertexFilter::Packed4Tap;
        d.octaves.combinedDisplacement = true;
    });
    l.add(SurfaceKind::Gerstner, "preset", "fast", [](ocean::OceanDesc& d) {
        d.grid.rings = 128;
        d.grid.segments = 256;
    });
    l.add(SurfaceKind::Fft, "preset", "fast", [](ocean::OceanDesc& d) {
        d.grid.rings = 128;
        d.grid.segments = 256;
        d.fft.size = 64;
    });
}

std::vector<Setting> sweep(bool quick) {
    using ocean::SurfaceKind;
    SettingList l;
    if (quick) {
        l.baseline(SurfaceKind::Octaves);
        l.grid(SurfaceKind::Octaves, 64, 128);
        l.grid(SurfaceKind::Octaves, 512, 1024);
        l.add(SurfaceKind::Octaves, "vertex_filter", "nearest",
              [](ocean::OceanDesc& d) { d.octaves.vertexFilter = ocean::VertexFilter::Nearest; });
        return l.out;
    }
    for (SurfaceKind m : {SurfaceKind::Octaves, SurfaceKind::Gerstner, SurfaceKind::Fft}) {
        l.baseline(m);
        if (m == SurfaceKind::Octaves)
            octaveKnobs(l);
        for (auto [r, s] : {std::pair{64, 128}, {128, 256}, {512, 1024}}) // 256x512 = baseline
            l.grid(m, r, s);
        l.add(m, "grid_kind", "projected",
              [](ocean::OceanDesc& d) { d.gridKind = ocean::GridKind::Projected; });
        if (m == SurfaceKind::Fft)
            fftKnobs(l);
        if (m == SurfaceKind::Gerstner)
            l.add(m, "foam_memory", "off", [](ocean::OceanDesc& d) { d.gerstner.foamMemory = false; });
        sharedKnobs(l, m);
    }
    presets(l);
    return l.out;
}

ocean::OceanFrame makeFrame(const Pose& pose, const gl::FrameTargets& targets, double time) {
    return ocean::makeOceanFrame(pose, static_cast<float>(FOV_Y_DEG * std::numbers::pi / 180.0),
                                 targets.width(), targets.height(), time, targets.sceneFramebuffer().id(),
                                 0.5f);
}

bool inFrustum(const glm::mat4& viewProj, const glm::vec3& rel) {
    const glm::vec4 c = viewProj * glm::vec4(rel, 1.0f);
    return c.w > 0.0f && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w;
}

// Grid edges (pairs of vertex indices) of the mesh in its vertex order: RadialGrid (centre, then rings of
// M + 1 vertices; the skirt rings beyond rMax are excluded by the caller's radius test) or ProjectedGrid
// (row-major, resolutionX per row).
std::vector<std::pair<uint32_t, uint32_t>> gridEdges(const ocean::OceanDesc& d, size_t count) {
    std::vector<std::pair<uint32_t, uint32_t>> e;
    // perRow vertices a row, rows `stride` apart (the radial grid pads its rings: RadialGrid::ringStride).
    auto addRowMajor = [&](size_t first, size_t perRow, size_t stride, size_t rows) {
        for (size_t r = 0; r < rows; ++r)
            for (size_t c = 0; c < perRow; ++c) {
                const size_t i = first + r * stride + c;
                if (c + 1 < perRow && i + 1 < count)
                    e.emplace_back(uint32_t(i), uint32_t(i + 1));
                if (r + 1 < rows && i + stride < count)
                    e.emplace_back(uint32_t(i), uint32_t(i + stride));
            }
    };
    if (d.gridKind == ocean::GridKind::Radial) {
        // Rings of M + 1 vertices, padded to the grid's stride (RadialGrid::vertexIndex).
        const size_t stride = static_cast<size_t>(ocean::RadialGrid::ringStrideFor(d.grid.segments));
        addRowMajor(1, static_cast<size_t>(d.grid.segments) + 1, stride, (count - 1) / stride);
    } else {
        const size_t perRow = static_cast<size_t>(d.projectedGrid.resolutionX);
        addRowMajor(0, perRow, perRow, count / perRow);
    }
    return e;
}

struct VertexError {
    double midRms = 0.0, nodeRms = 0.0;
    size_t samples = 0;
};

// Height error of the rendered mesh against the continuous reference. The mesh is the piecewise-linear image
// of the grid parameterisation g -> g + displacementAt(g); at an edge midpoint it holds the average of the
// two vertices, compared with the reference at the parameter midpoint (vertical component). The Earth-
// curvature drop is added back per vertex (it is exact there and not a knob's error).
VertexError vertexError(ocean::OceanRenderer& renderer, ecs::Registry& registry, ecs::Entity e,
                        const ocean::OceanComponent& ocean, const gl::FrameTargets& targets,
                        size_t maxSamples) {
    double sumMid = 0.0, sumNode = 0.0;
    size_t n = 0;
    for (const View& view : views()) {
        const ocean::OceanFrame frame = makeFrame(view.pose, targets, TIME);
        const auto verts = ocean::debug::displacedVertices(renderer, registry, e, frame);
        const glm::dvec3 cam = view.pose.position;
        const double rMax = ocean.desc.grid.rMax;
        auto height = [&](const ocean::debug::DisplacedVertex& v) {
            const double r = std::hypot(double(v.grid.x), double(v.grid.y));
            return double(v.position.z) + cam.z + ocean::curvatureDrop(r);
        };
        std::vector<std::pair<uint32_t, uint32_t>> inView;
        for (const auto& [a, b] : gridEdges(ocean.desc, verts.size())) {
            const auto &va = verts[a], &vb = verts[b];
            if (std::hypot(double(va.grid.x), double(va.grid.y)) > rMax ||
                std::hypot(double(vb.grid.x), double(vb.grid.y)) > rMax)
                continue;
            if (inFrustum(frame.camera.viewProj, 0.5f * (va.position + vb.position)))
                inView.emplace_back(a, b);
        }
        // A deterministic, evenly strided subset keeps the FFT's O(N^2)-per-point direct sum affordable.
        const size_t stride = std::max<size_t>(1, (inView.size() + maxSamples - 1) / maxSamples);
        for (size_t k = 0; k < inView.size(); k += stride) {
            const auto &va = verts[inView[k].first], &vb = verts[inView[k].second];
            const glm::dvec2 ga = glm::dvec2(cam) + glm::dvec2(va.grid);
            const glm::dvec2 gb = glm::dvec2(cam) + glm::dvec2(vb.grid);
            const double refMid = ocean.surface->displacementAt(0.5 * (ga + gb), TIME).z;
            const double refNode = ocean.surface->displacementAt(ga, TIME).z;
            const double dm = 0.5 * (height(va) + height(vb)) - refMid;
            const double dn = height(va) - refNode;
            sumMid += dm * dm;
            sumNode += dn * dn;
            ++n;
        }
    }
    VertexError out;
    out.samples = n;
    if (n > 0) {
        out.midRms = std::sqrt(sumMid / double(n));
        out.nodeRms = std::sqrt(sumNode / double(n));
    }
    return out;
}

// Interior vertices of the mesh with their four grid neighbours {i, left, right, down, up}, in the vertex
// order of gridEdges(): along a ring/row (left, right) and across rings/rows (down, up).
std::vector<std::array<uint32_t, 5>> gridStencils(const ocean::OceanDesc& d, size_t count) {
    std::vector<std::array<uint32_t, 5>> out;
    auto rowMajor = [&](size_t first, size_t perRow, size_t stride, size_t rows) {
        for (size_t r = 1; r + 1 < rows; ++r)
            for (size_t c = 1; c + 1 < perRow; ++c) {
                const size_t i = first + r * stride + c;
                if (i + stride < count)
                    out.push_back({uint32_t(i), uint32_t(i - 1), uint32_t(i + 1), uint32_t(i - stride),
                                   uint32_t(i + stride)});
            }
    };
    if (d.gridKind == ocean::GridKind::Radial) {
        // Rings of M + 1 vertices, padded to the grid's stride (RadialGrid::vertexIndex).
        const size_t stride = static_cast<size_t>(ocean::RadialGrid::ringStrideFor(d.grid.segments));
        rowMajor(1, static_cast<size_t>(d.grid.segments) + 1, stride, (count - 1) / stride);
    } else {
        const size_t perRow = static_cast<size_t>(d.projectedGrid.resolutionX);
        rowMajor(0, perRow, perRow, count / perRow);
    }
    return out;
}

struct NormalError {
    double meanDeg = 0.0, p95Deg = 0.0;
    size_t samples = 0;
};

// The normal the rendered mesh has at a vertex: the cross product of the central differences of its four
// grid neighbours (the displaced positions from transform feedback, curvature drop added back like the
// height error), which is the normal of the mesh's tangent plane there (second-order accurate in the grid
// spacing where the mesh resolves the waves). Reference: the continuous displaced surface's unit normal at
// the same grid point, N = dP/dx x dP/dy for P(g) = g + displacementAt(g): SurfaceModel::normalAt for
// Gerstner and FFT (exact cross products, GerstnerWaves.cpp/FftOcean.cpp); for octaves normalize(-dH/dx,
// -dH/dy, 1) of the DISPLACED octaves only (heightAndGradient(p, t, displacedOctaves)), because the
// octave model's normalAt adds the lighting-only octaves that never move a vertex. Statistics over the
// same in-view (frustum, r <= rMax) vertices and 3 cameras as the height error; p95 by nth_element.
NormalError normalError(ocean::OceanRenderer& renderer, ecs::Registry& registry, ecs::Entity e,
                        const ocean::OceanComponent& ocean, const gl::FrameTargets& targets,
                        size_t maxSamples) {
    const auto* octaves = dynamic_cast<const ocean::HeightOctaves*>(ocean.surface.get());
    std::vector<double> angles;
    for (const View& view : views()) {
        const ocean::OceanFrame frame = makeFrame(view.pose, targets, TIME);
        const auto verts = ocean::debug::displacedVertices(renderer, registry, e, frame);
        const glm::dvec3 cam = view.pose.position;
        const double rMax = ocean.desc.grid.rMax;
        auto radius = [&](uint32_t i) {
            return std::hypot(double(verts[i].grid.x), double(verts[i].grid.y));
        };
        auto pos = [&](uint32_t i) {
            const glm::dvec3 p(verts[i].position);
            return glm::dvec3(p.x, p.y, p.z + ocean::curvatureDrop(radius(i)));
        };
        std::vector<std::array<uint32_t, 5>> inView;
        for (const auto& st : gridStencils(ocean.desc, verts.size())) {
            if (std::any_of(st.begin(), st.end(), [&](uint32_t i) { return radius(i) > rMax; }))
                continue;
            if (inFrustum(frame.camera.viewProj, verts[st[0]].position))
                inView.push_back(st);
        }
        const size_t stride = std::max<size_t>(1, (inView.size() + maxSamples - 1) / maxSamples);
        for (size_t k = 0; k < inView.size(); k += stride) {
            const auto& st = inView[k];
            glm::dvec3 n = glm::cross(pos(st[2]) - pos(st[1]), pos(st[4]) - pos(st[3]));
            if (glm::length(n) == 0.0)
                continue; // coincident neighbours (none in these grids; guards the normalisation)
            n = glm::normalize(n.z < 0.0 ? -n : n);
            const glm::dvec2 world = glm::dvec2(cam) + glm::dvec2(verts[st[0]].grid);
            glm::dvec3 ref;
            if (octaves) {
                const glm::dvec3 hg =
                    octaves->heightAndGradient(world, TIME, ocean.desc.octaves.displacedOctaves);
                ref = glm::normalize(glm::dvec3(-hg.y, -hg.z, 1.0));
            } else {
                ref = ocean.surface->normalAt(world, TIME);
            }
            angles.push_back(std::acos(std::clamp(glm::dot(n, ref), -1.0, 1.0)) * 180.0 / std::numbers::pi);
        }
    }
    NormalError out;
    out.samples = angles.size();
    if (angles.empty())
        return out;
    double sum = 0.0;
    for (double a : angles)
        sum += a;
    out.meanDeg = sum / double(angles.size());
    const size_t k95 = static_cast<size_t>(std::ceil(0.95 * double(angles.size()))) - 1;
    std::nth_element(angles.begin(), angles.begin() + static_cast<std::ptrdiff_t>(k95), angles.end());
    out.p95Deg = angles[k95];
    return out;
}

// Scene-linear RGB of the three views, concatenated.
std::vector<float> renderViews(ocean::OceanRenderer& renderer, ecs::Registry& registry,
                               const gl::FrameTargets& targets) {
    std::vector<float> all, rgba;
    for (const View& view : views()) {
        render(renderer, registry, makeFrame(view.pose, targets, TIME));
        targets.readScene(rgba);
        for (size_t i = 0; i < rgba.size(); i += 4)
            all.insert(all.end(), {rgba[i], rgba[i + 1], rgba[i + 2]});
    }
    return all;
}

std::pair<double, double> imageError(const std::vector<float>& a, const std::vector<float>& ref) {
    double sum = 0.0, sumClamped = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        const double d = double(a[i]) - double(ref[i]);
        const double dc = std::clamp(double(a[i]), 0.0, 1.0) - std::clamp(double(ref[i]), 0.0, 1.0);
        sum += d * d;
        sumClamped += dc * dc;
    }
    const double rmse = std::sqrt(sum / double(a.size()));
    const double mseClamped = sumClamped / double(a.size());
    const double psnr =
        mseClamped > 0.0 ? 10.0 * std::log10(1.0 / mseClamped) : std::numeric_limits<double>::infinity();
    return {rmse, psnr};
}

// Median of `frames` timed renders of the mid view (t advances 1/60 s per frame so time-dependent passes,
// e.g. the FFT, do their work every frame). One untimed frame first absorbs uploads and shader builds.
double timeRender(ocean::OceanRenderer& renderer, ecs::Registry& registry, const gl::FrameTargets& targets,
                  gl::GpuTimer& timer, int frames) {
    const Pose pose = views()[1].pose;
    render(renderer, registry, makeFrame(pose, targets, TIME));
    glFinish();
    const size_t before = timer.samples().size();
    for (int i = 0; i < frames; ++i) {
        timer.begin();
        render(renderer, registry, makeFrame(pose, targets, TIME + i / 60.0));
        timer.end();
        glFinish();
    }
    timer.drain();
    std::vector<double> s(timer.samples().begin() + static_cast<std::ptrdiff_t>(before),
                          timer.samples().end());
    if (s.empty())
        return std::numeric_limits<double>::quiet_NaN();
    std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2), s.end());
    return s[s.size() / 2];
}

// Pareto front per model in (image_rmse, ms_median): not dominated by a setting that is no worse in both
// and better in one.
void markPareto(std::vector<Result>& rs) {
    for (Result& a : rs) {
        a.pareto = true;
        for (const Result& b : rs) {
            if (&a == &b || a.setting.desc.model != b.setting.desc.model)
                continue;
            if (b.imageRmse <= a.imageRmse && b.msMedian <= a.msMedian &&
                (b.imageRmse < a.imageRmse || b.msMedian < a.msMedian)) {
                a.pareto = false;
                break;
            }
        }
    }
}

// gnuplot double-quoted string literal: backslash and quote escaped, a newline in s written as \n.
std::string gpQuote(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '\n')
            out += "\\n";
        else if (c == '"' || c == '\\')
            out += std::string("\\") + c;
        else
            out += c;
    }
    return out + "\"";
}

// Writes accuracy.dat (per model: block 2m = every setting with image RMSE > 0 — the references' 0 is off a
// log axis — and block 2m+1 = its Pareto front by ms, each row "ms rmse label stagger") and accuracy.gp,
// which draws accuracy.png from it: image RMSE against median ms, log-log, one colour per model, the Pareto
// points filled, joined and labelled "knob=value". Paths are relative: `cd DIR && gnuplot accuracy.gp`
// re-draws the plot anywhere (the H100 machine has no gnuplot).
void writePlotFiles(const std::string& dir, const std::vector<Result>& rs, const std::string& clock,
                    const std::string& renderer) {
    std::ostringstream dat, gp; // written whole (writeFileAtomically): a killed run leaves no half a plot
    const std::map<std::string, std::string> colour = {
        {"octaves", "#1f77b4"}, {"gerstner", "#2ca02c"}, {"fft", "#d62728"}};
    std::vector<std::string> plots;
    int block = 0;
    std::vector<ocean::SurfaceKind> models;
    for (const Result& r : rs)
        if (std::find(models.begin(), models.end(), r.setting.desc.model) == models.end())
            models.push_back(r.setting.desc.model);
    for (ocean::SurfaceKind m : models) {
        const std::string name = modelName(m);
        const std::string rgb = gpQuote(colour.count(name) ? colour.at(name) : "#000000");
        const std::string lc = "lc rgb " + rgb;
        std::vector<const Result*> all, front;
        for (const Result& r : rs)
            if (r.setting.desc.model == m && r.imageRmse > 0.0 && std::isfinite(r.imageRmse) &&
                std::isfinite(r.msMedian) && r.msMedian > 0.0) {
                all.push_back(&r);
                if (r.pareto)
                    front.push_back(&r);
            }
        std::sort(front.begin(), front.end(),
                  [](const Result* a, const Result* b) { return a->msMedian < b->msMedian; });
        for (const auto* points : {&all, &front}) {
            dat << "# " << name << (points == &all ? ": every setting with image RMSE > 0" : ": Pareto front")
                << "; ms image_rmse label stagger\n";
            for (size_t k = 0; k < points->size(); ++k) {
                const Result* r = (*points)[k];
                // stagger 0, 1, 2 in turn lifts the label by 1.15^(stagger - 1), so neighbours on the
                // front (often equal RMSE, close ms) do not print over each other.
                dat << num(r->msMedian) << ' ' << num(r->imageRmse) << " \""
                    << (r->setting.knob == "baseline" ? std::string("baseline")
                                                      : r->setting.knob + "=" + r->setting.value)
                    << "\" " << k % 3 << "\n";
            }
            dat << "\n\n";
        }
        if (!all.empty())
            plots.push_back("'accuracy.dat' index " + std::to_string(block) +
                            " using 1:2 with points pt 6 ps 1.3 " + lc + " title " + gpQuote(name));
        if (!front.empty()) {
            plots.push_back("'' index " + std::to_string(block + 1) +
                            " using 1:2 with linespoints pt 7 ps 1.8 lw 1.5 " + lc + " title " +
                            gpQuote(name + " Pareto front"));
            plots.push_back(
                "'' index " + std::to_string(block + 1) +
                " using 1:($2*1.15**($4-1)):3 with labels left offset 0.8,0 font ',9' textcolor rgb " + rgb +
                " notitle");
        }
        block += 2;
    }
    gp << "# accuracy.gp, written by pacifica-accuracy: draws accuracy.png from accuracy.dat\n"
       << "# (cd into this directory, then: gnuplot accuracy.gp)\n"
       << "set terminal pngcairo size 1400,900 font 'DejaVu Sans,11' noenhanced\n"
       << "set output 'accuracy.png'\n"
       << "set title "
       << gpQuote("Pacifica accuracy sweep: image error vs cost - " + renderer + " (" + clock +
                  ")\nfilled and joined: each model's Pareto front; references (RMSE 0) are "
                  "off the log axis")
       << "\n"
       << "set logscale xy\nset xlabel " << gpQuote("median ms per frame (" + clock + ")") << "\nset ylabel "
       << gpQuote("image RMSE vs the model's reference (scene-linear RGB)") << "\n"
       << "set grid xtics ytics mxtics mytics\nset key outside right top\n"
       << "plot ";
    for (size_t i = 0; i < plots.size(); ++i)
        gp << (i ? ", \\\n     " : "") << plots[i];
    gp << "\n";
    writeFileAtomically(dir + "/accuracy.dat", dat.str());
    writeFileAtomically(dir + "/accuracy.gp", gp.str());
}

struct Args {
    std::string outDir = "accuracy";
    bool quick = false;
    int width = 320, height = 180, frames = 15;
    bool framesGiven = false;
    std::vector<std::string> knobs;
    std::string commandLine;
};

std::optional<int> parseArgs(int argc, char** argv, Args& a) {
    CLI::App app{"pacifica-accuracy: error and cost of the ocean's quality knobs (docs/ACCURACY.md)",
                 "pacifica-accuracy"};
    app.add_option("--out", a.outDir, "output directory (accuracy.csv, accuracy.md, accuracy.png)");
    app.add_flag("--quick", a.quick, "tiny sweep for the test: baseline + 3 settings, 160x90, 3 frames");
    app.add_option("--knob", a.knobs,
                   "only this knob (repeatable; e.g. min_ring_pixels, grid, vertex_filter): each model's "
                   "reference and baseline and that knob's settings");
    app.add_option("--width", a.width, "render width")->check(CLI::Range(16, 4096));
    app.add_option("--height", a.height, "render height")->check(CLI::Range(16, 4096));
    app.add_option("--frames", a.frames, "timed frames per setting (default 15; 5 on software GL)")
        ->check(CLI::Range(1, 1000));
    if (const auto code = bench::parseCommandLine(app, argc, argv))
        return code;
    a.framesGiven = app.count("--frames") > 0;
    if (a.quick) {
        a.width = 160;
        a.height = 90;
        a.frames = 3;
    }
    a.commandLine = bench::commandLine(argc, argv);
    return std::nullopt;
}

/// The sweep's settings, or with --knob only the references, baselines and that knob's.
std::vector<Setting> selectSettings(const Args& a) {
    std::vector<Setting> settings = sweep(a.quick);
    if (a.knobs.empty())
        return settings;
    std::erase_if(settings, [&](const Setting& st) {
        return st.knob != "reference" && st.knob != "baseline" &&
               std::find(a.knobs.begin(), a.knobs.end(), st.knob) == a.knobs.end();
    });
    size_t matched = 0;
    for (const Setting& st : settings)
        matched += st.knob != "reference" && st.knob != "baseline";
    if (matched == 0)
        throw std::runtime_error("--knob: no setting has knob '" + a.knobs.front() + "'");
    return settings;
}

/// One renderer measuring every setting against its model's reference (measured first).
struct Sweep {
    const Args& a;
    int frames;
    gl::GpuTimer& timer;
    gl::FrameTargets targets;
    ocean::OceanRenderer renderer;
    ecs::Registry registry;
    std::vector<Result> results;
    std::map<ocean::SurfaceKind, std::vector<float>> refImages;
    std::map<ocean::SurfaceKind, double> refHs;

    Sweep(const Args& args, int f, gl::GpuTimer& t)
        : a(args), frames(f), timer(t), targets(args.width, args.height) {}
    void run(const Setting& s, bool isReference);
    void errors(Result& r, const ocean::OceanComponent& oc);
};

/// The vertex and normal errors with culling off: every vertex displaced, so every in-view vertex compares.
void Sweep::errors(Result& r, const ocean::OceanComponent& oc) {
    const ocean::SurfaceKind m = oc.desc.model;
    ocean::OceanComponent uncut = oc;
    uncut.desc.cullVertices = false;
    const ecs::Entity ev = registry.create();
    registry.emplace<ocean::OceanComponent>(ev, uncut);
    const size_t maxSamples =
        m == ocean::SurfaceKind::Fft
            ? std::clamp<size_t>(size_t(400.0 * std::pow(256.0 / oc.desc.fft.size, 2)), 400, 4000)
            : (a.quick ? 4000 : 20000);
    const VertexError ve = vertexError(renderer, registry, ev, uncut, targets, maxSamples / 3);
    r.vertexRms = ve.nodeRms / refHs.at(m);
    r.meshRms = ve.midRms / refHs.at(m);
    r.samples = ve.samples;
    const NormalError ne = normalError(renderer, registry, ev, uncut, targets, maxSamples / 3);
    r.normalMeanDeg = ne.meanDeg;
    r.normalP95Deg = ne.p95Deg;
    r.normalSamples = ne.samples;
    registry.destroy(ev);
}

void Sweep::run(const Setting& s, bool isReference) {
    const auto t0 = std::chrono::steady_clock::now();
    const ecs::Entity e = registry.create();
    const ocean::OceanComponent& oc = registry.emplace<ocean::OceanComponent>(e, ocean::makeOcean(s.desc));
    const ocean::SurfaceKind m = s.desc.model;
    if (isReference)
        refHs[m] = oc.surface->significantWaveHeight();
    Result r{s};
    r.msMedian = timeRender(renderer, registry, targets, timer, frames);
    r.vertices = renderer.lastStats().vertices;
    const std::vector<float> img = renderViews(renderer, registry, targets);
    if (isReference)
        refImages[m] = img;
    std::tie(r.imageRmse, r.psnrDb) = imageError(img, refImages.at(m));
    errors(r, oc);
    registry.destroy(e);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr,
                 "[%s] %s=%s: vertex %.4g Hs, normal %.3g/%.3g deg, image rmse %.4g, %.3f ms (%.1f s)\n",
                 modelName(m), s.knob.c_str(), s.value.c_str(), r.vertexRms, r.normalMeanDeg, r.normalP95Deg,
                 r.imageRmse, r.msMedian, secs);
    results.push_back(r);
}

std::string csvReport(const std::vector<Result>& results, const std::string& clock,
                      const std::string& renderer) {
    std::ostringstream csv;
    csv << "knob,value,model,vertex_rms_over_hs,mesh_rms_over_hs,normal_mean_deg,normal_p95_deg,normal_"
           "samples,samples,image_rmse,psnr_db,ms_median,vertices,clock,renderer,pareto\n";
    for (const Result& r : results)
        csv << r.setting.knob << ',' << csvQuote(r.setting.value) << ',' << modelName(r.setting.desc.model)
            << ',' << num(r.vertexRms) << ',' << num(r.meshRms) << ',' << num(r.normalMeanDeg) << ','
            << num(r.normalP95Deg) << ',' << r.normalSamples << ',' << r.samples << ',' << num(r.imageRmse)
            << ',' << num(r.psnrDb) << ',' << num(r.msMedian) << ',' << r.vertices << ',' << clock << ','
            << csvQuote(renderer) << ',' << (r.pareto ? 1 : 0) << '\n';
    return csv.str();
}

std::string markdownReport(const std::vector<Result>& results, const Args& a, int frames,
                           const std::string& clock, const std::string& renderer) {
    std::ostringstream md;
    md << "# Pacifica accuracy sweep\n\n"
       << "- GL_RENDERER: " << renderer << "\n- clock: " << clock << "\n- date: " << bench::utcNow()
       << "\n- command: `" << a.commandLine << "`\n- image: " << a.width << "x" << a.height
       << " scene-linear RGB of 3 views vs the model's reference; PSNR peak 1.0 after clamping to [0, "
          "1]\n"
       << "- vertex error: RMS height error at the vertices (mesh: at grid-edge midpoints) / Hs of the "
          "reference, t = "
       << TIME << " s, in-frustum, r <= rMax, culling off\n"
       << "- normal error: angle between the mesh normal at interior vertices (central differences of "
          "the "
          "4 neighbouring vertices) and the continuous displaced surface's normal, degrees (mean, p95)\n"
       << "- ms: median of " << frames << " frames of render + glFinish\n"
       << "- plot: accuracy.png (gnuplot, from accuracy.gp + accuracy.dat): image RMSE vs ms, Pareto "
          "fronts "
          "marked\n\n"
       << "| model | knob | value | vertex rms/Hs | mesh rms/Hs | normal mean° | normal p95° | image "
          "RMSE | "
          "PSNR dB | ms | vertices | pareto |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Result& r : results)
        md << "| " << modelName(r.setting.desc.model) << " | " << r.setting.knob << " | " << r.setting.value
           << " | " << num(r.vertexRms, 3) << " | " << num(r.meshRms, 3) << " | " << num(r.normalMeanDeg, 3)
           << " | " << num(r.normalP95Deg, 3) << " | " << num(r.imageRmse, 3) << " | " << num(r.psnrDb, 3)
           << " | " << num(r.msMedian, 3) << " | " << r.vertices << " | " << (r.pareto ? "**yes**" : "")
           << " |\n";
    return md.str();
}

} // namespace

int main(int argc, char** argv) {
    Args a;
    if (const auto code = parseArgs(argc, argv, a))
        return *code;
    return bench::runGlBench("pacifica-accuracy", a.outDir, {"accuracy.png"}, [&](gl::GlContext& context) {
        const gl::ContextInfo info = context.info();
        gl::GpuTimer timer(info);
        // llvmpipe renders a 256 x 512 grid in ~0.2 s: 5 frames there keep the full sweep near 3 minutes.
        const int frames = !a.quick && !a.framesGiven && info.software ? 5 : a.frames;
        Sweep sweepRun(a, frames, timer);
        const std::vector<Setting> settings = selectSettings(a);
        std::vector<ocean::SurfaceKind> models;
        for (const Setting& s : settings)
            if (std::find(models.begin(), models.end(), s.desc.model) == models.end())
                models.push_back(s.desc.model);
        for (ocean::SurfaceKind m : models) {
            sweepRun.run({"reference", "512x1024 bilinear no-cull all-octaves N=256", referenceDesc(m)},
                         true);
            for (const Setting& s : settings)
                if (s.desc.model == m)
                    sweepRun.run(s, false);
        }
        std::vector<Result>& results = sweepRun.results;
        markPareto(results);
        writeFileAtomically(a.outDir + "/accuracy.csv", csvReport(results, timer.clockName(), info.renderer));
        writeFileAtomically(a.outDir + "/accuracy.md",
                            markdownReport(results, a, frames, timer.clockName(), info.renderer));
        writePlotFiles(a.outDir, results, timer.clockName(), info.renderer);
        const bool plotted = bench::runGnuplot(a.outDir, "accuracy.gp", "accuracy.png");
        std::cout << "wrote " << a.outDir << "/accuracy.csv, accuracy.md" << (plotted ? ", accuracy.png" : "")
                  << " (" << results.size() << " settings, " << info.renderer << ", " << timer.clockName()
                  << ")\n";
        if (!plotted)
            std::cerr
                << "pacifica-accuracy: gnuplot is not installed, so accuracy.png was not drawn: install "
                   "gnuplot-nox, then run `gnuplot accuracy.gp` in "
                << a.outDir << "\n";
        return 0;
    });
}
