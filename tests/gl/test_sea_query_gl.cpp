// The asynchronous GPU height queries (OceanRenderer::queueHeights / takeHeights; ctest labels gl,
// stability):
// - only what the scene calls for: a frame with nothing queued has no query pass; a queued batch adds one;
// - the answers are what the GPU draws: equal to the CPU twin of the drawn surface (displacementSeenFrom,
//   with the Gerstner sum's distance fade) within float precision for the octaves and Gerstner models, also
//   at 10^7 m from the origin at t = 10^6 s; with an explosion, within the effects field's interpolation of
//   the CPU's batched queries (SeaQuery, the analytic field); the FFT sea's CPU path (FftSampledSea) against
//   what the GPU draws, near the camera and where the drawn sea fades its finest cascade;
// - no stall: the answers are taken after the next frame (ready once the GPU is done; a batch not yet
//   rendered is not ready), latency one frame; a full ring drops the oldest batch (counted);
// - bad input: a NaN point, a wrong span size, an unknown ticket are refused as a Status.
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "ocean/Ocean.h"
#include "ocean/SeaQuery.h"

#include "GlLayerTest.h"
#include "OceanTestFrame.h"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <tuple>
#include <vector>

using namespace pacifica;
using namespace pacifica::ocean;

namespace {

constexpr int W = 160, H = 90;

/// The shared headless context and its checks (GlLayerTest.h: no GL error or KHR_debug error left behind).
class SeaQueryGl : public gltest::GlTest {
protected:
    gl::FrameTargets targets{W, H};
    OceanRenderer renderer;

    OceanFrame frameAt(const glm::dvec3& camera, double t) const {
        return gltest::oceanFrameAt(camera, 30.0, -20.0, t, targets.sceneFramebuffer().id(), W, H);
    }

    static OceanComponent sea(SurfaceKind model) {
        OceanDesc d;
        d.model = model;
        OceanComponent c;
        EXPECT_TRUE(makeOcean(d, c).ok());
        return c;
    }

    static std::vector<glm::dvec2> pointsAround(const glm::dvec2& centre, double spread, size_t n) {
        std::mt19937 rng(3);
        std::uniform_real_distribution<double> u(-spread, spread);
        std::vector<glm::dvec2> p(n);
        for (glm::dvec2& q : p)
            q = centre + glm::dvec2(u(rng), u(rng));
        return p;
    }

    /// Queues `points`, renders one frame, then takes the answers (after glFinish: ready).
    std::vector<double> gpuHeights(const OceanComponent& ocean, const EffectsView& effects,
                                   const OceanFrame& frame, const std::vector<glm::dvec2>& points) {
        std::uint64_t ticket = 0;
        EXPECT_TRUE(renderer.queueHeights(7, points, ticket).ok());
        const OceanInstance oceans[] = {{7, &ocean}};
        const Status s = renderer.render({oceans, effects}, frame);
        EXPECT_TRUE(s.ok()) << s.message;
        glFinish();
        std::vector<double> h(points.size(), NAN);
        bool ready = false;
        EXPECT_TRUE(renderer.takeHeights(ticket, h, ready).ok());
        EXPECT_TRUE(ready);
        return h;
    }

    static std::vector<double> cpuHeights(const OceanComponent& ocean, const EffectsView& effects, double t,
                                          const std::vector<glm::dvec2>& points) {
        SeaQuery q;
        EXPECT_TRUE(q.init(ocean, {.fields = SeaField::Height}).ok());
        EXPECT_TRUE(q.update(t, effects).ok());
        std::vector<double> h(points.size());
        EXPECT_TRUE(q.heights(points, h).ok());
        return h;
    }
};

/// The CPU twin of what sea_query.comp evaluates: the Eulerian height of the surface as the GPU draws it
/// for a camera at cameraXY (SurfaceModel::displacementSeenFrom: the Gerstner sum fades its short waves with
/// the distance), solved by the same fixed point in double run to convergence.
std::vector<double> drawnHeights(const SurfaceModel& surface, double t, const glm::dvec2& cameraXY,
                                 const std::vector<glm::dvec2>& points) {
    std::vector<double> out(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        glm::dvec2 x0 = points[i];
        for (int k = 0; k < 200; ++k)
            x0 = points[i] - glm::dvec2(surface.displacementSeenFrom(x0, t, cameraXY));
        out[i] = surface.displacementSeenFrom(x0, t, cameraXY).z;
    }
    return out;
}

double maxDifference(const std::vector<double>& a, const std::vector<double>& b) {
    double worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i)
        worst = std::max(worst, std::isfinite(a[i]) ? std::abs(a[i] - b[i]) : INFINITY);
    return worst;
}

} // namespace

TEST_F(SeaQueryGl, TheAnswersAreWhatTheGpuDrawsNearAndFar) {
    for (SurfaceKind model : {SurfaceKind::Octaves, SurfaceKind::Gerstner}) {
        const OceanComponent ocean = sea(model);
        for (const auto& [camera, t] :
             {std::pair{glm::dvec3(0.0, 0.0, 40.0), 12.5}, std::pair{glm::dvec3(1e7, -1e7, 40.0), 1e6}}) {
            const std::vector<glm::dvec2> points =
                pointsAround(glm::dvec2(camera) + glm::dvec2(100.0, 150.0), 150.0, 2000);
            const std::vector<double> gpu = gpuHeights(ocean, {}, frameAt(camera, t), points);
            const std::vector<double> drawn = drawnHeights(*ocean.surface, t, glm::dvec2(camera), points);
            const double worst = maxDifference(gpu, drawn);
            // The unfaded surface (SeaQuery, the CPU queries) differs by the Gerstner sum's distance fade.
            const double fade = maxDifference(cpuHeights(ocean, {}, t, points), drawn);
            std::printf("%s at t = %g: max |GPU - drawn| %.2e m, |drawn - unfaded| %.2e m over %zu points\n",
                        toString(model), t, worst, fade, points.size());
            // Float evaluation of the model's GLSL within ~300 m of the camera: measured 2.2e-6 m.
            EXPECT_LT(worst, 1e-4) << toString(model);
        }
    }
}

TEST_F(SeaQueryGl, BeyondTheDisplacedGridTheDrawnSeaIsFlat) {
    // The grid displaces out to rMax (40 km by default); the skirt beyond is flat, and so are the answers.
    // (The octaves: the Gerstner and FFT seas fade their waves out within a few km anyway.)
    const OceanComponent ocean = sea(SurfaceKind::Octaves);
    const glm::dvec3 camera(5e6, 3e6, 40.0);
    const std::vector<glm::dvec2> points = {glm::dvec2(camera) + glm::dvec2(39000.0, 0.0),
                                            glm::dvec2(camera) + glm::dvec2(0.0, -41000.0)};
    const std::vector<double> gpu = gpuHeights(ocean, {}, frameAt(camera, 7.0), points);
    EXPECT_NE(gpu[0], 0.0);
    EXPECT_EQ(gpu[1], 0.0);
}

TEST_F(SeaQueryGl, AnExplosionIsInTheAnswers) {
    const OceanComponent ocean = sea(SurfaceKind::Gerstner);
    Explosion e;
    e.center = {120.0, 160.0};
    e.startTime = 8.0;
    e.params = explosionParams(1.0);
    const EffectsView effects{{&e, 1}, {}};
    const double t = 14.0;
    const std::vector<glm::dvec2> points = pointsAround(e.center, 60.0, 1000);
    const std::vector<double> gpu = gpuHeights(ocean, effects, frameAt({0.0, 0.0, 40.0}, t), points);
    const std::vector<double> cpu = cpuHeights(ocean, effects, t, points);
    const std::vector<double> plain = cpuHeights(ocean, {}, t, points);
    const double effect = maxDifference(cpu, plain), worst = maxDifference(gpu, cpu);
    std::printf("explosion: largest effect %.3f m, max |GPU - CPU| %.3f m\n", effect, worst);
    EXPECT_GT(effect, 0.3);
    // The GPU reads the effects field's texels (bilinear, band-limited per level); the CPU the analytic
    // field.
    EXPECT_LT(worst, 0.1 * effect);
}

TEST_F(SeaQueryGl, NoStallOneFrameLatencyAndOnlyWhenAsked) {
    const OceanComponent ocean = sea(SurfaceKind::Gerstner);
    const OceanInstance oceans[] = {{7, &ocean}};
    const OceanFrame f = frameAt({0.0, 0.0, 40.0}, 3.0);
    ASSERT_TRUE(renderer.render({oceans, {}}, f).ok());
    const int plainPasses = renderer.lastStats().passes;

    const std::vector<glm::dvec2> points = pointsAround({50.0, 80.0}, 40.0, 500);
    std::vector<double> h(points.size());
    std::uint64_t ticket = 0;
    ASSERT_TRUE(renderer.queueHeights(7, points, ticket).ok());
    bool ready = true;
    ASSERT_TRUE(renderer.takeHeights(ticket, h, ready).ok());
    EXPECT_FALSE(ready); // not rendered yet: no answer, no wait
    ASSERT_TRUE(renderer.render({oceans, {}}, f).ok());
    EXPECT_EQ(renderer.lastStats().passes, plainPasses + 1); // the query pass
    glFinish(); // the host's next frame: the GPU is done with this one
    ASSERT_TRUE(renderer.takeHeights(ticket, h, ready).ok());
    EXPECT_TRUE(ready);
    ASSERT_TRUE(renderer.render({oceans, {}}, f).ok());
    EXPECT_EQ(renderer.lastStats().passes, plainPasses); // nothing queued: no pass
    // Taken: the ticket is gone.
    const Status again = renderer.takeHeights(ticket, h, ready);
    EXPECT_EQ(again.code, ErrorCode::InvalidArgument);
    EXPECT_NE(again.message.find("is not pending"), std::string::npos) << again.message;

    // A full ring drops the oldest batch not taken.
    std::uint64_t tickets[GPU_QUERY_RING + 1];
    for (std::uint64_t& t : tickets)
        ASSERT_TRUE(renderer.queueHeights(7, points, t).ok());
    EXPECT_EQ(renderer.gpuQueryCounters().dropped, points.size());
    EXPECT_EQ(renderer.takeHeights(tickets[0], h, ready).code, ErrorCode::InvalidArgument);
    ASSERT_TRUE(renderer.render({oceans, {}}, f).ok());
    glFinish();
    for (size_t i = 1; i <= GPU_QUERY_RING; ++i) {
        ASSERT_TRUE(renderer.takeHeights(tickets[i], h, ready).ok());
        EXPECT_TRUE(ready);
    }
    const GpuQueryCounters& c = renderer.gpuQueryCounters();
    EXPECT_EQ(c.queued, points.size() * (GPU_QUERY_RING + 2));
    EXPECT_EQ(c.answered, points.size() * (GPU_QUERY_RING + 1));
    EXPECT_EQ(c.notReady, 1u);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(SeaQueryGl, BadInputIsRefused) {
    std::vector<glm::dvec2> points(10, glm::dvec2(1.0));
    points[4].y = NAN;
    std::uint64_t ticket = 0;
    Status s = renderer.queueHeights(7, points, ticket);
    EXPECT_EQ(s.code, ErrorCode::InvalidArgument);
    EXPECT_NE(s.message.find("points[4]"), std::string::npos) << s.message;
    points[4].y = 0.0;
    ASSERT_TRUE(renderer.queueHeights(7, points, ticket).ok());
    std::vector<double> h(9);
    bool ready = true;
    s = renderer.takeHeights(ticket, h, ready);
    EXPECT_NE(s.message.find("has 10 points but heights holds 9"), std::string::npos) << s.message;
    EXPECT_FALSE(ready);
    EXPECT_EQ(renderer.takeHeights(12345, h, ready).code, ErrorCode::InvalidArgument);
}

TEST_F(SeaQueryGl, TheFftSampledCpuPathAgainstWhatTheGpuDraws) {
    // The FFT sea's CPU queries (FftSampledSea: bicubic on the CPU's own transform, the unfaded sea) against
    // its drawn surface (the GPU's float transform read bilinearly, each cascade faded with the distance from
    // the camera): the error a game sees between its physics and its pixels. Within 20 m of the camera no
    // cascade is faded (measured RMS 3.6-4.1 cm, max 9.7 cm: bilinear against bicubic); 50-350 m away the
    // finest cascade fades out of the drawn sea (RMS 10 cm, max 37 cm; docs/ACCURACY.md).
    const OceanComponent ocean = sea(SurfaceKind::Fft);
    for (const auto& [camera, t] :
         {std::pair{glm::dvec3(0.0, 0.0, 40.0), 12.5}, std::pair{glm::dvec3(1e7, -1e7, 40.0), 1e6}}) {
        for (const auto& [offset, spread, rmsBound, maxBound] :
             {std::tuple{glm::dvec2(10.0, 15.0), 8.0, 0.06, 0.15},
              std::tuple{glm::dvec2(100.0, 150.0), 150.0, 0.15, 0.5}}) {
            const std::vector<glm::dvec2> points = pointsAround(glm::dvec2(camera) + offset, spread, 2000);
            const std::vector<double> gpu = gpuHeights(ocean, {}, frameAt(camera, t), points);
            const std::vector<double> cpu = cpuHeights(ocean, {}, t, points);
            double sum = 0.0;
            for (size_t i = 0; i < points.size(); ++i)
                sum += (gpu[i] - cpu[i]) * (gpu[i] - cpu[i]);
            const double rms = std::sqrt(sum / points.size()), worst = maxDifference(gpu, cpu);
            std::printf("fft at t = %g, %.0f m out: |GPU - CPU sampled| RMS %.4f m, max %.4f m (Hs %.2f m)\n",
                        t, glm::length(offset), rms, worst, ocean.surface->significantWaveHeight());
            EXPECT_LT(rms, rmsBound);
            EXPECT_LT(worst, maxBound);
        }
    }
}
