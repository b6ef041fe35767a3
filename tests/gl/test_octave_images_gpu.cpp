// Painted octave height maps end to end, from image files: a cosine written to an EXR and a 4-frame
// travelling cosine strip are read back with the tools' loader (tools/src/ImageInputs.cpp, as
// `pacifica replay --height-map` does), the loaded map holds the analytic cosine in the documented
// orientation (top row = north edge), and the heights the sea's vertex shader draws from them (transform
// feedback) equal the CPU's HeightOctaves::heightAt — near the origin and at 10^7 m / t = 10^6 s, the same
// 1e-3 m bound as tests/gl/test_ocean_gpu_cpu.cpp.
#include "ImageInputs.h"
#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/capture/Capture.h"
#include "engine/gl/GlContext.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanDebug.h"
#include "ocean/OceanHost.h"

#include "GlLayerTest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <unistd.h>

using namespace pacifica;

namespace {

constexpr int W = 64;
constexpr double TWO_PI = 2.0 * std::numbers::pi;

/// cos(2 pi (3 u + 2 v) - 2 pi f / 4) at texel centres, v northward.
double cosine(int x, int y, int frame) {
    const double u = (x + 0.5) / W, v = (y + 0.5) / W;
    return std::cos(TWO_PI * (3.0 * u + 2.0 * v) - TWO_PI * frame / 4.0);
}

/// Writes `frames` square frames stacked top to bottom, each row top-down = north edge first, as RGB.
std::filesystem::path writeCosineExr(const std::string& name, int frames) {
    std::vector<float> rgb;
    for (int f = 0; f < frames; ++f)
        for (int row = 0; row < W; ++row)
            for (int x = 0; x < W; ++x)
                for (int c = 0; c < 3; ++c)
                    rgb.push_back(static_cast<float>(cosine(x, W - 1 - row, f)));
    const auto path = std::filesystem::temp_directory_path() /
                      ("pacifica_" + std::to_string(getpid()) + "_" + name + ".exr");
    capture::writeExrHalf(path, W, W * frames, 3, rgb.data(), {});
    return path;
}

class OctaveImagesGpu : public gltest::GlTest {
protected:
    static void SetUpTestSuite() {
        still = writeCosineExr("still", 1);
        strip = writeCosineExr("strip", 4);
        renderer = std::make_unique<ocean::OceanRenderer>();
        entity = registry.create();
        ocean::OceanDesc desc;
        desc.cullVertices = false; // every vertex displaced, so every vertex compares
        desc.octaves.images.assign(desc.octaves.octaves.size(), {});
        desc.octaves.images[0] = tools::loadHeightMap(still); // the 1109 m swell: painted, still
        desc.octaves.images[1] = tools::loadHeightMap(strip); // the 256 m octave: painted, 4 frames
        desc.octaves.mapSize = W;
        desc.octaves.frames = 4;
        registry.emplace<ocean::OceanComponent>(entity, ocean::makeOcean(desc));
    }
    static void TearDownTestSuite() {
        renderer.reset();
        std::filesystem::remove(still);
        std::filesystem::remove(strip);
    }
    static const ocean::HeightOctaves& octaves() {
        return dynamic_cast<const ocean::HeightOctaves&>(
            *registry.get<ocean::OceanComponent>(entity).surface);
    }
    static inline std::filesystem::path still, strip;
    static inline std::unique_ptr<ocean::OceanRenderer> renderer;
    static inline ecs::Registry registry;
    static inline ecs::Entity entity;
};

TEST_F(OctaveImagesGpu, LoadedMapsHoldTheCosineNorthUp) {
    const ocean::HeightOctaves& s = octaves();
    // The loader normalises to unit RMS: a whole-cycle cosine (RMS 1/sqrt 2) becomes sqrt(2) cos. Error
    // bound: the EXR's half (|cos| <= 1: <= 2^-12, times sqrt 2) plus the map's half (|h| <= 1.42: <= 2^-11).
    const double bound = std::sqrt(2.0) * std::ldexp(1.0, -12) + std::ldexp(1.0, -11);
    double worst = 0.0;
    for (int f = 0; f < 4; ++f)
        for (int y = 0; y < W; y += 3)
            for (int x = 0; x < W; x += 5) {
                const glm::dvec2 u = (glm::dvec2(x, y) + 0.5) / double(W);
                worst = std::max(worst, std::abs(s.sampleHeight(0, ocean::VertexFilter::Bilinear, u, f) -
                                                 std::sqrt(2.0) * cosine(x, y, 0)));
                worst = std::max(worst, std::abs(s.sampleHeight(1, ocean::VertexFilter::Bilinear, u, f) -
                                                 std::sqrt(2.0) * cosine(x, y, f)));
            }
    EXPECT_LE(worst, bound);
    std::printf("loaded maps vs sqrt(2) cos: max error %.3g (bound %.3g)\n", worst, bound);
}

TEST_F(OctaveImagesGpu, GpuHeightsEqualTheCpuForLoadedMaps) {
    struct Case {
        const char* name;
        glm::dvec3 camera;
        double time;
    };
    for (const Case& c : {Case{"origin_t0_30m", {0.0, 0.0, 30.0}, 0.0},
                          Case{"far_1e7_t1e6", {1.0e7 + 0.37, -1.0e7 + 0.81, 30.0}, 1.0e6 + 0.123}}) {
        Pose pose;
        pose.position = c.camera;
        pose.pitchDeg = -20.0;
        ocean::OceanFrame frame;
        frame.camera = makeCameraFrame(pose, 1.0f, 16.0f / 9.0f, 0.05f);
        frame.time = c.time;
        const auto captured = ocean::debug::displacedVertices(*renderer, registry, entity, frame);
        const auto& oc = registry.get<ocean::OceanComponent>(entity);
        const ocean::RadialGrid grid(oc.desc.grid);
        ASSERT_EQ(captured.size(), grid.vertexCount());
        const size_t displacedEnd = grid.vertexIndex(grid.desc().rings, 0); // the first skirt vertex
        double worst = 0.0, range = 0.0;
        for (size_t i = 0; i < displacedEnd; ++i) {
            const glm::vec3 p = captured[i].position;
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << "vertex " << i;
            const double d = grid.vertices()[i * 2 + 1];
            const double gpuHeight = double(p.z) + c.camera.z + ocean::curvatureDrop(d);
            const glm::dvec2 world = glm::dvec2(c.camera) + glm::dvec2(p.x, p.y);
            const double cpu = oc.surface->heightAt(world, c.time);
            worst = std::max(worst, std::abs(gpuHeight - cpu));
            range = std::max(range, std::abs(cpu));
        }
        std::printf("[%s] loaded maps: max |GPU - CPU| = %.3g m (heights up to %.2f m)\n", c.name, worst,
                    range);
        // Same bound and reasoning as test_ocean_gpu_cpu.cpp: 1e-3 m, float tile coordinates at 40 km.
        EXPECT_LT(worst, 1e-3) << c.name;
        EXPECT_GT(range, 0.5) << c.name; // the painted swell (0.55 m x sqrt 2 peak) is there
    }
}

} // namespace
