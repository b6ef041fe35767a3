// Compute shading (OceanDesc::computeShading, ctest labels gl, performance): the sea and sky lit by one
// compute pass over a G-buffer draw the same picture as the grids' fragment stage. Forward and compute
// frames of the same view are compared pixel by pixel in the host's own RGBA16F + D32F framebuffer: the
// depth the host gets is identical, and the colours differ little (measured on llvmpipe: at most 0.0104% of
// pixels by more than 2% in luminance, mean at most 0.0044%; the fog noise's footprint lacks its vertical
// part; the most at 2 m toward the sun). Views
// from 2 m to 10 km, at 10^7 m from the origin at t = 10^6 s, the three surface models, a scene with an
// explosion and a wake; without the sky the host's pixels stay untouched; a target it cannot use (a
// renderbuffer colour, 24-bit depth) is shaded forward.
#include "engine/Ecs.h"
#include "engine/Pose.h"
#include "engine/Space.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"
#include "ocean/OceanDebug.h"
#include "ocean/OceanHost.h"
#include "ocean/Presets.h"

#include "OceanTestFrame.h"

#include "GlLayerTest.h"
#include <epoxy/gl.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

using namespace pacifica;
using namespace pacifica::ocean;

namespace {

constexpr int W = 320, H = 180;

/// A host's framebuffer: RGBA16F colour and 32-bit float depth textures (as engine's FrameTargets), or a
/// renderbuffer colour (which images cannot store).
struct HostTarget {
    gl::Texture color, depth;
    GLuint colorRenderbuffer = 0;
    gl::Framebuffer fbo = gl::Framebuffer::create();
    explicit HostTarget(bool renderbufferColor = false, GLenum depthFormat = GL_DEPTH_COMPONENT32F) {
        depth = gl::Texture::create2D(depthFormat, W, H);
        fbo.attachDepth(depth);
        if (renderbufferColor) {
            glCreateRenderbuffers(1, &colorRenderbuffer);
            glNamedRenderbufferStorage(colorRenderbuffer, GL_RGBA16F, W, H);
            glNamedFramebufferRenderbuffer(fbo.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                           colorRenderbuffer);
        } else {
            color = gl::Texture::create2D(GL_RGBA16F, W, H);
            fbo.attachColor(0, color);
        }
    }
    ~HostTarget() {
        if (colorRenderbuffer)
            glDeleteRenderbuffers(1, &colorRenderbuffer);
    }
    void clear(float value) const {
        const float c[4] = {value, value, value, 1.0f};
        glClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, c);
    }
    std::vector<float> readColor() const {
        std::vector<float> rgba(static_cast<size_t>(W) * H * 4);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo.id());
        glReadPixels(0, 0, W, H, GL_RGBA, GL_FLOAT, rgba.data());
        return rgba;
    }
    std::vector<float> readDepth() const {
        std::vector<float> d(static_cast<size_t>(W) * H);
        glGetTextureImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(d.size() * 4),
                          d.data());
        return d;
    }
};

OceanFrame frameAt(const HostTarget& target, const glm::dvec3& camera, double headingDeg, double pitchDeg,
                   double t) {
    return gltest::oceanFrameAt(camera, headingDeg, pitchDeg, t, target.fbo.id(), W, H);
}

/// The same, rolled by rollDeg.
OceanFrame bankedFrameAt(const HostTarget& target, const glm::dvec3& camera, double headingDeg,
                         double pitchDeg, double rollDeg, double t) {
    Pose pose;
    pose.position = camera;
    pose.headingDeg = headingDeg;
    pose.pitchDeg = pitchDeg;
    pose.rollDeg = rollDeg;
    OceanFrame f = frameAt(target, camera, headingDeg, pitchDeg, t);
    f.camera = makeCameraFrame(pose, f.camera.fovY, f.camera.aspect, f.camera.zNear);
    return f;
}

double luminance(const float* p) {
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

/// How far two frames of the same view differ: the share of pixels whose luminance differs by more than
/// 2% (relative, floor 0.01), the mean relative difference, and the largest.
struct Difference {
    double over2Percent = 0.0, mean = 0.0, max = 0.0;
    size_t nonFinite = 0;
};
Difference compare(const std::vector<float>& a, const std::vector<float>& b) {
    Difference d;
    size_t over = 0;
    const size_t n = a.size() / 4;
    for (size_t i = 0; i < n; ++i) {
        const double la = luminance(&a[i * 4]), lb = luminance(&b[i * 4]);
        if (!std::isfinite(la) || !std::isfinite(lb)) {
            ++d.nonFinite;
            continue;
        }
        const double rel = std::abs(la - lb) / std::max(lb, 0.01);
        over += rel > 0.02 ? 1 : 0;
        d.mean += rel;
        d.max = std::max(d.max, rel);
    }
    d.over2Percent = static_cast<double>(over) / static_cast<double>(n);
    d.mean /= static_cast<double>(n);
    return d;
}

class ComputeShadingGl : public gltest::GlTest {
protected:
    ecs::Registry registry;
    ecs::Entity oceanEntity = registry.create();
    OceanRenderer renderer;
    HostTarget target;
    int mDumped = 0; // PACIFICA_COMPUTE_DUMP=DIR: every compared pair as PPM

    void setOcean(OceanDesc desc) { registry.emplaceOrReplace<OceanComponent>(oceanEntity, makeOcean(desc)); }

    /// Renders `f` forward and compute-shaded; expects the same depth and colours within the bounds.
    void expectSameFrame(const OceanFrame& f, const std::string& what, double meanBound = 0.0001) {
        OceanDesc desc = registry.get<OceanComponent>(oceanEntity).desc;
        desc.computeShading = false;
        setOcean(desc);
        target.clear(0.0f);
        render(renderer, registry, f);
        EXPECT_FALSE(renderer.lastStats().computeShaded);
        const std::vector<float> forward = target.readColor();
        const std::vector<float> forwardDepth = target.readDepth();
        const int forwardPasses = renderer.lastStats().passes;

        desc.computeShading = true;
        setOcean(desc);
        target.clear(0.0f);
        render(renderer, registry, f);
        EXPECT_TRUE(renderer.lastStats().computeShaded) << what;
        // The sky's draw becomes the shading dispatch: as many passes, and by tiles (on llvmpipe, where
        // OceanDesc::shadeTiles Auto sorts them) the sorting pass and one dispatch per kind instead of one.
        EXPECT_EQ(renderer.lastStats().passes, forwardPasses + (renderer.lastStats().shadeTiled ? 4 : 0))
            << what;
        const std::vector<float> compute = target.readColor();
        const std::vector<float> computeDepth = target.readDepth();
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << what;

        EXPECT_TRUE(forwardDepth == computeDepth) << what << ": the host's depth must be the forward pass's";
        if (const char* dump = std::getenv("PACIFICA_COMPUTE_DUMP"); dump && *dump)
            for (const auto& [suffix, img] :
                 {std::pair{"forward", &forward}, std::pair{"compute", &compute}}) {
                std::string name = std::string(dump) + "/" + std::to_string(mDumped) + "_" + suffix + ".ppm";
                FILE* out = std::fopen(name.c_str(), "wb");
                std::fprintf(out, "P6 %d %d 255\n", W, H);
                for (int y = H - 1; y >= 0; --y)
                    for (int x = 0; x < W; ++x)
                        for (int c = 0; c < 3; ++c) {
                            const float v = (*img)[(static_cast<size_t>(y) * W + x) * 4 + c];
                            std::fputc(static_cast<int>(255.0f * std::pow(v / (1.0f + v), 1.0f / 2.2f)), out);
                        }
                std::fclose(out);
            }
        ++mDumped;
        const Difference d = compare(compute, forward);
        std::printf("[%s] pixels > 2%%: %.4f%%, mean %.5f%%, max %.3f%%\n", what.c_str(),
                    100.0 * d.over2Percent, 100.0 * d.mean, 100.0 * d.max);
        EXPECT_EQ(d.nonFinite, 0u) << what;
        EXPECT_LT(d.over2Percent, 0.0005) << what;
        EXPECT_LT(d.mean, meanBound) << what;
    }
};

struct View {
    const char* name;
    glm::dvec3 camera;
    double heading, pitch, time;
};

const View VIEWS[] = {
    {"20 m, the low grazing view", {2000.0, 0.0, 20.0}, 70.0, -3.0, 100.0},
    {"2 m toward the sun", {-300.0, 450.0, 2.0}, 200.0, -8.0, 17.25},
    {"500 m banked down", {0.0, 0.0, 500.0}, 30.0, -25.0, 40.0},
    {"10 km", {5000.0, -3000.0, 10000.0}, 120.0, -35.0, 60.0},
    {"10^7 m from the origin at t = 10^6 s", {1.0e7, -1.0e7, 30.0}, 300.0, -6.0, 1.0e6},
};

TEST(ComputeShadingDefaults, OnInThePresetsForwardInTheReference) {
    EXPECT_TRUE(OceanDesc{}.computeShading);
    for (Quality q : {Quality::Low, Quality::Medium, Quality::High})
        EXPECT_TRUE(oceanPreset(q).computeShading) << toString(q);
    EXPECT_FALSE(oceanPreset(Quality::Reference).computeShading);
}

TEST_F(ComputeShadingGl, OctaveSeaMatchesForwardShading) {
    setOcean(oceanPreset(Quality::High));
    for (const View& v : VIEWS)
        expectSameFrame(frameAt(target, v.camera, v.heading, v.pitch, v.time),
                        std::string("octaves, ") + v.name);
}

TEST_F(ComputeShadingGl, GerstnerAndFftSeasMatchForwardShading) {
    for (SurfaceKind kind : {SurfaceKind::Gerstner, SurfaceKind::Fft}) {
        OceanDesc desc;
        desc.model = kind;
        setOcean(desc);
        // The FFT sea's finest cascades (5 m and 37 m tiles, 4 cm and 29 cm texels) put texel-scale contrast
        // in every near pixel, where the two paths' footprints (the pixel quad's derivatives vs the
        // G-buffer's) pick mip levels a fraction apart: scattered pixels, mean 0.014 % at 20 m (llvmpipe; a
        // single 500 m tile measured 0.004 %), so its mean bound is 0.02 %.
        for (const View& v : {VIEWS[0], VIEWS[2]})
            expectSameFrame(frameAt(target, v.camera, v.heading, v.pitch, v.time),
                            std::string(toString(kind)) + ", " + v.name,
                            kind == SurfaceKind::Fft ? 0.0002 : 0.0001);
    }
}

/// A secondary grid for every effect in view (by default only those next to the eye get one).
OceanDesc withEveryGrid(OceanDesc desc) {
    desc.effectGrids.minAngularSize = desc.effectGrids.minAmplitudePixels = 0.0;
    desc.effectGrids.maxExplosionGrids = desc.effectGrids.maxWakeGrids = 1024;
    return desc;
}

TEST_F(ComputeShadingGl, EffectGridsMatchForwardShading) {
    setOcean(withEveryGrid(OceanDesc{}));
    ecs::EventQueue events;
    EffectsSystem fx(registry, events);
    const ecs::Entity ship = registry.create();
    registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 60.0});
    events.enqueue(AttachShipTrail{ship, WakeParams{}});
    events.enqueue(SpawnExplosion{{350.0, 150.0}, 55.0, 2.0});
    for (int i = 0; i <= 600; ++i) { // 60 s at 10 m/s heading east
        registry.get<Ship>(ship).position = {i * 1.0, 0.0};
        events.dispatch();
        fx.update(i * 0.1, {300.0, -400.0, 200.0});
    }
    const OceanFrame f = frameAt(target, {300.0, -400.0, 200.0}, 0.0, -35.0, 60.0);
    expectSameFrame(f, "an explosion and a wake");
    EXPECT_EQ(renderer.lastStats().wakes.draws, 1);
    EXPECT_EQ(renderer.lastStats().explosions.draws, 1);
}

TEST_F(ComputeShadingGl, WithoutTheSkyTheHostsPixelsStay) {
    OceanDesc desc;
    desc.drawSky = false;
    desc.computeShading = true;
    setOcean(desc);
    target.clear(7.0f);
    render(renderer, registry, frameAt(target, {0.0, 0.0, 20.0}, 0.0, 0.0, 10.0)); // horizon mid-screen
    ASSERT_TRUE(renderer.lastStats().computeShaded);
    const std::vector<float> rgba = target.readColor();
    auto at = [&](int x, int y) { return rgba[(static_cast<size_t>(y) * W + x) * 4]; }; // rows bottom-up
    EXPECT_EQ(at(W / 2, H - 5), 7.0f) << "sky pixel overwritten";
    EXPECT_LT(at(W / 2, 5), 1.0f) << "sea pixel not shaded";
}

TEST_F(ComputeShadingGl, TargetsItCannotUseAreShadedForward) {
    OceanDesc desc;
    desc.computeShading = true;
    setOcean(desc);
    // A renderbuffer colour (images cannot store it) and a 24-bit depth (too coarse to rebuild the surface).
    const HostTarget renderbuffer(true), depth24(false, GL_DEPTH_COMPONENT24);
    for (const auto& [what, host] :
         {std::pair{"renderbuffer colour", &renderbuffer}, {"24-bit depth", &depth24}}) {
        render(renderer, registry, frameAt(*host, {0.0, 0.0, 20.0}, 0.0, -5.0, 10.0));
        EXPECT_FALSE(renderer.lastStats().computeShaded) << what;
        const std::vector<float> rgba = host->readColor();
        EXPECT_GT(luminance(&rgba[(static_cast<size_t>(5) * W + W / 2) * 4]), 0.0) << what << ": sea drawn";
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << what;
    }
    // And back on a target it can use: compute shading again.
    render(renderer, registry, frameAt(target, {0.0, 0.0, 20.0}, 0.0, -5.0, 10.0));
    EXPECT_TRUE(renderer.lastStats().computeShaded);
}

// OceanDesc::skipHiddenRings: the inner rings whose whole disc lies outside the frustum (hiddenDiscRadius)
// are not drawn. That must change no pixel and no depth, in views from 0.5 m (inside the waves' reach:
// nothing skipped) to 15 km, banked, with ring thinning, and for the horizontally displaced models, while
// fewer vertices are shaded from altitude.
TEST_F(ComputeShadingGl, SkippingHiddenRingsChangesNoPixel) {
    struct Case {
        const char* name;
        SurfaceKind model;
        glm::dvec3 camera;
        double heading, pitch, roll;
        double minRingPixels;
        double maxShare; // vertices shaded with the skip / without, at most
    };
    const Case cases[] = {
        {"octaves, 20 m, the low grazing view",
         SurfaceKind::Octaves,
         {2000.0, 0.0, 20.0},
         70.0,
         -3.0,
         0.0,
         0.0,
         1.0},
        {"octaves, 0.5 m (within the waves)",
         SurfaceKind::Octaves,
         {10.0, 20.0, 0.5},
         10.0,
         -20.0,
         0.0,
         0.0,
         1.0},
        {"octaves, 3 km, 10 deg down", SurfaceKind::Octaves, {0.0, 0.0, 3000.0}, 40.0, -10.0, 0.0, 0.0, 0.55},
        {"octaves, 15 km, 35 deg down",
         SurfaceKind::Octaves,
         {1e4, 2e4, 15000.0},
         250.0,
         -35.0,
         0.0,
         0.0,
         0.45},
        {"octaves, 800 m banked 60 deg",
         SurfaceKind::Octaves,
         {-500.0, 0.0, 800.0},
         120.0,
         -15.0,
         60.0,
         0.0,
         1.0},
        {"octaves, 3 km, thinned rings",
         SurfaceKind::Octaves,
         {0.0, 0.0, 3000.0},
         40.0,
         -10.0,
         0.0,
         1.0,
         0.9},
        {"gerstner, 300 m, 25 deg down",
         SurfaceKind::Gerstner,
         {0.0, 0.0, 300.0},
         200.0,
         -25.0,
         0.0,
         0.0,
         0.8},
        {"fft, 1 km, 40 deg down", SurfaceKind::Fft, {3000.0, 0.0, 1000.0}, 300.0, -40.0, 0.0, 0.0, 0.75},
    };
    for (const Case& c : cases) {
        const OceanFrame f = bankedFrameAt(target, c.camera, c.heading, c.pitch, c.roll, 33.0);
        OceanDesc desc;
        desc.model = c.model;
        desc.grid.minRingPixels = c.minRingPixels;
        long long vertices[2] = {0, 0};
        std::vector<float> color[2], depth[2];
        for (int skip = 0; skip < 2; ++skip) {
            desc.skipHiddenRings = skip == 1;
            setOcean(desc);
            target.clear(0.0f);
            render(renderer, registry, f);
            vertices[skip] = renderer.lastStats().vertices;
            color[skip] = target.readColor();
            depth[skip] = target.readDepth();
        }
        const double share = double(vertices[1]) / double(vertices[0]);
        std::printf("[%s] vertices shaded %lld -> %lld (%.3f)\n", c.name, vertices[0], vertices[1], share);
        EXPECT_TRUE(color[0] == color[1]) << c.name << ": a pixel changed";
        EXPECT_TRUE(depth[0] == depth[1]) << c.name << ": a depth changed";
        EXPECT_LE(share, c.maxShare) << c.name;
        if (c.maxShare == 1.0 && c.pitch > -5.0) {
            EXPECT_GT(share, 0.7) << c.name << ": looking at the horizon most rings are in view";
        }
    }
}

// OceanDesc::shadeTiles: sorted into 8x8 tiles by what they hold, each kind lit by a program with only its
// part of the lighting, the frame is the one program's. The kinds' counts are checked against the tiles
// of the host's depth; views with every kind: the sea to the horizon (20 m), sky above the sea beyond the
// grid (15 km), banked, an explosion and a wake, a displaced model, and without the sky (the host's pixels
// stay, its sky tiles are not lit at all).
TEST_F(ComputeShadingGl, ShadingByTilesChangesNoPixel) {
    struct Case {
        const char* name;
        SurfaceKind model;
        glm::dvec3 camera;
        double heading, pitch, roll;
        bool sky, effects;
        bool beyond; // tiles of sky and the sea beyond the grid are in view
    };
    const Case cases[] = {
        {"octaves, 20 m, the low grazing view",
         SurfaceKind::Octaves,
         {2000.0, 0.0, 20.0},
         70.0,
         -3.0,
         0.0,
         true,
         false,
         false},
        {"octaves, 15 km, 20 deg down",
         SurfaceKind::Octaves,
         {1e4, 2e4, 15000.0},
         250.0,
         -20.0,
         0.0,
         true,
         false,
         true},
        {"octaves, 800 m banked 60 deg",
         SurfaceKind::Octaves,
         {-500.0, 0.0, 800.0},
         120.0,
         -5.0,
         60.0,
         true,
         false,
         false},
        {"gerstner, 0.5 m", SurfaceKind::Gerstner, {10.0, 20.0, 0.5}, 10.0, -2.0, 0.0, true, false, false},
        {"octaves, an explosion and a wake, 200 m",
         SurfaceKind::Octaves,
         {300.0, -400.0, 200.0},
         0.0,
         -12.0,
         0.0,
         true,
         true,
         false},
        {"octaves, 15 km, no sky",
         SurfaceKind::Octaves,
         {1e4, 2e4, 15000.0},
         250.0,
         -20.0,
         0.0,
         false,
         false,
         true},
    };
    ecs::EventQueue events;
    EffectsSystem fx(registry, events);
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        if (c.effects) {
            const ecs::Entity ship = registry.create();
            registry.emplace<Ship>(ship, Ship{{0.0, 0.0}, 60.0});
            events.enqueue(AttachShipTrail{ship, WakeParams{}});
            events.enqueue(SpawnExplosion{{350.0, 150.0}, 55.0, 2.0});
            for (int i = 0; i <= 600; ++i) {
                registry.get<Ship>(ship).position = {i * 1.0, 0.0};
                events.dispatch();
                fx.update(i * 0.1, c.camera);
            }
        }
        const OceanFrame f = bankedFrameAt(target, c.camera, c.heading, c.pitch, c.roll, 60.0);
        OceanDesc desc = withEveryGrid(oceanPreset(Quality::High));
        desc.model = c.model;
        desc.drawSky = c.sky;
        std::vector<float> color[2], depth[2];
        std::array<int, 4> counts{};
        for (int tiles = 0; tiles < 2; ++tiles) {
            desc.shadeTiles = tiles ? OceanDesc::ShadeTiles::On : OceanDesc::ShadeTiles::Off;
            setOcean(desc);
            target.clear(7.0f);
            render(renderer, registry, f);
            ASSERT_TRUE(renderer.lastStats().computeShaded);
            EXPECT_EQ(renderer.lastStats().shadeTiled, tiles == 1);
            if (tiles)
                counts = ocean::debug::shadeTileCounts(renderer);
            color[tiles] = target.readColor();
            depth[tiles] = target.readDepth();
            EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
        }
        if (c.effects) {
            EXPECT_EQ(renderer.lastStats().wakes.draws, 1);
            EXPECT_EQ(renderer.lastStats().explosions.draws, 1);
        }
        EXPECT_TRUE(depth[0] == depth[1]);
        // The same code in another program: equal pixels, up to the rounding LLVM may choose differently.
        size_t differing = 0;
        double maxRel = 0.0;
        for (size_t i = 0; i < color[0].size(); ++i)
            if (color[0][i] != color[1][i]) {
                ++differing;
                maxRel = std::max(maxRel, std::abs(double(color[0][i]) - color[1][i]) /
                                              std::max(std::abs(double(color[0][i])), 1e-3));
            }
        // The host's tiles: what each holds, from its depth (rows bottom-up, as the depth texture).
        constexpr int T = 8;
        const int tilesX = (W + T - 1) / T, tilesY = (H + T - 1) / T;
        int mixed = 0, sea = 0, open = 0, hostKept = 0;
        for (int ty = 0; ty < tilesY; ++ty)
            for (int tx = 0; tx < tilesX; ++tx) {
                bool anySea = false, anyOther = false;
                for (int y = ty * T; y < std::min(H, ty * T + T); ++y)
                    for (int x = tx * T; x < std::min(W, tx * T + T); ++x)
                        (depth[1][static_cast<size_t>(y) * W + x] > 0.0f ? anySea : anyOther) = true;
                mixed += anySea && anyOther;
                sea += anySea && !anyOther;
                open += !anySea;
            }
        for (size_t i = 0; i < depth[1].size(); ++i)
            hostKept += depth[1][i] == 0.0f && color[1][i * 4] == 7.0f;
        std::printf("[%s] tiles mixed %d, sea %d, sky %d, beyond %d of %d; pixels differing %zu (max %.2e)\n",
                    c.name, counts[0], counts[1], counts[2], counts[3], tilesX * tilesY, differing, maxRel);
        EXPECT_LE(maxRel, 1e-5);
        if (info().software) {
            EXPECT_EQ(differing, 0u) << "llvmpipe compiles the same lighting to the same bits";
        }
        EXPECT_EQ(counts[0], mixed);
        EXPECT_EQ(counts[1], sea);
        EXPECT_GT(sea, 0);
        EXPECT_LE(mixed, tilesX * tilesY / 4) << "the edge tiles are a band, not the screen";
        if (c.sky) {
            EXPECT_EQ(counts[2] + counts[3], open);
            EXPECT_EQ(hostKept, 0) << "every sky pixel is lit";
            EXPECT_GT(counts[2], 0) << "tiles of open sky";
            if (c.beyond) {
                EXPECT_GT(counts[3], 0) << "tiles of the sea beyond the grid";
            }
        } else {
            EXPECT_EQ(counts[2] + counts[3], 0) << "no sky drawn: its tiles are not lit";
            EXPECT_GT(hostKept, W * H / 10) << "the host's sky stays";
        }
    }
}

} // namespace
