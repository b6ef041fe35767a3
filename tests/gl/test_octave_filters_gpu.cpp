// GPU vs CPU for every vertex displacement path of the octave model (GPU Gems 2 §18.2.4 filters, listings
// 18-2/18-3, and the §18.2.5 combined two-pass path): modelDisplacement() evaluated by the GLSL through
// transform feedback (SurfaceProbe) equals HeightOctaves::heightSeenFrom() in double at a few thousand points
// out to 40 km, for cameras at the origin and 10^7 m away, at t = 0 and 10^6 s. Also measures (does not
// assert) each path's vertex cost on the current GL renderer.
#include "engine/Time.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GpuTimer.h"
#include "engine/gl/Shader.h"
#include "gpu/OctavesGpu.h"
#include "gpu/SurfaceProbe.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"
#include "ocean/RadialGrid.h" // RadialGridDesc defaults

#include <epoxy/gl.h>

#include "GlLayerTest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <string>

using namespace pacifica;
using ocean::HeightOctaves;
using ocean::HeightOctavesDesc;
using ocean::VertexFilter;

namespace {

struct Mode {
    VertexFilter filter;
    bool combined;
};

std::string modeName(const Mode& m) {
    std::string s = ocean::toString(m.filter);
    std::replace(s.begin(), s.end(), '-', '_');
    return s + (m.combined ? "_combined" : "");
}

/// Camera-relative probe points: radii log-uniform from 0.1 m to 40 km (the radial grid's range), random
/// directions, plus the extreme corners of the displaced disc.
std::vector<glm::vec2> probePoints(int count) {
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> logR(std::log(0.1), std::log(40000.0)),
        angle(0.0, 2.0 * std::numbers::pi);
    std::vector<glm::vec2> p = {{0.0f, 0.0f}, {40000.0f, 0.0f}, {0.0f, -40000.0f}, {-28284.0f, 28284.0f}};
    while (static_cast<int>(p.size()) < count) {
        const double r = std::exp(logR(rng)), a = angle(rng);
        p.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)));
    }
    return p;
}

/// Nearest only: whether the GPU's float tile coordinate of a lookup at `world`, dist metres from the camera,
/// may land across a texel edge from the CPU's double one. rel * B + fract(camera * B) in float is off by at
/// most about (dist * B + 1) * 2^-22 tile (B's rounding, the product's, the sum's: 1.5 ulp of dist * B);
/// the tolerance takes twice that, in texels.
bool nearTexelEdge(const HeightOctaves& s, const glm::dvec2& world, double dist) {
    const HeightOctavesDesc& d = s.desc();
    for (int i = 0; i < d.displacedOctaves; ++i) {
        const double b = 1.0 / d.octaves[static_cast<size_t>(i)].tileSize;
        const double tol = (dist * b + 1.0) * std::ldexp(1.0, -21) * d.mapSize;
        for (double c : {world.x, world.y}) {
            const double p = wrapPhase(c * b, 1.0) * d.mapSize;
            if (std::abs(p - std::round(p)) <= tol)
                return true;
        }
    }
    return false;
}

/// Whether any Nearest lookup behind the displacement at `world` is near a texel edge: the point itself
/// (per-vertex path) or one of the four combined nodes around it (HeightOctaves::combinedHeight's formula).
bool lookupsNearTexelEdge(const HeightOctaves& s, const glm::dvec2& world, const glm::dvec2& cam) {
    if (!s.desc().combinedDisplacement)
        return nearTexelEdge(s, world, glm::length(world - cam));
    const int k = s.combinedLevelFor(world - cam), n = s.desc().combinedSize;
    const double texel = s.combinedTexel(k);
    const glm::dvec2 origin = s.combinedOrigin(k, cam);
    const glm::dvec2 p =
        glm::clamp((world - origin) / texel + (n / 2 - 0.5), glm::dvec2(0.0), glm::dvec2(n - 1));
    const glm::dvec2 p0 = glm::min(glm::floor(p), glm::dvec2(n - 2));
    for (const glm::dvec2 corner : {glm::dvec2(0, 0), glm::dvec2(1, 0), glm::dvec2(0, 1), glm::dvec2(1, 1)}) {
        const glm::dvec2 node = origin + (p0 + corner + (0.5 - n / 2)) * texel;
        if (nearTexelEdge(s, node, glm::length(node - cam)))
            return true;
    }
    return false;
}

class OctaveFiltersGpu : public gltest::GlTestOf<::testing::TestWithParam<Mode>> {
protected:
};

TEST_P(OctaveFiltersGpu, GpuMatchesTheDoubleCpuPathOutTo40km) {
    const Mode mode = GetParam();
    HeightOctavesDesc desc;
    desc.vertexFilter = mode.filter;
    desc.combinedDisplacement = mode.combined;
    const auto surface = std::make_shared<const HeightOctaves>(desc);
    ocean::OctavesGpu gpu(surface);

    // Work accounting: textures counted once; every update mixes the lighting maps to its time (1 pass),
    // plus the combine pass when enabled.
    const ocean::SurfaceGpuStats first = gpu.update(0.0, glm::dvec3(0.0));
    EXPECT_EQ(first.uploads, static_cast<int>(desc.octaves.size()) + 1); // the maps + the filter's texture
    EXPECT_EQ(first.computePasses, mode.combined ? 2 : 1);
    const ocean::SurfaceGpuStats second = gpu.update(0.0, glm::dvec3(0.0));
    EXPECT_EQ(second.uploads, 0);
    EXPECT_EQ(second.computePasses, mode.combined ? 2 : 1);
    EXPECT_LE(gpu.unitsUsed(), 12); // OceanRenderer's lighting textures start at unit 12

    // Bounds. Float: the GPU forms tile coordinates rel * B + fract(camera * B) in float; at 40 km that is
    // ~6e-5 tile for the 61 m octave, times its steepest slope: ~3e-4 m (test_ocean_gpu_cpu.cpp); the
    // combined path interpolates GPU node values with the same error. HardwareBilinear adds the CPU's
    // emulated 8-bit weight quantisation vs the renderer's own weights (hardwareBilinearBound()). Nearest
    // is discontinuous: where a lookup's double position lies within that float error of a texel edge
    // (lookupsNearTexelEdge) the GPU may take the neighbouring texel, a jump of up to one texel step per
    // axis and octave; everywhere else it must match like the others. (The combined nodes of levels 0-2
    // fall exactly on edges of the 61 m and 1109 m maps at regular intervals: 61 j / 128 = odd * 2^-3.)
    const double floatBound = 1e-3;
    double bound = floatBound;
    if (mode.filter == VertexFilter::HardwareBilinear)
        bound += surface->hardwareBilinearBound();
    double jump = 0.0;
    for (int i = 0; i < desc.displacedOctaves; ++i)
        jump += desc.octaves[static_cast<size_t>(i)].amplitude * 2.0 * surface->maxTexelStep(i);

    const std::vector<glm::vec2> rel = probePoints(3000);
    for (const glm::dvec3 camera :
         {glm::dvec3(0.0, 0.0, 30.0), glm::dvec3(1.0e7 + 0.37, -1.0e7 + 0.81, 30.0)}) {
        for (double t : {0.0, 1.0e6 + 0.123}) {
            const ocean::ProbeResult r = ocean::probeSurface(gpu, rel, camera, t);
            ASSERT_EQ(r.displacement.size(), rel.size());
            double worst = 0.0;
            double worstClear = 0.0; // Nearest: over points with no lookup near a texel edge
            size_t worstIndex = 0, outside = 0, ambiguous = 0;
            for (size_t i = 0; i < rel.size(); ++i) {
                const glm::vec3 d = r.displacement[i], l = r.lighting[i];
                ASSERT_TRUE(std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z) &&
                            std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z))
                    << "point " << i;
                ASSERT_EQ(d.x, 0.0f);
                ASSERT_EQ(d.y, 0.0f);
                const glm::dvec2 cam(camera);
                const double cpu = surface->heightSeenFrom(cam + glm::dvec2(rel[i]), t, cam);
                const double err = std::abs(double(d.z) - cpu);
                if (err > floatBound)
                    ++outside;
                if (mode.filter == VertexFilter::Nearest) {
                    if (lookupsNearTexelEdge(*surface, cam + glm::dvec2(rel[i]), cam))
                        ++ambiguous;
                    else
                        worstClear = std::max(worstClear, err);
                }
                if (err > worst) {
                    worst = err;
                    worstIndex = i;
                }
            }
            std::printf("[%-26s] camera %.3g t %.3g: max |GPU - CPU| = %.3g m at |rel| = %.0f m (%zu of %zu "
                        "points > 1 mm)",
                        modeName(mode).c_str(), camera.x, t, worst, glm::length(rel[worstIndex]), outside,
                        rel.size());
            if (mode.filter == VertexFilter::Nearest)
                std::printf("; %zu points near a texel edge, max elsewhere %.3g m", ambiguous, worstClear);
            std::printf("\n");
            RecordProperty("max_abs_error_m_" + std::to_string(camera.x > 1.0) + std::to_string(t > 1.0),
                           std::to_string(worst));
            if (mode.filter == VertexFilter::Nearest) {
                EXPECT_LE(worstClear, floatBound);
                EXPECT_LE(worst, floatBound + jump);
            } else {
                EXPECT_LE(worst, bound);
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    AllPaths, OctaveFiltersGpu,
    ::testing::Values(Mode{VertexFilter::Nearest, false}, Mode{VertexFilter::Bilinear, false},
                      Mode{VertexFilter::HardwareBilinear, false}, Mode{VertexFilter::Packed4Tap, false},
                      Mode{VertexFilter::Trilinear, false}, Mode{VertexFilter::Nearest, true},
                      Mode{VertexFilter::Bilinear, true}, Mode{VertexFilter::HardwareBilinear, true},
                      Mode{VertexFilter::Packed4Tap, true}, Mode{VertexFilter::Trilinear, true}),
    [](const ::testing::TestParamInfo<Mode>& p) { return modeName(p.param); });

class OctaveLightingGpu : public gltest::GlTest {};
class OctaveFilterCost : public gltest::GlTest {};

// The lighting maps are mixed to the frame's time once per frame (octaves_light_mix.comp) instead of per
// pixel: halfway between two time slices the lighting gradient is the mean of the two slices' (filtering is
// linear), up to the one rounding of the mix to half; at a slice's own instant it is that slice. One octave
// (61 m tile, 12 s loop, 32 slices: a slice every 0.375 s).
TEST_F(OctaveLightingGpu, LightingMapsFollowTimeLinearlyBetweenSlices) {
    HeightOctavesDesc desc;
    desc.octaves = {{61.0, 0.13, 12.0}};
    desc.displacedOctaves = 1;
    const auto surface = std::make_shared<const HeightOctaves>(desc);
    ocean::OctavesGpu gpu(surface);
    const std::vector<glm::vec2> rel = probePoints(500);
    const glm::dvec3 camera(1.0e7 + 0.37, -1.0e7 + 0.81, 30.0);
    const double slice = 12.0 / 32.0, t0 = 1.0e6 * 12.0 + 5.0 * slice; // whole loops: slice 5 exactly
    const ocean::ProbeResult a = ocean::probeSurface(gpu, rel, camera, t0);
    const ocean::ProbeResult b = ocean::probeSurface(gpu, rel, camera, t0 + slice);
    const ocean::ProbeResult m = ocean::probeSurface(gpu, rel, camera, t0 + 0.5 * slice);
    double scale = 0.0, worst = 0.0, change = 0.0;
    for (size_t i = 0; i < rel.size(); ++i)
        scale = std::max({scale, double(std::abs(a.lighting[i].x)), double(std::abs(a.lighting[i].y))});
    ASSERT_GT(scale, 0.0);
    for (size_t i = 0; i < rel.size(); ++i) {
        for (int c = 0; c < 2; ++c) {
            const double mean = 0.5 * (double(a.lighting[i][c]) + double(b.lighting[i][c]));
            worst = std::max(worst, std::abs(double(m.lighting[i][c]) - mean));
            change = std::max(change, std::abs(double(a.lighting[i][c]) - double(b.lighting[i][c])));
        }
    }
    std::printf(
        "lighting gradient: max |mid - mean of slices| = %.3g, max slice-to-slice change %.3g, scale %.3g\n",
        worst, change, scale);
    EXPECT_GT(change, 1e-2 * scale) << "the two slices differ, so the test can tell";
    EXPECT_LE(worst, 2e-3 * scale) << "one half rounding of the mixed map (2^-11 relative) and float noise";
}

// Living whitecaps: the foam height the shaders threshold (modelFoamInputs, from the lighting fetches) equals
// HeightOctaves::foamHeightAt in double, near the origin and 10^7 m away, at t = 17 s and 10^6 s. The default
// octaves; the probe runs in the vertex stage, so the lighting array is read at level 0 like the CPU's
// bilinear lookup. Bound: the mix to the frame's time is rounded to half (2^-11 of a memory of up to ~4
// unit heights, times A_i) plus the float tile coordinate at 40 km.
TEST_F(OctaveLightingGpu, FoamHeightMatchesTheCpu) {
    const auto surface = std::make_shared<const HeightOctaves>(HeightOctavesDesc{});
    ocean::OctavesGpu gpu(surface);
    const std::vector<glm::vec2> rel = probePoints(2000);
    for (const glm::dvec3 camera :
         {glm::dvec3(0.0, 0.0, 30.0), glm::dvec3(1.0e7 + 0.37, -1.0e7 + 0.81, 30.0)})
        for (double t : {17.0, 1.0e6 + 0.123}) {
            const ocean::ProbeResult r = ocean::probeSurface(gpu, rel, camera, t);
            ASSERT_EQ(r.foam.size(), rel.size());
            double worst = 0.0, largest = 0.0;
            for (size_t i = 0; i < rel.size(); ++i) {
                const double cpu = surface->foamHeightAt(glm::dvec2(camera) + glm::dvec2(rel[i]), t);
                ASSERT_TRUE(std::isfinite(r.foam[i].x)) << i;
                worst = std::max(worst, std::abs(double(r.foam[i].x) - cpu));
                largest = std::max(largest, cpu);
            }
            std::printf("foam height: camera %.3g t %.3g: max |GPU - CPU| = %.3g m (largest %.3f m)\n",
                        camera.x, t, worst, largest);
            EXPECT_GT(largest, 0.5);
            EXPECT_LE(worst, 3e-3);
        }
}

double minMs(const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
}

double medianMs(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// Points of a full-circle radial grid, r_i = a0 + a1 i^4 (§18.2.3) from the default 10 cm to 40 km, plus
/// the centre: the displaced vertices a draw of that grid shades.
std::vector<glm::vec2> radialGridPoints(int rings, int segments) {
    const ocean::RadialGridDesc d;
    const double a1 = (d.rMax - d.rMin) / std::pow(rings - 1.0, 4.0);
    std::vector<glm::vec2> p = {glm::vec2(0.0f)};
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const double r = d.rMin + a1 * std::pow(double(i), 4.0);
            const double a = 2.0 * std::numbers::pi * j / segments;
            p.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)));
        }
    return p;
}

/// Cost of each path: GPU time of a vertex-only transform-feedback draw of the default 256 x 512 radial
/// grid's displaced vertices (and, on hardware, of an 8x denser one: 131k vertices sit at the H100's
/// per-draw floor), and of the combine pass (update()) where there is one. gl::GpuTimer: GL timer queries
/// on hardware, wall clock around glFinish on llvmpipe (whose timer queries are wrong, docs/PLATFORM.md).
/// Minimum and median of 10 runs (the minimum is the least disturbed by other processes on a shared
/// machine); printed, not asserted.
TEST_F(OctaveFilterCost, VertexAndCombinePassTimePerPath) {
    std::vector<int> segments = {ocean::RadialGridDesc{}.segments};
    if (!info().software)
        segments.push_back(8 * segments[0]);
    const glm::dvec3 camera(1.0e7 + 0.37, -1.0e7 + 0.81, 30.0);
    const double time = 1.0e6 + 0.123;
    for (const int m : segments) {
        const std::vector<glm::vec2> rel = radialGridPoints(ocean::RadialGridDesc{}.rings, m);
        gl::Buffer input = gl::Buffer::create(rel.size() * sizeof(glm::vec2), rel.data());
        gl::Buffer output = gl::Buffer::create(rel.size() * sizeof(float), nullptr);
        gl::VertexArray vao = gl::VertexArray::create();
        glVertexArrayVertexBuffer(vao.id(), 0, input.id(), 0, sizeof(glm::vec2));
        glEnableVertexArrayAttrib(vao.id(), 0);
        glVertexArrayAttribFormat(vao.id(), 0, 2, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao.id(), 0, 0);
        gl::Texture color = gl::Texture::create2D(GL_RGBA8, 1, 1);
        gl::Framebuffer fbo = gl::Framebuffer::create();
        fbo.attachColor(0, color);

        std::printf("vertex cost, %zu displaced vertices (256 x %d grid), renderer %s, clock: %s\n",
                    rel.size(), m, info().renderer.c_str(), gl::GpuTimer(info()).clockName());
        std::printf(
            "| path | vertex draw ms (min / median) | combine pass ms (min / median) |\n|---|---|---|\n");
        for (const Mode mode : {Mode{VertexFilter::Nearest, false}, Mode{VertexFilter::Bilinear, false},
                                Mode{VertexFilter::HardwareBilinear, false},
                                Mode{VertexFilter::Packed4Tap, false}, Mode{VertexFilter::Trilinear, false},
                                Mode{VertexFilter::Bilinear, true}, Mode{VertexFilter::Trilinear, true}}) {
            HeightOctavesDesc desc;
            desc.vertexFilter = mode.filter;
            desc.combinedDisplacement = mode.combined;
            ocean::OctavesGpu gpu(std::make_shared<const HeightOctaves>(desc));
            std::vector<gl::ShaderSource> sources;
            sources.push_back({"<ocean constants>", ocean::shaderConstantDefines()});
            for (const std::string& f : gpu.glslFiles())
                sources.push_back({f, std::string(ocean::shaderText(f))});
            sources.push_back({"<cost.vert>", "layout(location = 0) in vec2 aRel;\nout float vHeight;\n"
                                              "void main() {\n    vHeight = modelDisplacement(aRel).z;\n"
                                              "    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n}\n"});
            gl::Program program =
                gl::buildProgram({{gl::ShaderStage::Vertex, sources}}, "octave filter cost", {"vHeight"});
            gl::StateGuard guard;
            glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo.id());
            gl::GpuTimer combineTimer(info()), drawTimer(info());
            for (int run = 0; run < 11; ++run) { // run 0: shader compilation and first-use costs
                combineTimer.begin();
                gpu.update(time, camera);
                combineTimer.end();
                glUseProgram(program.id());
                gpu.bind(program.id(), 0, time, camera);
                glBindVertexArray(vao.id());
                glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, output.id());
                glEnable(GL_RASTERIZER_DISCARD);
                drawTimer.begin();
                glBeginTransformFeedback(GL_POINTS);
                glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(rel.size()));
                glEndTransformFeedback();
                drawTimer.end();
                glDisable(GL_RASTERIZER_DISCARD);
                glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
            }
            combineTimer.drain();
            drawTimer.drain();
            ASSERT_EQ(drawTimer.samples().size(), 11u);
            const std::vector<double> drawMs(drawTimer.samples().begin() + 1, drawTimer.samples().end());
            const std::vector<double> combineMs(combineTimer.samples().begin() + 1,
                                                combineTimer.samples().end());
            char combine[64] = "-";
            if (mode.combined)
                std::snprintf(combine, sizeof combine, "%.2f / %.2f", minMs(combineMs), medianMs(combineMs));
            std::printf("| %s | %.2f / %.2f | %s |\n", modeName(mode).c_str(), minMs(drawMs),
                        medianMs(drawMs), combine);
            RecordProperty("draw_ms_" + modeName(mode) + "_" + std::to_string(rel.size()),
                           std::to_string(minMs(drawMs)));
            // The feedback buffer holds finite heights (the draw really ran).
            float h[4];
            glGetNamedBufferSubData(output.id(), 0, sizeof h, h);
            EXPECT_TRUE(std::isfinite(h[0]) && std::isfinite(h[3]));
        }
    }
}

} // namespace
