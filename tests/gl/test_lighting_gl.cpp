// GL tests of the shading (sky.glsl, sky.frag, ocean.frag, LightingGpu) through the public render path:
// an ecs::Registry with an OceanComponent drawn by OceanRenderer into FrameTargets, cameras from
// makeCameraFrame. Checks: the HDR environment map shows in the sky with the documented lat-long
// orientation (north at the map's centre column) and changes the picture; frames stay finite; the height
// falloff fog lets the sea show from 15 km while a fog of the same sea-level density without falloff hides
// it, and at 0.5 m the horizon is the fog colour; foam brightens the sea; each lighting texture is uploaded
// once and counted. Set PACIFICA_LIGHTING_DUMP=DIR to write every rendered frame as a scene-linear EXR.
#include "SharedData.h"
#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/capture/Capture.h"
#include "engine/gl/FrameTargets.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/Shader.h"
#include "gpu/LightingGpu.h"
#include "ocean/Lighting.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanHost.h"
#include "ocean/OceanShaders.h"

#include "GlLayerTest.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

using namespace pacifica;

namespace {

constexpr int W = 192;
constexpr int H = 108;
constexpr float FOV_Y = static_cast<float>(std::numbers::pi / 3.0); // 60 degrees

using pacifica::testdata::sharedDir;

/// The Kerner lat-long map (1024 x 512, RGBA half) as an EnvironmentMap, read once.
std::shared_ptr<const ocean::EnvironmentMap> kerner() {
    static const std::shared_ptr<const ocean::EnvironmentMap> map = [] {
        const capture::Image img = capture::readImage(sharedDir() / "data/hdr/KernerEnvLatLong.exr");
        std::vector<float> rgb(static_cast<size_t>(img.width) * img.height * 3);
        for (size_t p = 0; p < rgb.size() / 3; ++p)
            for (size_t c = 0; c < 3; ++c)
                rgb[p * 3 + c] = img.pixels[p * static_cast<size_t>(img.channels) + c];
        return std::make_shared<const ocean::EnvironmentMap>(
            ocean::makeEnvironmentMap(img.width, img.height, std::move(rgb)));
    }();
    return map;
}

Pose pose(double z, double headingDeg, double pitchDeg) {
    Pose p;
    p.position = {1234.5, -678.9, z};
    p.headingDeg = headingDeg;
    p.pitchDeg = pitchDeg;
    return p;
}

/// One ocean (its own registry and renderer) rendered with a given lighting.
class Scene {
public:
    explicit Scene(const ocean::OceanDesc& desc) : mTargets(W, H) {
        mEntity = mRegistry.create();
        mRegistry.emplace<ocean::OceanComponent>(mEntity, ocean::makeOcean(desc));
    }
    /// RGBA scene-linear pixels, rows top-down.
    std::vector<float> render(const ocean::LightingDesc& lighting, const Pose& p, const std::string& name) {
        ocean::validateLighting(lighting);
        mRegistry.get<ocean::OceanComponent>(mEntity).desc.lighting = lighting;
        const ocean::OceanFrame frame =
            ocean::makeOceanFrame(p, FOV_Y, W, H, 17.25, mTargets.sceneFramebuffer().id());
        ocean::render(mRenderer, mRegistry, frame);
        std::vector<float> rgba;
        mTargets.readScene(rgba);
        if (const char* dump = std::getenv("PACIFICA_LIGHTING_DUMP"); dump && *dump)
            capture::writeExrHalf(std::filesystem::path(dump) / (name + ".exr"), W, H, 4, rgba.data(), {});
        mLastCamera = frame.camera;
        return rgba;
    }
    const CameraFrame& lastCamera() const { return mLastCamera; }

private:
    ecs::Registry mRegistry;
    ecs::Entity mEntity;
    ocean::OceanRenderer mRenderer;
    gl::FrameTargets mTargets;
    CameraFrame mLastCamera;
};

class LightingGl : public gltest::GlTest {
protected:
};

/// Every value finite and >= 0 (scene-linear radiance).
void expectFinite(const std::vector<float>& rgba, const std::string& what) {
    size_t bad = 0;
    for (float v : rgba)
        bad += (!std::isfinite(v) || v < 0.0f) ? 1 : 0;
    EXPECT_EQ(bad, 0u) << what << ": non-finite or negative values";
}

/// Mean RGB over rows [r0, r1).
glm::dvec3 meanRows(const std::vector<float>& rgba, int r0, int r1) {
    glm::dvec3 sum(0.0);
    for (int y = r0; y < r1; ++y)
        for (int x = 0; x < W; ++x) {
            const float* p = &rgba[(static_cast<size_t>(y) * W + x) * 4];
            sum += glm::dvec3(p[0], p[1], p[2]);
        }
    return sum / static_cast<double>((r1 - r0) * W);
}

double luminance(const glm::dvec3& c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

/// Largest per-channel relative difference |a - b| / b.
double relativeDifference(const glm::dvec3& a, const glm::dvec3& b) {
    return std::max({std::abs(a.r - b.r) / b.r, std::abs(a.g - b.g) / b.g, std::abs(a.b - b.b) / b.b});
}

/// World direction of pixel (x, y) (rows top-down), as sky.frag computes it.
glm::dvec3 pixelDirection(const CameraFrame& cam, int x, int y) {
    const glm::vec4 ndc((x + 0.5f) / W * 2.0f - 1.0f, 1.0f - (y + 0.5f) / H * 2.0f, 0.5f, 1.0f);
    const glm::vec4 p = glm::inverse(cam.viewProj) * ndc;
    return glm::normalize(glm::dvec3(p) / static_cast<double>(p.w));
}

/// The map at level 0 with GL's bilinear filtering (u repeats, v clamps).
glm::dvec3 sampleMap(const ocean::EnvironmentMap& m, const glm::dvec3& dir) {
    const glm::dvec2 uv = ocean::environmentUv(dir);
    const double fx = uv.x * m.width - 0.5, fy = std::clamp(uv.y * m.height - 0.5, 0.0, m.height - 1.0);
    const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
    const double ax = fx - x0, ay = fy - y0;
    auto texel = [&](int x, int y) {
        x = ((x % m.width) + m.width) % m.width;
        y = std::clamp(y, 0, m.height - 1);
        const float* p = &m.rgb[(static_cast<size_t>(y) * m.width + x) * 3];
        return glm::dvec3(p[0], p[1], p[2]);
    };
    return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax),
                    glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax), ay);
}

ocean::LightingDesc noFog() {
    ocean::LightingDesc l;
    l.fogDensity = 0.0f;
    return l;
}

} // namespace

TEST_F(LightingGl, EnvironmentMapShowsInTheSkyWithTheDocumentedOrientation) {
    Scene scene({});
    // Looking toward the map's sun (heading ~73 deg, elevation ~21 deg), a little upward: the upper rows are
    // sky, trees and the sun.
    const ocean::EnvironmentMap& map = *kerner();
    const Pose p = pose(30.0, 60.0, 12.0);
    ocean::LightingDesc procedural = noFog();
    ocean::LightingDesc withMap = noFog();
    withMap.environment = kerner();
    const std::vector<float> a = scene.render(procedural, p, "env_procedural");
    const std::vector<float> b = scene.render(withMap, p, "env_kerner");
    const CameraFrame cam = scene.lastCamera();
    expectFinite(a, "procedural sky");
    expectFinite(b, "environment map");

    const int skyRows = H * 2 / 5; // elevations ~ +18..+42 degrees: sky only
    const double la = luminance(meanRows(a, 0, skyRows)), lb = luminance(meanRows(b, 0, skyRows));
    EXPECT_GT(std::abs(lb - la), 0.1 * la) << "sky mean: procedural " << la << ", environment " << lb;

    // Without fog the sky pixels are the map at level 0: compare with a CPU bilinear lookup in the
    // direction of each pixel. A wrong convention (mirrored, rotated, upside down) fails on the textured
    // map. Tolerance: half-float storage (5e-4) and llvmpipe's 8-bit bilinear weights, which at the sharp
    // edges of branches and the sun (1678 next to 0.3) move a few pixels far more; so the test is on the
    // 90th percentile of the per-pixel relative error.
    std::vector<double> errors;
    for (int y = 0; y < skyRows; y += 3)
        for (int x = 0; x < W; x += 3) {
            const glm::dvec3 expected = sampleMap(map, pixelDirection(cam, x, y));
            const float* px = &b[(static_cast<size_t>(y) * W + x) * 4];
            errors.push_back(relativeDifference(glm::dvec3(px[0], px[1], px[2]) + 1e-3, expected + 1e-3));
        }
    std::sort(errors.begin(), errors.end());
    EXPECT_LT(errors[errors.size() * 9 / 10], 0.03) << "median " << errors[errors.size() / 2];

    // The brightest direction of the map is its sun: the pixel looking there is far brighter than the sky.
    const glm::dvec3 sun = ocean::environmentBrightestDirection(map);
    const glm::vec4 clip = cam.viewProj * glm::vec4(glm::vec3(sun), 0.0f);
    const int sx = static_cast<int>((clip.x / clip.w * 0.5f + 0.5f) * W);
    const int sy = static_cast<int>((0.5f - clip.y / clip.w * 0.5f) * H);
    ASSERT_TRUE(sx >= 0 && sx < W && sy >= 0 && sy < H) << sx << "," << sy;
    EXPECT_GT(b[(static_cast<size_t>(sy) * W + sx) * 4 + 1], 50.0f);
}

TEST_F(LightingGl, EnvironmentLightsTheSeaAndStaysFiniteFromEveryAltitude) {
    Scene scene({});
    ocean::LightingDesc l;
    l.environment = kerner();
    l.sunDirection = ocean::environmentBrightestDirection(*kerner());
    for (const auto& [z, pitch] : {std::pair{0.5, 0.0}, {40.0, -10.0}, {3000.0, -35.0}, {15000.0, -60.0}}) {
        const std::vector<float> rgba =
            scene.render(l, pose(z, 40.0, pitch), "env_sea_" + std::to_string(int(z)));
        expectFinite(rgba, "environment at z = " + std::to_string(z));
        const double sea = luminance(meanRows(rgba, H * 3 / 4, H));
        EXPECT_GT(sea, 0.005) << z;
        // Lit, not blown out. From 0.5 m toward the map's low sun the near sea is Cox & Munk's glitter,
        // whose footprint term 1 / (4 cos theta_v) brightens grazing views: 7.0 there (was 5.0 or less with
        // the Blinn-Phong lobe before 2026-11-25).
        EXPECT_LT(sea, 10.0) << z;
    }
}

// The default sky is the physical clear sky (ocean/Atmosphere.h), as rendered: with the sun 30 degrees up,
// the zenith's hue is blue (b > g > r), and the band 2-5 degrees above the horizon, looking away from the
// sun, is brighter than the zenith. The sunlit side is brighter than the side opposite at 20 degrees up
// (the aureole), and from 12 km the zenith is darker and bluer than from the sea.
TEST_F(LightingGl, PhysicalSkyHasABlueZenithAndABrighterHorizonBand) {
    Scene scene({});
    ocean::LightingDesc l; // defaults: the physical sky with the fog's haze in it
    ASSERT_EQ(l.sky, ocean::LightingDesc::Sky::Physical);
    l.sunDirection = glm::dvec3(std::cos(M_PI / 6.0), 0.0, std::sin(M_PI / 6.0)); // east, 30 degrees up
    // Mean radiance of the pixels whose view direction lies in the given elevation band and within
    // `maxFromHeading` degrees of `heading` (any heading when 180).
    auto band = [&](const std::vector<float>& rgba, double lo, double hi, double heading,
                    double maxFromHeading) {
        const CameraFrame cam = scene.lastCamera();
        glm::dvec3 sum(0.0);
        int n = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const glm::dvec3 d = pixelDirection(cam, x, y);
                const double e = std::asin(std::clamp(d.z, -1.0, 1.0)) * 180.0 / M_PI;
                double dh = std::abs(std::atan2(d.x, d.y) * 180.0 / M_PI - heading);
                dh = std::min(dh, 360.0 - dh);
                if (e < lo || e > hi || (maxFromHeading < 180.0 && dh > maxFromHeading))
                    continue;
                const float* px = &rgba[(static_cast<size_t>(y) * W + x) * 4];
                sum += glm::dvec3(px[0], px[1], px[2]);
                ++n;
            }
        EXPECT_GT(n, 20) << lo << ".." << hi;
        return n ? sum / static_cast<double>(n) : sum;
    };
    const std::vector<float> up = scene.render(l, pose(20.0, 0.0, 89.0), "physical_zenith");
    const glm::dvec3 zenith = band(up, 80.0, 90.0, 0.0, 180.0);
    const std::vector<float> away = scene.render(l, pose(20.0, 270.0, 5.0), "physical_away");
    const glm::dvec3 horizon = band(away, 2.0, 5.0, 270.0, 20.0);
    const glm::dvec3 awayHigh = band(away, 18.0, 22.0, 270.0, 20.0);
    const std::vector<float> toward = scene.render(l, pose(20.0, 90.0, 5.0), "physical_toward");
    const glm::dvec3 towardHigh = band(toward, 18.0, 22.0, 90.0, 20.0);
    std::printf("physical sky, sun 30 deg: zenith %.3f %.3f %.3f, horizon band %.3f %.3f %.3f, 20 deg up "
                "toward the sun %.3f / away %.3f\n",
                zenith.r, zenith.g, zenith.b, horizon.r, horizon.g, horizon.b, luminance(towardHigh),
                luminance(awayHigh));
    EXPECT_GT(zenith.b, 1.5 * zenith.g);
    EXPECT_GT(zenith.g, 1.5 * zenith.r);
    EXPECT_GT(luminance(horizon), 2.0 * luminance(zenith));
    EXPECT_GT(luminance(towardHigh), 2.0 * luminance(awayHigh));
    const std::vector<float> high = scene.render(l, pose(12000.0, 0.0, 89.0), "physical_zenith_12km");
    const glm::dvec3 zenithHigh = band(high, 80.0, 90.0, 0.0, 180.0);
    EXPECT_LT(luminance(zenithHigh), 0.5 * luminance(zenith));
    EXPECT_GT(zenithHigh.b / zenithHigh.r, zenith.b / zenith.r);
    // The gradient sky (the knob) is another sky: its zenith differs by more than 10 %.
    ocean::LightingDesc g = l;
    g.sky = ocean::LightingDesc::Sky::Gradient;
    const glm::dvec3 gradient =
        band(scene.render(g, pose(20.0, 0.0, 89.0), "gradient_zenith"), 80.0, 90.0, 0.0, 180.0);
    EXPECT_GT(std::abs(luminance(gradient) - luminance(zenith)), 0.1 * luminance(zenith));
}

// A frame's physical sky depends on its own camera only: the sky a renderer prefetched on a worker thread
// while the camera climbed (the levels next to the camera's, LightingGpu) gives the same pixels as a fresh
// renderer drawing that altitude first.
TEST_F(LightingGl, PhysicalSkyDoesNotDependOnTheFramesBefore) {
    ocean::LightingDesc l;
    l.sunDirection = glm::dvec3(0.3, 0.8, 0.4);
    const Pose last = pose(1240.0, 30.0, 10.0);
    Scene fresh({});
    const std::vector<float> direct = fresh.render(l, last, "physical_direct");
    Scene climbing({});
    for (double z : {1000.0, 1100.0, 1150.0, 1200.0})
        climbing.render(l, pose(z, 30.0, 10.0), "physical_climb");
    const std::vector<float> climbed = climbing.render(l, last, "physical_climbed");
    ASSERT_EQ(direct.size(), climbed.size());
    size_t differing = 0;
    for (size_t i = 0; i < direct.size(); ++i)
        differing += direct[i] != climbed[i];
    EXPECT_EQ(differing, 0u);
}

TEST_F(LightingGl, HeightFalloffFogThinsWithAltitude) {
    // A calm sea (2 % of the default octave heights) so that from 0.5 m the horizon is water kilometres
    // away, not the crest of the next wave; a dense, shallow sea fog: 1/20 m at sea level (80 m visibility)
    // with a 6 m scale height, whose whole column is only rho0 H = 0.3 thick.
    ocean::OceanDesc calm;
    for (ocean::OctaveDesc& o : calm.octaves.octaves)
        o.amplitude *= 0.02;
    Scene scene(calm);
    ocean::LightingDesc l;
    l.fogDensity = 1.0f / 20.0f;
    l.fogHeightFalloff = 6.0f;
    l.fogNoise = 0.0f;
    l.fogColor = glm::vec3(0.55f, 0.60f, 0.66f);
    const glm::dvec3 fog(*l.fogColor);

    // 15 km looking down 30 degrees: the rows below the centre see the sea at 30..60 degrees depression,
    // through optical depth 0.3 / sin(30 deg) = 0.6 or less: transmittance >= 0.55, so the dark sea shows.
    const std::vector<float> high = scene.render(l, pose(15000.0, 0.0, -30.0), "fog_15km");
    expectFinite(high, "fog from 15 km");
    const glm::dvec3 seaHigh = meanRows(high, H / 2, H);
    EXPECT_GT(relativeDifference(seaHigh, fog), 0.05)
        << "sea " << seaHigh.r << " " << seaHigh.g << " " << seaHigh.b;
    EXPECT_LT(luminance(seaHigh), 0.8 * luminance(fog));

    // The same sea-level density without the falloff (uniform fog): 30 km of it, the sea is pure fog colour.
    ocean::LightingDesc uniform = l;
    uniform.fogHeightFalloff = 0.0f;
    const glm::dvec3 seaUniform =
        meanRows(scene.render(uniform, pose(15000.0, 0.0, -30.0), "fog_15km_uniform"), H / 2, H);
    EXPECT_LT(relativeDifference(seaUniform, fog), 0.01);

    // 0.5 m looking at the horizon: the two rows straddling it (0.55 degrees each: the sea from 50 m out, the
    // sky just above) are the fog colour within a few percent.
    const std::vector<float> low = scene.render(l, pose(0.5, 0.0, 0.0), "fog_0m5");
    expectFinite(low, "fog from 0.5 m");
    const glm::dvec3 horizon = meanRows(low, H / 2 - 1, H / 2 + 1);
    EXPECT_LT(relativeDifference(horizon, fog), 0.03)
        << "horizon " << horizon.r << " " << horizon.g << " " << horizon.b;
}

TEST_F(LightingGl, FoamAboveTheHeightThresholdBrightensTheSea) {
    Scene scene({});
    ocean::LightingDesc everywhere = noFog();
    // The sun behind the camera (azimuth 20 degrees, 30 high; the default sun, ahead and to the left of
    // this view, put Cox & Munk's glitter into the water's mean).
    everywhere.sunDirection = glm::dvec3(0.296, 0.814, 0.5);
    everywhere.foamHeightStart = -10.0f; // every wave is above H0 (and above Hmax): alpha = 1
    everywhere.foamHeightFull = -9.0f;
    ocean::LightingDesc nowhere = everywhere;
    nowhere.foamHeightStart = 10.0f; // no wave reaches H0
    nowhere.foamHeightFull = 11.0f;
    const Pose p = pose(20.0, 200.0, -40.0);
    const std::vector<float> a = scene.render(everywhere, p, "foam_everywhere");
    const std::vector<float> b = scene.render(nowhere, p, "foam_nowhere");
    expectFinite(a, "foam everywhere");
    expectFinite(b, "no foam");
    // Rows whose sea is within the foam fade-out distance (< 1.5 km: depression > 0.8 deg).
    const double la = luminance(meanRows(a, H / 3, H)), lb = luminance(meanRows(b, H / 3, H));
    EXPECT_GT(la, 3.0 * lb) << "foam " << la << " vs water " << lb;
}

TEST_F(LightingGl, LightingTexturesAreUploadedOnceAndCounted) {
    const gl::Program program =
        gl::buildProgram({{gl::ShaderStage::Vertex,
                           {{"<ocean constants>", ocean::shaderConstantDefines()},
                            {"sky.vert", std::string(ocean::shaderText("sky.vert"))}}},
                          {gl::ShaderStage::Fragment,
                           {{"<ocean constants>", ocean::shaderConstantDefines()},
                            {"sky.glsl", std::string(ocean::shaderText("sky.glsl"))},
                            {"sky.frag", std::string(ocean::shaderText("sky.frag"))}}}},
                         "lighting test sky");
    ocean::LightingGpu lighting;
    ocean::OceanDesc desc;
    ocean::OceanFrame frame;
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 3); // foam pattern + fog noise + the physical sky, once
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 0); // nothing new
    // The physical sky is computed per altitude level (OceanConstants.h): 10 m shares the sea-level sky,
    // 3 km needs its own, and going back to the sea finds the kept one.
    frame.camera.origin.z = 10.0;
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 0);
    frame.camera.origin.z = 3000.0;
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 1);
    frame.camera.origin.z = 0.0;
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 0);
    desc.lighting.sunDirection = {0.0, 1.0, 1.0}; // another sun: another sky
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 1);
    // The gradient sky computes and uploads nothing.
    desc.lighting.sky = ocean::LightingDesc::Sky::Gradient;
    desc.lighting.sunDirection = {1.0, 0.0, 1.0};
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 0);
    desc.lighting.environment = kerner();
    lighting.bind(program.id(), 12, desc, frame);
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 1); // the map, once for two binds
    auto copy = std::make_shared<const ocean::EnvironmentMap>(*kerner());
    desc.lighting.environment = copy; // another map object: uploaded again
    lighting.bind(program.id(), 12, desc, frame);
    EXPECT_EQ(lighting.uploadsSinceLastCall(), 1);
}

// The optional third function of the surface-model contract: a model that defines MODEL_HAS_FOAM_INPUTS and
// modelFoamInputs() gets its (height, Jacobian) used by ocean.frag; without the #define the sea program
// still links and never calls it.
TEST_F(LightingGl, ModelFoamInputsAreOptionalInTheContract) {
    const std::string model = R"(
uniform float uStubJacobian;
vec3 modelDisplacement(vec2 rel) { return vec3(0.0); }
vec3 modelLighting(vec2 rel) { return vec3(0.0); }
)";
    const std::string foamInputs = R"(
#define MODEL_HAS_FOAM_INPUTS
vec2 modelFoamInputs(vec2 rel) { return vec2(0.0, uStubJacobian); }
)";
    auto build = [&](const std::string& modelText) {
        const gl::ShaderSource constants{"<ocean constants>", ocean::shaderConstantDefines()};
        return gl::buildProgram({{gl::ShaderStage::Vertex,
                                  {constants,
                                   {"stub.glsl", modelText},
                                   {"ocean.vert", std::string(ocean::shaderText("ocean.vert"))}}},
                                 {gl::ShaderStage::Fragment,
                                  {constants,
                                   {"stub.glsl", modelText},
                                   {"sky.glsl", std::string(ocean::shaderText("sky.glsl"))},
                                   {"ocean.frag", std::string(ocean::shaderText("ocean.frag"))}}}},
                                "lighting test stub sea");
    };
    const gl::Program with = build(model + foamInputs);
    const gl::Program without = build(model);
    // The stub's Jacobian uniform is live only when ocean.frag calls modelFoamInputs().
    EXPECT_GE(with.uniformLocation("uStubJacobian"), 0);
    EXPECT_GE(with.uniformLocation("uFoamJacobianThreshold"), 0);
    EXPECT_EQ(without.uniformLocation("uStubJacobian"), -1) << "modelFoamInputs used without the #define";
    EXPECT_GE(without.uniformLocation("uFoamHeightStart"), 0);
}

// Spot lights (Lighting.h SpotLight, OceanScene::spots), forward and compute shading, without and with an
// explosion's grid under the lamp: a searchlight 25 m up, pointing straight down 40 m ahead of a camera 30 m
// up, at dusk. Pixels whose sea lies well outside its cone are the frame without it (within float rounding);
// inside it the light a pixel gains follows the CPU's spotIrradiance (the falloff and inverse square) at the
// pixel's sea point; every value is finite, the axis's point (theta = 0) included. A frame without spots
// builds no new program and uploads nothing more; ten spots light with eight (the rest counted); a bad spot
// is refused naming its field, and the registry's adapter leaves it out instead, counting it.
TEST_F(LightingGl, SpotLightsLightTheirConeOnlyAndStayFinite) {
    double waterLeast = 0.0, waterMedian = 0.0; // the light the water gains per irradiance, without effects
    for (int run = 0; run < 3; ++run) {
        const bool compute = run == 1, withEffects = run == 2;
        SCOPED_TRACE(compute       ? "compute shading"
                     : withEffects ? "forward shading, an explosion"
                                   : "forward shading");
        ocean::OceanDesc desc;
        desc.computeShading = compute;
        desc.lighting = noFog();
        desc.lighting.sunDirection = {0.0, -1.0, 0.05}; // dusk, behind the camera
        desc.lighting.sunIntensity = 0.5f;
        desc.lighting.skyIntensity = 0.05f;
        const ocean::OceanComponent ocean = ocean::makeOcean(desc);
        const ocean::OceanInstance oceans[] = {{1, &ocean}};
        gl::FrameTargets targets(W, H);
        ocean::OceanRenderer renderer;
        Pose p;
        p.position = {1e6, -1e6, 30.0};
        p.headingDeg = 0.0;
        p.pitchDeg = -30.0;
        const ocean::OceanFrame frame =
            ocean::makeOceanFrame(p, FOV_Y, W, H, 17.25, targets.sceneFramebuffer().id());
        ocean::SpotLight spot;
        spot.position = p.position + glm::dvec3(0.0, 40.0, -5.0);
        spot.direction = {0.0, 0.0, -1.0};
        spot.frustumDeg = 20.0;
        // An explosion 6 m from the lamp's nadir, 3 s old: its grid is drawn under the light.
        ocean::Explosion explosion;
        explosion.center = glm::dvec2(spot.position) + glm::dvec2(6.0, 0.0);
        explosion.startTime = frame.time - 3.0;
        const ocean::EffectsView effects =
            withEffects ? ocean::EffectsView{{&explosion, 1}, {}} : ocean::EffectsView{};
        auto draw = [&](std::span<const ocean::SpotLight> spots) {
            const ocean::Status s = renderer.render({oceans, effects, spots}, frame);
            EXPECT_TRUE(s.ok()) << s.message;
            std::vector<float> rgba;
            targets.readScene(rgba);
            return rgba;
        };
        (void)draw({}); // builds the programs without spots, uploads the lighting's textures
        const std::vector<float> dark = draw({});
        const ocean::OceanStats plain = renderer.lastStats();
        const std::vector<float> lit = draw({&spot, 1});
        EXPECT_GT(renderer.lastStats().programsBuilt, 0); // the spots' variant
        EXPECT_EQ(renderer.lastStats().spots, 1);
        EXPECT_EQ(renderer.lastStats().uploads, plain.uploads);
        if (withEffects) {
            EXPECT_EQ(renderer.lastStats().explosions.drawn, 1)
                << "the explosion's grid is drawn under the lamp";
        }
        (void)draw({});
        EXPECT_EQ(renderer.lastStats().programsBuilt, 0) << "a frame without spots uses the plain programs";
        EXPECT_EQ(renderer.lastStats().spots, 0);
        expectFinite(lit, "lit");
        // Each pixel's ray against the sea: the flat sea outside the cone (the waves' few decimetres are far
        // inside the margin), the CPU's heights in it (heightsAt, a few fixed-point steps along the ray).
        // There the light gained per unit of the CPU's irradiance varies only with the view (Fresnel, the
        // refracted path) and the waves' tilt, a few per cent over this patch.
        auto seaHit = [&](const glm::dvec3& dir) {
            double z = 0.0;
            glm::dvec3 hit{};
            for (int k = 0; k < 6; ++k) {
                hit = p.position + dir * ((p.position.z - z) / -dir.z);
                const glm::dvec2 xy(hit);
                EXPECT_TRUE(ocean::heightsAt(ocean, effects, {&xy, 1}, frame.time, {&z, 1}).ok());
            }
            return hit;
        };
        int outside = 0, core = 0;
        double worstOutside = 0.0;
        std::vector<double> gainPerIrradiance;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const glm::dvec3 dir = pixelDirection(frame.camera, x, y);
                if (dir.z > -0.05)
                    continue;
                const glm::dvec3 hit = p.position + dir * (p.position.z / -dir.z);
                const double r = glm::length(glm::dvec2(hit) - glm::dvec2(spot.position));
                const size_t i = (static_cast<size_t>(y) * W + x) * 4;
                const glm::dvec3 a(dark[i], dark[i + 1], dark[i + 2]), b(lit[i], lit[i + 1], lit[i + 2]);
                if (r > 25.0 * std::tan(20.0 * std::numbers::pi / 180.0) + 4.0) {
                    ++outside;
                    worstOutside = std::max(worstOutside, relativeDifference(b, a));
                } else if (r < 25.0 * std::tan(16.0 * std::numbers::pi / 180.0)) {
                    core += r < 25.0 * std::tan(10.0 * std::numbers::pi / 180.0) ? 1 : 0;
                    gainPerIrradiance.push_back((luminance(b) - luminance(a)) /
                                                luminance(ocean::spotIrradiance(spot, seaHit(dir))));
                }
            }
        ASSERT_GT(gainPerIrradiance.size(), 100u);
        std::sort(gainPerIrradiance.begin(), gainPerIrradiance.end());
        const double least = gainPerIrradiance.front(), most = gainPerIrradiance.back();
        const double median = gainPerIrradiance[gainPerIrradiance.size() / 2];
        std::printf(
            "[spot] %s: %d pixels outside the cone (worst relative change %.2g); %zu in it (%d in its "
            "core), light gained per irradiance %.4g..%.4g, median %.4g\n",
            compute       ? "compute"
            : withEffects ? "forward+explosion"
                          : "forward",
            outside, worstOutside, gainPerIrradiance.size(), core, least, most, median);
        if (const char* dump = std::getenv("PACIFICA_LIGHTING_DUMP"); dump && *dump)
            capture::writeExrHalf(std::filesystem::path(dump) / ("spot_" + std::to_string(run) + ".exr"), W,
                                  H, 4, lit.data(), {});
        ASSERT_GT(outside, 1000);
        ASSERT_GT(core, 20);
        EXPECT_LT(worstOutside, 1e-5) << "the sea outside the cone changed";
        if (!withEffects) {
            // Measured 0.00393..0.00432 (median 0.00414), forward and compute alike.
            EXPECT_GT(least, 0.93 * median) << "the light gained does not follow spotIrradiance";
            EXPECT_LT(most, 1.07 * median) << "the light gained does not follow spotIrradiance";
            waterLeast = least;
            waterMedian = median;
        } else {
            // The explosion's foam covers part of the cone: a pixel gains between the water's share and the
            // foam's, FOAM_ALBEDO / pi SUN_DIFFUSE_SCALE (n.l <= 1) -- the lamp's diffuse light is scaled as
            // the sun's. Measured 0.0167..0.0475, median 0.0362 (the foam's bound 0.0509).
            const double foam = ocean::FOAM_ALBEDO / std::numbers::pi * ocean::SUN_DIFFUSE_SCALE;
            EXPECT_GT(least, 0.9 * waterLeast);
            EXPECT_LT(most, 1.02 * foam) << "the foam is lit more than a diffuse white can be";
            EXPECT_GT(median, 3.0 * waterMedian) << "the lamp does not light the explosion's foam";
        }
        // Ten spots: eight light the sea, two are counted out.
        std::vector<ocean::SpotLight> ten(10, spot);
        (void)draw(ten);
        EXPECT_EQ(renderer.lastStats().spots, ocean::MAX_SPOT_LIGHTS);
        EXPECT_EQ(renderer.lastStats().spotsDropped, 2);
        // A bad spot: the span API refuses the frame naming the field; the registry's adapter leaves it out.
        ocean::SpotLight bad = spot;
        bad.direction = glm::dvec3(0.0);
        const ocean::Status refused = renderer.render({oceans, {}, {&bad, 1}}, frame);
        EXPECT_EQ(refused.code, ocean::ErrorCode::InvalidArgument);
        EXPECT_EQ(refused.message, "OceanScene.spots[0].direction must be finite and non-zero");
        ecs::Registry registry;
        registry.emplace<ocean::OceanComponent>(registry.create(), ocean);
        registry.emplace<ocean::SpotLight>(registry.create(), bad);
        registry.emplace<ocean::SpotLight>(registry.create(), spot);
        ocean::render(renderer, registry, frame);
        EXPECT_EQ(renderer.lastStats().spots, 1);
        EXPECT_EQ(renderer.lastStats().spotsRejected, 1);
    }
}

// The spots' beams in the fog (spot.glsl spotScatter) against the CPU's spotInScatter, forward and compute
// shading: a searchlight 150 m ahead of a camera 20 m up, its 8-degree beam raised 19 degrees toward the east
// through a fog of 2e-3/m (no noise), so the beam crosses the sky and touches no sea. What a pixel gains with
// the lamp is the beam alone: zero where the CPU's integral along the pixel's ray is zero, and within 2 % of
// it across the beam (same quadrature, float against double). Eight samples or none: with none, no pixel
// changes.
TEST_F(LightingGl, SpotBeamsMatchTheCpuInScatter) {
    for (bool compute : {false, true}) {
        SCOPED_TRACE(compute ? "compute shading" : "forward shading");
        ocean::OceanDesc desc;
        desc.computeShading = compute;
        desc.lighting.fogDensity = 2e-3f;
        desc.lighting.fogNoise = 0.0f;
        desc.lighting.sunDirection = {0.0, -1.0, 0.02}; // dusk, behind the camera
        desc.lighting.sunIntensity = 0.5f;
        desc.lighting.skyIntensity = 0.05f;
        ocean::OceanComponent ocean = ocean::makeOcean(desc);
        const ocean::OceanInstance oceans[] = {{1, &ocean}};
        gl::FrameTargets targets(W, H);
        ocean::OceanRenderer renderer;
        Pose p;
        p.position = {1e6, -1e6, 20.0};
        p.headingDeg = 0.0;
        p.pitchDeg = 5.0;
        const ocean::OceanFrame frame =
            ocean::makeOceanFrame(p, FOV_Y, W, H, 17.25, targets.sceneFramebuffer().id());
        ocean::SpotLight spot;
        spot.position = p.position + glm::dvec3(-60.0, 150.0, 0.0);
        spot.direction = glm::normalize(glm::dvec3(1.0, 0.0, 0.35));
        spot.frustumDeg = 8.0;
        spot.range = 2000.0;
        auto draw = [&](std::span<const ocean::SpotLight> spots) {
            const ocean::Status s = renderer.render({oceans, {}, spots}, frame);
            EXPECT_TRUE(s.ok()) << s.message;
            std::vector<float> rgba;
            targets.readScene(rgba);
            return rgba;
        };
        const std::vector<float> dark = draw({});
        const std::vector<float> lit = draw({&spot, 1});
        expectFinite(lit, "lit");
        int beam = 0, close = 0, outside = 0, changedOutside = 0;
        double most = 0.0, worst = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const glm::dvec3 dir = pixelDirection(frame.camera, x, y);
                const double cpu =
                    ocean::spotInScatter(spot, ocean.desc.lighting, p.position, dir, 1e30, 8).g;
                const size_t i = (static_cast<size_t>(y) * W + x) * 4 + 1;
                const double gpu = static_cast<double>(lit[i]) - static_cast<double>(dark[i]);
                if (cpu == 0.0) {
                    ++outside;
                    changedOutside += gpu != 0.0 ? 1 : 0;
                } else if (cpu > 1e-6) {
                    ++beam;
                    const double err = std::abs(gpu / cpu - 1.0);
                    close += err < 0.02 ? 1 : 0;
                    worst = std::max(worst, err);
                    most = std::max(most, cpu);
                }
            }
        std::printf(
            "[beam] %s: %d beam pixels (brightest %.3g, sky %.3g), %d within 2%% (worst %.2g); %d outside, "
            "%d changed\n",
            compute ? "compute" : "forward", beam, most, luminance(meanRows(dark, 0, H / 4)), close, worst,
            outside, changedOutside);
        if (const char* dump = std::getenv("PACIFICA_LIGHTING_DUMP"); dump && *dump)
            capture::writeExrHalf(std::filesystem::path(dump) /
                                      (compute ? "beam_compute.exr" : "beam_forward.exr"),
                                  W, H, 4, lit.data(), {});
        ASSERT_GT(beam, 300);
        ASSERT_GT(outside, 10000);
        EXPECT_EQ(changedOutside, 0) << "pixels off the beam changed";
        EXPECT_GE(close, beam * 98 / 100) << "the GPU's beam differs from spotInScatter"; // 2624 of 2645
        EXPECT_LT(worst, 0.1);
        // No samples: the lamps still light the sea, but no pixel of this view (all of it off the lit sea)
        // changes.
        ocean.desc.lighting.spotScatterSamples = 0;
        const std::vector<float> noBeams = draw({&spot, 1});
        EXPECT_EQ(noBeams, dark) << "spotScatterSamples = 0 still draws beams";
    }
}
