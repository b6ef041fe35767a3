// GPU vs CPU: the heights the sea's vertex shader produces (captured with transform feedback) equal the
// CPU's double-precision HeightOctaves::heightAt at the same points — near the origin, 10^7 m from it, at
// t = 10^6 s, from 0.5 m and 15 km altitude. Also: every captured value is finite, the skirt stays flat.
#include "engine/Ecs.h"
#include "engine/Space.h"
#include "engine/gl/GlContext.h"
#include "ocean/Ocean.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanDebug.h"
#include "ocean/OceanHost.h"

#include "GlLayerTest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

using namespace pacifica;

namespace {

struct Case {
    const char* name;
    glm::dvec3 camera;
    double time;
};

class OceanGpuCpu : public gltest::GlTestOf<::testing::TestWithParam<Case>> {
protected:
    static void SetUpTestSuite() {
        renderer = std::make_unique<ocean::OceanRenderer>();
        entity = registry.create();
        // Frustum culling off: every vertex is displaced, so every vertex can be compared.
        ocean::OceanDesc desc;
        desc.cullVertices = false;
        registry.emplace<ocean::OceanComponent>(entity, ocean::makeOcean(desc));
    }
    static void TearDownTestSuite() { renderer.reset(); }
    static inline std::unique_ptr<ocean::OceanRenderer> renderer;
    static inline ecs::Registry registry;
    static inline ecs::Entity entity;
};

TEST_P(OceanGpuCpu, DisplacedHeightsMatchTheDoubleReference) {
    const Case c = GetParam();
    Pose pose;
    pose.position = c.camera;
    pose.pitchDeg = -20.0;
    ocean::OceanFrame frame;
    frame.camera = makeCameraFrame(pose, 1.0f, 16.0f / 9.0f, 0.05f);
    frame.time = c.time;
    const auto captured = ocean::debug::displacedVertices(*renderer, registry, entity, frame);
    std::vector<glm::vec3> gpu;
    for (const auto& v : captured)
        gpu.push_back(v.position);
    const auto& oc = registry.get<ocean::OceanComponent>(entity);
    const ocean::RadialGrid grid(oc.desc.grid);
    ASSERT_EQ(gpu.size(), grid.vertexCount());

    // Bound 1e-3 m (the required readback bound). Expected float error: the GPU forms tile coordinates as
    // rel * B + fract(camera * B) in float; at 40 km, rel * B reaches ~660 tiles for the 61 m octave, whose
    // float spacing (6e-5 tile) times the map's steepest slope (~0.13 m * 40 per tile) is ~3e-4 m.
    double worst = 0.0;
    size_t worstIndex = 0;
    const size_t displacedEnd = grid.vertexIndex(grid.desc().rings, 0); // the first skirt vertex
    for (size_t i = 0; i < gpu.size(); ++i) {
        ASSERT_TRUE(std::isfinite(gpu[i].x) && std::isfinite(gpu[i].y) && std::isfinite(gpu[i].z))
            << "vertex " << i;
        // Undo the Earth-curvature drop the shader applies with distance (same formula, in double).
        const double d = grid.vertices()[i * 2 + 1];
        const double gpuHeight = double(gpu[i].z) + c.camera.z + ocean::curvatureDrop(d);
        if (i >= displacedEnd) { // skirt: no waves, only the curvature drop (float: 1e-7 relative of it)
            EXPECT_NEAR(gpuHeight, 0.0, 1e-3 + (std::abs(c.camera.z) + ocean::curvatureDrop(d)) * 1.2e-7)
                << "skirt vertex " << i;
            continue;
        }
        const glm::dvec2 world = glm::dvec2(c.camera) + glm::dvec2(gpu[i].x, gpu[i].y);
        const double err = std::abs(gpuHeight - oc.surface->heightAt(world, c.time));
        if (err > worst) {
            worst = err;
            worstIndex = i;
        }
    }
    RecordProperty("max_abs_height_error_m", std::to_string(worst));
    std::printf("[%s] max |GPU - CPU| height = %.3g m (vertex %zu)\n", c.name, worst, worstIndex);
    // The GPU outputs z relative to the camera in float: at 15 km altitude that float's spacing is ~1 mm,
    // which the comparison cannot beat, so the bound grows by one spacing of the camera height.
    const float camZ = static_cast<float>(c.camera.z);
    const double zSpacing = double(std::nextafter(camZ, 2.0f * camZ + 1.0f)) - double(camZ);
    EXPECT_LT(worst, 1e-3 + zSpacing);
}

INSTANTIATE_TEST_SUITE_P(
    HardCases, OceanGpuCpu,
    ::testing::Values(Case{"origin_t0_30m", {0.0, 0.0, 30.0}, 0.0},
                      Case{"far_1e7_t1e6", {1.0e7 + 0.37, -1.0e7 + 0.81, 30.0}, 1.0e6 + 0.123},
                      Case{"low_0_5m", {-5432.1, 987.6, 0.5}, 77.7},
                      Case{"high_15km", {2.5e6, 3.3e6, 15000.0}, 3.6e5}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

class OceanGpuCpuErrors : public gltest::GlTest {};

TEST_F(OceanGpuCpuErrors, EntityWithoutOceanIsRejected) {
    ocean::OceanRenderer r;
    ecs::Registry reg;
    const ecs::Entity e = reg.create();
    EXPECT_THROW(ocean::debug::displacedVertices(r, reg, e, {}), std::invalid_argument);
}

} // namespace
