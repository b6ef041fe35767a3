// Look tests (label `look`), headless EGL: the sun's glitter as rendered follows the sea state's slope
// statistics. Seen from 2 km, looking at the specular point, the sun's share of each pixel (a render with the
// sun minus one without) divided by Schlick's Fresnel falls off with the half-vector angle as
// cos(theta_h)^s (the shader's normalised Blinn-Phong, s = 2 / m^2 - 2, Beckmann-like). A least-squares fit
// of ln(L / F) against ln(cos theta_h) over the bright pixels gives s, so m^2 = 2 / (s + 2): it must be the
// Cox & Munk (1954) total slope variance of the wind (model slopes + the sub-model ones applySeaState sets).
#include <epoxy/gl.h>

#include "engine/Space.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/SeaState.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

using namespace pacifica;

namespace {

constexpr int N = 256;
constexpr double ALTITUDE = 2000.0, SUN_ELEVATION_DEG = 50.0;

/// The fitted Beckmann mean-square slope of the rendered glitter at wind speed u.
double glitterSlopeVariance(double u) {
    const double el = SUN_ELEVATION_DEG * M_PI / 180.0;
    const glm::dvec3 sun(0.0, -std::cos(el), std::sin(el)); // in the south
    auto render = [&](float sunIntensity) {
        ocean::OceanDesc d = ocean::applySeaState({}, {u, 60.0});
        d.lighting.sunDirection = sun;
        d.lighting.sunIntensity = sunIntensity;
        d.lighting.normalTilt = 0.0f; // the fit assumes the surface's own normals
        d.lighting.fogDensity = 0.0f; // no sunlight lost on the way
        d.lighting.foamIntensity = 0.0f;
        ecs::Registry registry;
        registry.emplace<ocean::OceanComponent>(registry.create(), ocean::makeOcean(d));
        ocean::OceanRenderer renderer;
        gl::FrameTargets targets(N, N);
        Pose cam;
        cam.position = {3.0e5, -2.0e5, ALTITUDE};
        cam.headingDeg = 180.0; // toward the sun
        cam.pitchDeg = -SUN_ELEVATION_DEG;
        ocean::OceanFrame f;
        f.camera = makeCameraFrame(cam, static_cast<float>(100.0 * M_PI / 180.0), 1.0f, 1.0f);
        f.time = 17.0;
        f.targetFramebuffer = targets.sceneFramebuffer().id();
        f.width = N;
        f.height = N;
        renderer.render(registry, f);
        std::vector<float> px;
        targets.readScene(px);
        return std::make_pair(px, f.camera);
    };
    const auto [lit, camera] = render(40.0f);
    const auto [unlit, camera2] = render(0.0f);
    const glm::mat4 inv = glm::inverse(camera.viewProj);
    struct Sample {
        double x, y;
    };
    std::vector<Sample> samples;
    double peak = 0.0;
    std::vector<double> sunShare(N * N, 0.0), logCos(N * N, 0.0);
    for (int row = 0; row < N; ++row)
        for (int col = 0; col < N; ++col) {
            const size_t i = static_cast<size_t>(row * N + col);
            const glm::vec4 ndc((col + 0.5f) / N * 2.0f - 1.0f, 1.0f - (row + 0.5f) / N * 2.0f, 1.0f, 1.0f);
            glm::vec4 p = inv * ndc;
            const glm::dvec3 dir = glm::normalize(glm::dvec3(p) / double(p.w));
            if (dir.z > -0.05)
                continue; // the horizon and above
            const glm::dvec3 v = -dir, h = glm::normalize(v + sun);
            const double f = ocean::WATER_F0 + (1.0 - ocean::WATER_F0) * std::pow(1.0 - v.z, 5.0); // n = up
            const double share = (lit[i * 4 + 1] - unlit[i * 4 + 1]) / f; // green: the sun is near white
            sunShare[i] = share;
            logCos[i] = std::log(h.z);
            peak = std::max(peak, share);
        }
    // The peak as the 99.9th percentile: a few pixels where a resolved wave facet mirrors the sun exactly
    // stand far above the lobe.
    std::vector<double> sorted = sunShare;
    std::sort(sorted.begin(), sorted.end());
    std::printf("sun share: max %.3f, p99.9 %.3f, p99 %.3f, p90 %.3f\n", peak,
                sorted[sorted.size() * 999 / 1000], sorted[sorted.size() * 99 / 100],
                sorted[sorted.size() * 9 / 10]);
    peak = sorted[sorted.size() * 999 / 1000];
    for (size_t i = 0; i < sunShare.size(); ++i)
        if (sunShare[i] > 0.05 * peak)
            samples.push_back({logCos[i], std::log(sunShare[i])});
    // Least squares y = c + s x.
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const Sample& s : samples) {
        sx += s.x;
        sy += s.y;
        sxx += s.x * s.x;
        sxy += s.x * s.y;
    }
    const double n = static_cast<double>(samples.size());
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    const double m2 = 2.0 / (slope + 2.0);
    std::printf("U = %4.1f m/s: %zu glitter pixels, fitted shininess %.2f -> m^2 %.4f; Cox-Munk %.4f\n", u,
                samples.size(), slope, m2, ocean::coxMunkSlopeVariance(u));
    EXPECT_GT(samples.size(), 500u) << "too few glitter pixels to fit";
    return m2;
}

class LookGl : public ::testing::Test {
protected:
    static void SetUpTestSuite() { sCtx = gl::createHeadlessContext({}); }
    static void TearDownTestSuite() { sCtx.reset(); }
    static std::unique_ptr<gl::GlContext> sCtx;
};
std::unique_ptr<gl::GlContext> LookGl::sCtx;

} // namespace

TEST_F(LookGl, SunGlitterWidthFollowsCoxAndMunk) {
    const double m6 = glitterSlopeVariance(6.0), m20 = glitterSlopeVariance(20.0);
    EXPECT_NEAR(m6 / ocean::coxMunkSlopeVariance(6.0), 1.0, 0.15);
    EXPECT_NEAR(m20 / ocean::coxMunkSlopeVariance(20.0), 1.0, 0.15);
    // More wind, a wider glitter, by Cox & Munk's ratio (3.1) within 25 %.
    EXPECT_NEAR((m20 / m6) / (ocean::coxMunkSlopeVariance(20.0) / ocean::coxMunkSlopeVariance(6.0)), 1.0,
                0.25);
}
