// The find_package consumer: uses only installed public headers and Pacifica:: targets. Checks the CPU
// ocean maths, then renders one frame headless and checks the pixels are finite scene-linear values.
#include <engine/Ecs.h>
#include <engine/Space.h>
#include <engine/gl/FrameTargets.h>
#include <engine/gl/GlContext.h>
#include <ocean/Ocean.h>
#include <ocean/OceanHost.h>
#include <recording/EarthFrame.h>

#include <epoxy/gl.h>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
    const pacifica::ocean::RadialGrid grid({});
    if (std::abs(grid.radius(grid.desc().rings - 1) - 40000.0) > 0.04) {
        std::fprintf(stderr, "consumer: radial grid r_max %.6f != 40000\n",
                     grid.radius(grid.desc().rings - 1));
        return 1;
    }
    // Pacifica::recording: a point 1 km north of the frame's origin is 1 km up its y axis.
    const pacifica::recording::EarthFrame earth(44.5, 37.0);
    const glm::dvec3 north = earth.toWorld(44.5 + 1000.0 / 111132.0, 37.0, 0.0);
    if (std::abs(north.y - 1000.0) > 2.0 || std::abs(north.x) > 1e-6) {
        std::fprintf(stderr, "consumer: EarthFrame put 1 km north at (%f, %f)\n", north.x, north.y);
        return 1;
    }
    auto context = pacifica::gl::createHeadlessContext();
    pacifica::ecs::Registry registry;
    const auto e = registry.create();
    auto& ocean = registry.emplace<pacifica::ocean::OceanComponent>(e, pacifica::ocean::makeOcean({}));
    const double h = ocean.surface->heightAt({100.0, 200.0}, 5.0);
    if (!std::isfinite(h) || std::abs(h) > 10.0) {
        std::fprintf(stderr, "consumer: heightAt gave %f\n", h);
        return 1;
    }
    pacifica::gl::FrameTargets targets(64, 36);
    pacifica::ocean::OceanRenderer renderer;
    pacifica::Pose pose;
    pose.position = {1e7, -2e6, 30.0};
    pose.pitchDeg = -10.0;
    pacifica::ocean::OceanFrame frame;
    frame.camera = pacifica::makeCameraFrame(pose, 1.0f, 64.0f / 36.0f, 0.05f);
    frame.time = 1e6;
    frame.targetFramebuffer = targets.sceneFramebuffer().id();
    frame.width = 64;
    frame.height = 36;
    render(renderer, registry, frame);
    std::vector<float> rgba;
    targets.readScene(rgba);
    for (float v : rgba)
        if (!std::isfinite(v) || v < 0.0f) {
            std::fprintf(stderr, "consumer: bad pixel value %f\n", v);
            return 1;
        }
    std::printf("consumer OK: heightAt = %.4f m, %d draws, renderer %s\n", h, renderer.lastStats().draws,
                context->info().renderer.c_str());
    return 0;
}
