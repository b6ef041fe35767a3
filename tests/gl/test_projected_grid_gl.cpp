// GL test of the projected grid as drawn: ocean/shaders/ocean_projected.vert with a flat stand-in surface
// model (modelDisplacement = 0) and a fragment shader writing 1, rendered into a 320x180 target for a sweep
// of camera poses (0.5 m to 15 km, straight down to 45 degrees up, rolled, 10^7 m from the origin, curved
// and flat sea). Every pixel whose centre ray hits the sea on the CPU (double-precision ray / drop-surface
// intersection) must be covered, and no pixel above the horizon may be: no gaps at the horizon or the
// screen's edges, and no geometry folded over the sky.
#include <epoxy/gl.h>

#include "engine/Space.h"
#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"
#include "engine/gl/Shader.h"
#include "ocean/OceanConstants.h"
#include "ocean/OceanShaders.h"
#include "ocean/ProjectedGrid.h"

#include "GlLayerTest.h"

#include <gtest/gtest.h>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

using namespace pacifica;
using ocean::ProjectedGrid;

namespace {

constexpr double PI = 3.14159265358979323846;
constexpr int WIDTH = 320, HEIGHT = 180;

/// First hit of the ray along `dir` (camera at the origin, height h) with the sea z = -h - d^2 / 2R
/// (flat when R = 0), as its horizontal distance; nothing if it misses.
std::optional<double> seaHitDistance(const glm::dvec3& dir, double h, double R) {
    const double rho = std::hypot(dir.x, dir.y);
    const double a = R > 0.0 ? rho * rho / (2.0 * R) : 0.0;
    if (dir.z >= 0.0)
        return std::nullopt;
    const double disc = dir.z * dir.z - 4.0 * a * h;
    if (disc < 0.0)
        return std::nullopt;
    return rho * 2.0 * h / (-dir.z + std::sqrt(disc));
}

class ProjectedGridGl : public gltest::GlTest {}; // GlEnvironment prints GL_RENDERER

TEST_F(ProjectedGridGl, EverySeaPixelIsCoveredAndNoSkyPixel) {
    const std::vector<gl::ShaderSource> vertex = {
        {"<ocean constants>", ocean::shaderConstantDefines()},
        {"<flat model>", "vec3 modelDisplacement(vec2 rel) { return vec3(0.0); }\n"},
        {"ocean_projected.vert", std::string(ocean::shaderText("ocean_projected.vert"))}};
    const std::vector<gl::ShaderSource> fragment = {
        {"<coverage>", "out vec4 fragColor;\nvoid main() { fragColor = vec4(1.0); }\n"}};
    const gl::Program program = gl::buildProgram(
        {{gl::ShaderStage::Vertex, vertex}, {gl::ShaderStage::Fragment, fragment}}, "coverage");
    const GLuint prog = program.id();

    const ProjectedGrid grid({}); // the default 256 x 512 grid, maxDisplacement 3 m, guard band 0.05
    const gl::Buffer vertices =
        gl::Buffer::create(grid.vertices().size() * sizeof(float), grid.vertices().data());
    const gl::Buffer indices =
        gl::Buffer::create(grid.indices().size() * sizeof(uint32_t), grid.indices().data());
    const gl::VertexArray vao = gl::VertexArray::create();
    glVertexArrayVertexBuffer(vao.id(), 0, vertices.id(), 0, 2 * sizeof(float));
    glVertexArrayElementBuffer(vao.id(), indices.id());
    glEnableVertexArrayAttrib(vao.id(), 0);
    glVertexArrayAttribFormat(vao.id(), 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao.id(), 0, 0);

    const gl::Texture color = gl::Texture::create2D(GL_R8, WIDTH, HEIGHT);
    gl::Framebuffer fbo = gl::Framebuffer::create();
    fbo.attachColor(0, color);
    fbo.checkComplete("projected grid coverage");
    glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    glViewport(0, 0, WIDTH, HEIGHT);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); // Space.h's reverse-Z projection
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(prog);
    glBindVertexArray(vao.id());

    int poses = 0, drawn = 0;
    long long seaPixels = 0, uncovered = 0, skyCovered = 0, withinTolerance = 0;
    double worstMiss = 0.0; // pixels: the farthest from the horizon a pixel within the tolerance differed
    double maxGap = 0.0;    // radians: the largest horizon gap of the tessellation
    std::vector<unsigned char> pixels(size_t(WIDTH) * HEIGHT);
    for (double R : {ocean::EARTH_RADIUS, 0.0})
        for (double h : {0.5, 2.0, 10.0, 100.0, 1000.0, 5000.0, 15000.0})
            for (double pitch : {-90.0, -30.0, -10.0, -3.0, 0.0, 3.0, 10.0, 45.0})
                for (double roll : {0.0, 60.0}) {
                    Pose pose;
                    pose.position = {1e7, -1e7, h};
                    pose.headingDeg = 137.5;
                    pose.pitchDeg = pitch;
                    pose.rollDeg = roll;
                    const CameraFrame cam =
                        makeCameraFrame(pose, float(60.0 * PI / 180.0), float(WIDTH) / HEIGHT, 0.1f);
                    const ProjectedGrid::Frame f = grid.frame(cam, R);
                    ++poses;
                    glClearColor(0, 0, 0, 0);
                    glClear(GL_COLOR_BUFFER_BIT);
                    if (f.visible) {
                        ++drawn;
                        const std::array<glm::vec4, 4> corners = f.cornerUniforms();
                        glProgramUniform4fv(prog, glGetUniformLocation(prog, "uCorners"), 4,
                                            glm::value_ptr(corners[0]));
                        glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "uViewProj"), 1, GL_FALSE,
                                                  glm::value_ptr(cam.viewProj));
                        glProgramUniform1f(prog, glGetUniformLocation(prog, "uCameraHeight"), float(h));
                        glProgramUniform1f(prog, glGetUniformLocation(prog, "uDisplaceRadius"), 1e30f);
                        glProgramUniform1f(prog, glGetUniformLocation(prog, "uCurvature"),
                                           R > 0.0 ? float(1.0 / (2.0 * R)) : 0.0f);
                        glProgramUniform3f(prog, glGetUniformLocation(prog, "uCull"), 0.0f, 0.0f, 0.0f);
                        glDrawElements(GL_TRIANGLES, GLsizei(grid.indices().size()), GL_UNSIGNED_INT,
                                       nullptr);
                    }
                    glPixelStorei(GL_PACK_ALIGNMENT, 1);
                    glReadPixels(0, 0, WIDTH, HEIGHT, GL_RED, GL_UNSIGNED_BYTE, pixels.data());

                    // Tolerances, from the geometry and the rasteriser:
                    //  - Triangles are flat, and the elevation seen along a straight edge is monotonic, so
                    //  the
                    //    drawn horizon in each column of the grid is its highest vertex, a little below the
                    //    true (tangent) horizon: rows near the horizon are far apart (their spacing grows as
                    //    distance^2 / projector height), and the flat sea stops FLAT_HORIZON_GAP below eye
                    //    level. That gap is measured on this frame's grid: the largest over the columns of
                    //    the smallest angle between a vertex and the horizon.
                    //  - The rasteriser snaps vertices to 1/256 pixel (llvmpipe's 8 subpixel bits).
                    const double pixelAngle = 60.0 * PI / 180.0 / HEIGHT;
                    const double snap = pixelAngle / 256.0;
                    const double dip = R > 0.0 ? std::atan(std::sqrt(2.0 * h / R)) : 0.0;
                    double gap = 0.0;
                    if (f.visible) {
                        const glm::dmat4 vp(cam.viewProj);
                        const int nx = grid.desc().resolutionX;
                        const size_t rows = grid.vertexCount() / size_t(nx);
                        for (int i = 0; i < nx; ++i) {
                            double columnGap = 1e9;
                            bool onScreen = false;
                            for (size_t j = 0; j < rows; ++j) {
                                const float* uv = &grid.vertices()[2 * (j * size_t(nx) + size_t(i))];
                                const glm::dvec2 q = f.gridPoint({uv[0], uv[1]});
                                const double rho = glm::length(q);
                                const double z = -h - (R > 0.0 ? rho * rho / (2.0 * R) : 0.0);
                                const double g = -std::atan2(z, rho) - dip;
                                if (g < columnGap) {
                                    columnGap = g;
                                    const glm::dvec4 c = vp * glm::dvec4(q, z, 1.0);
                                    onScreen = c.w > 0.0 && std::abs(c.x) <= c.w && std::abs(c.y) <= c.w;
                                }
                            }
                            if (onScreen) // the column's horizon is drawn on the screen
                                gap = std::max(gap, columnGap);
                        }
                    }
                    maxGap = std::max(maxGap, gap);
                    EXPECT_LT(gap, 0.05 * pixelAngle) << "h " << h << " pitch " << pitch << " roll " << roll;
                    const double below = gap + snap, above = snap;

                    const glm::dmat4 inv = glm::inverse(glm::dmat4(cam.viewProj));
                    int poseUncovered = 0, poseSky = 0;
                    for (int y = 0; y < HEIGHT; ++y)
                        for (int x = 0; x < WIDTH; ++x) {
                            const glm::dvec4 p = inv * glm::dvec4((x + 0.5) / WIDTH * 2.0 - 1.0,
                                                                  (y + 0.5) / HEIGHT * 2.0 - 1.0, 1.0, 1.0);
                            const glm::dvec3 d = glm::normalize(glm::dvec3(p) / p.w);
                            const double depression = -std::asin(d.z) - dip; // below the horizon
                            const bool covered = pixels[size_t(y) * WIDTH + x] > 127;
                            const bool sea = seaHitDistance(d, h, R).has_value();
                            seaPixels += sea;
                            if (sea && !covered) {
                                if (depression < below) {
                                    ++withinTolerance;
                                    worstMiss = std::max(worstMiss, depression / pixelAngle);
                                } else {
                                    ++poseUncovered;
                                }
                            }
                            if (!sea && covered) {
                                if (-depression < above) {
                                    ++withinTolerance;
                                    worstMiss = std::max(worstMiss, -depression / pixelAngle);
                                } else {
                                    ++poseSky;
                                }
                            }
                        }
                    uncovered += poseUncovered;
                    skyCovered += poseSky;
                    EXPECT_EQ(poseUncovered, 0) << "h " << h << " pitch " << pitch << " roll " << roll
                                                << " R " << R << ": sea pixels not covered";
                    EXPECT_EQ(poseSky, 0) << "h " << h << " pitch " << pitch << " roll " << roll << " R " << R
                                          << ": sky pixels covered by the grid";
                }
    ASSERT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    std::printf(
        "[projected grid GL] %d poses (%d drawn), %lld sea pixels: %lld uncovered, %lld sky pixels "
        "covered; %lld pixels within the horizon tolerance (centre at most %.3f px from the horizon); "
        "largest tessellation gap below the horizon %.3g rad\n",
        poses, drawn, seaPixels, uncovered, skyCovered, withinTolerance, worstMiss, maxGap);
    EXPECT_GT(seaPixels, 1000000);
}

} // namespace
