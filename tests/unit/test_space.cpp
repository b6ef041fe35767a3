// Unit tests for engine/Space.h and engine/Pose.h: camera-relative precision far from the origin, the
// rotation-only view matrix, the reverse-Z infinite projection, attitude conventions and pose slerp.
#include "engine/Pose.h"
#include "engine/Space.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <stdexcept>

using pacifica::attitudeMatrix;
using pacifica::CameraFrame;
using pacifica::interpolatePose;
using pacifica::makeCameraFrame;
using pacifica::perspectiveReverseZInfinite;
using pacifica::Pose;
using pacifica::toCameraRelative;
using pacifica::viewRotation;

namespace {

constexpr double PI = 3.14159265358979323846;

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tol, const char* what) {
    EXPECT_NEAR(actual.x, expected.x, tol) << what;
    EXPECT_NEAR(actual.y, expected.y, tol) << what;
    EXPECT_NEAR(actual.z, expected.z, tol) << what;
}

// Signed difference of two headings in degrees, in (-180, 180].
double headingDifference(double a, double b) {
    double d = std::fmod(a - b, 360.0);
    if (d > 180.0)
        d -= 360.0;
    if (d <= -180.0)
        d += 360.0;
    return d;
}

// Window depth of an eye-space point under a [0,1]-depth projection.
float depthOf(const glm::mat4& proj, const glm::vec3& eye) {
    const glm::vec4 clip = proj * glm::vec4(eye, 1.0f);
    return clip.z / clip.w;
}

} // namespace

TEST(Space, CameraRelativeKeepsPrecisionFarFromOrigin) {
    const glm::dvec3 camera(1e7, -1e7, 1000.0);
    // A point 0.37 m from the camera (|(2, -2, 1)/3| = 1).
    const glm::dvec3 offset = 0.37 * glm::dvec3(2.0, -2.0, 1.0) / 3.0;
    ASSERT_NEAR(glm::length(offset), 0.37, 1e-15);
    const glm::dvec3 world = camera + offset;

    // Subtracting in double: the double spacing at 1e7 is 1.9e-9 m and the float rounding of a 0.37 m
    // offset is ~3e-8 m, so the error is far below the 1e-6 m bound.
    const glm::vec3 rel = toCameraRelative(world, camera);
    const double relError = glm::length(glm::dvec3(rel) - offset);
    EXPECT_LT(relError, 1e-6);

    // Naive: round both to float first. Float spacing in [2^23, 2^24) = [8.4e6, 1.7e7) is 1 m, so x and y
    // each snap to a whole metre and the 0.25 m offsets vanish: the error is ~0.35 m, above the 0.1 m bound.
    const glm::vec3 naive = glm::vec3(world) - glm::vec3(camera);
    const double naiveError = glm::length(glm::dvec3(naive) - offset);
    EXPECT_GT(naiveError, 0.1);
}

TEST(Pose, AttitudeMatrixConventions) {
    const double tol = 1e-12;
    {
        const glm::dmat3 m = attitudeMatrix(0, 0, 0);
        expectNear(m[0], {0, 1, 0}, tol, "heading 0: forward north");
        expectNear(m[1], {1, 0, 0}, tol, "heading 0: right east");
        expectNear(m[2], {0, 0, 1}, tol, "heading 0: up");
    }
    {
        const glm::dmat3 m = attitudeMatrix(90, 0, 0);
        expectNear(m[0], {1, 0, 0}, tol, "heading 90: forward east");
        expectNear(m[1], {0, -1, 0}, tol, "heading 90: right south");
    }
    expectNear(attitudeMatrix(180, 0, 0)[0], {0, -1, 0}, tol, "heading 180: forward south");
    expectNear(attitudeMatrix(270, 0, 0)[0], {-1, 0, 0}, tol, "heading 270: forward west");
    {
        const glm::dmat3 m = attitudeMatrix(0, 90, 0);
        expectNear(m[0], {0, 0, 1}, tol, "pitch 90: forward up");
        expectNear(m[2], {0, -1, 0}, tol, "pitch 90: up points back (south)");
    }
    {
        const glm::dmat3 m = attitudeMatrix(0, 0, 90);
        expectNear(m[1], {0, 0, -1}, tol, "roll 90: right wing down");
        expectNear(m[2], {1, 0, 0}, tol, "roll 90: up points east");
        expectNear(m[0], {0, 1, 0}, tol, "roll leaves forward alone");
    }
    {
        const glm::dmat3 m = attitudeMatrix(30, 0, 0);
        expectNear(m[0], {0.5, std::sqrt(3.0) / 2, 0}, tol, "heading 30 is clockwise from north");
    }
    // Orthonormal for a general attitude, with forward x right = -up (the column order's det is -1).
    const glm::dmat3 m = attitudeMatrix(123, -37, 61);
    EXPECT_NEAR(glm::length(m[0]), 1.0, tol);
    EXPECT_NEAR(glm::length(m[1]), 1.0, tol);
    EXPECT_NEAR(glm::dot(m[0], m[1]), 0.0, tol);
    EXPECT_NEAR(glm::dot(m[0], m[2]), 0.0, tol);
    EXPECT_NEAR(glm::dot(m[1], m[2]), 0.0, tol);
    expectNear(glm::cross(m[0], m[1]), -m[2], tol, "forward x right = -up");
    EXPECT_NEAR(glm::determinant(m), -1.0, tol);
    EXPECT_NEAR(m[0].z, std::sin(-37 * PI / 180), tol); // pitch sets the climb of forward
}

TEST(Space, ViewRotationMapsBodyAxesToEyeAxes) {
    const double angles[][3] = {{0, 0, 0},     {90, 0, 0},     {180, 10, 0},   {271, -45, 30},
                                {45, 89, -60}, {12, -80, 170}, {359, 5, -179}, {200, 33, 90}};
    for (const auto& a : angles) {
        Pose pose;
        pose.position = {1e7, -1e7, 3000};
        pose.headingDeg = a[0];
        pose.pitchDeg = a[1];
        pose.rollDeg = a[2];
        const glm::mat4 view = viewRotation(pose);
        const glm::dmat3 body = attitudeMatrix(a[0], a[1], a[2]);
        const glm::vec3 fwd = glm::vec3(view * glm::vec4(glm::vec3(body[0]), 0.0f));
        const glm::vec3 right = glm::vec3(view * glm::vec4(glm::vec3(body[1]), 0.0f));
        const glm::vec3 up = glm::vec3(view * glm::vec4(glm::vec3(body[2]), 0.0f));
        const std::string what = "heading " + std::to_string(a[0]) + " pitch " + std::to_string(a[1]) +
                                 " roll " + std::to_string(a[2]);
        expectNear(glm::dvec3(fwd), {0, 0, -1}, 1e-6, what.c_str());
        expectNear(glm::dvec3(right), {1, 0, 0}, 1e-6, what.c_str());
        expectNear(glm::dvec3(up), {0, 1, 0}, 1e-6, what.c_str());
        // No translation, ever: the GPU never sees the camera's absolute position.
        EXPECT_EQ(view[3], glm::vec4(0, 0, 0, 1)) << what;
        EXPECT_EQ(view[0][3], 0.0f);
        EXPECT_EQ(view[1][3], 0.0f);
        EXPECT_EQ(view[2][3], 0.0f);
        EXPECT_NEAR(glm::determinant(view), 1.0f, 1e-5f) << what; // a proper rotation
    }
}

TEST(Space, ReverseZInfiniteProjection) {
    const float zNear = 0.1f;
    const float fovY = glm::radians(60.0f);
    const glm::mat4 p = perspectiveReverseZInfinite(fovY, 16.0f / 9.0f, zNear);
    EXPECT_EQ(depthOf(p, {0, 0, -zNear}), 1.0f); // n / n, exact
    const float far = depthOf(p, {0, 0, -40000.0f});
    EXPECT_LT(far, 1e-5f); // 0.1 / 40000 = 2.5e-6
    EXPECT_GT(far, 0.0f);
    EXPECT_NEAR(far, 2.5e-6f, 1e-11f);
    EXPECT_NEAR(depthOf(p, {0, 0, -1.0f}), 0.1f, 1e-7f);
    // Monotonic: nearer is greater (depth test GL_GREATER).
    EXPECT_GT(depthOf(p, {0, 0, -10.0f}), depthOf(p, {0, 0, -11.0f}));
    // Points behind the camera get w < 0 and are clipped.
    EXPECT_LT((p * glm::vec4(0, 0, 1, 1)).w, 0.0f);
    // The top edge of the frustum at distance d is at y = d tan(fovY/2): maps to NDC y = 1.
    const float d = 500.0f;
    const glm::vec4 top = p * glm::vec4(0, d * std::tan(fovY / 2), -d, 1);
    EXPECT_NEAR(top.y / top.w, 1.0f, 1e-6f);
    const glm::vec4 side = p * glm::vec4(d * std::tan(fovY / 2) * 16.0f / 9.0f, 0, -d, 1);
    EXPECT_NEAR(side.x / side.w, 1.0f, 1e-6f);

    EXPECT_THROW(perspectiveReverseZInfinite(fovY, 1.0f, 0.0f), std::invalid_argument);
    EXPECT_THROW(perspectiveReverseZInfinite(0.0f, 1.0f, 0.1f), std::invalid_argument);
    EXPECT_THROW(perspectiveReverseZInfinite(4.0f, 1.0f, 0.1f), std::invalid_argument);
    EXPECT_THROW(perspectiveReverseZInfinite(fovY, -1.0f, 0.1f), std::invalid_argument);
}

TEST(Space, CameraFrameEndToEndFarFromOrigin) {
    Pose pose;
    pose.position = {1e7, -1e7, 1000.0};
    pose.headingDeg = 73;
    pose.pitchDeg = -12;
    pose.rollDeg = 8;
    const CameraFrame cam = makeCameraFrame(pose, glm::radians(50.0f), 1.5f, 0.1f);
    EXPECT_EQ(cam.origin, pose.position);
    EXPECT_EQ(cam.fovY, glm::radians(50.0f));
    EXPECT_EQ(cam.aspect, 1.5f);
    EXPECT_EQ(cam.zNear, 0.1f);
    EXPECT_EQ(cam.view, viewRotation(pose));
    EXPECT_EQ(cam.viewProj, cam.proj * cam.view);

    const glm::dmat3 body = attitudeMatrix(pose.headingDeg, pose.pitchDeg, pose.rollDeg);
    // A point straight ahead at zNear lands at the screen centre with depth 1; at 40 km, depth ~0.
    for (const double dist : {0.1, 40000.0}) {
        const glm::dvec3 world = pose.position + body[0] * dist;
        const glm::vec4 clip = cam.viewProj * glm::vec4(toCameraRelative(world, cam.origin), 1.0f);
        EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-5f);
        EXPECT_NEAR(clip.y / clip.w, 0.0f, 1e-5f);
        const float depth = clip.z / clip.w;
        if (dist < 1.0) {
            EXPECT_NEAR(depth, 1.0f, 1e-5f);
        } else {
            EXPECT_LT(depth, 1e-5f);
            EXPECT_GT(depth, 0.0f);
        }
    }
}

TEST(Pose, InterpolateTakesShortestArcThroughNorth) {
    Pose a, b;
    a.headingDeg = 350;
    b.headingDeg = 10;
    a.position = {0, 0, 100};
    b.position = {10, -20, 300};
    const Pose mid = interpolatePose(a, b, 0.5);
    EXPECT_NEAR(headingDifference(mid.headingDeg, 0.0), 0.0, 1e-9) << mid.headingDeg; // not 180
    EXPECT_GE(mid.headingDeg, 0.0);
    EXPECT_LT(mid.headingDeg, 360.0);
    EXPECT_NEAR(mid.pitchDeg, 0.0, 1e-9);
    EXPECT_NEAR(mid.rollDeg, 0.0, 1e-9);
    expectNear(mid.position, {5, -10, 200}, 1e-12, "position is linear");

    const Pose quarter = interpolatePose(a, b, 0.25);
    EXPECT_NEAR(headingDifference(quarter.headingDeg, 355.0), 0.0, 1e-9) << quarter.headingDeg;
}

TEST(Pose, InterpolateEndpointsAndSingleAxisMotion) {
    Pose a, b;
    a.headingDeg = 40;
    a.pitchDeg = 10;
    a.rollDeg = -20;
    b.headingDeg = 100;
    b.pitchDeg = -25;
    b.rollDeg = 35;
    for (const double s : {0.0, 1.0}) {
        const Pose& ref = s == 0.0 ? a : b;
        const Pose p = interpolatePose(a, b, s);
        EXPECT_NEAR(headingDifference(p.headingDeg, ref.headingDeg), 0.0, 1e-9);
        EXPECT_NEAR(p.pitchDeg, ref.pitchDeg, 1e-9);
        EXPECT_NEAR(p.rollDeg, ref.rollDeg, 1e-9);
    }
    // Pure pitch change about a fixed horizontal axis: slerp moves the angle linearly.
    Pose c, d;
    c.headingDeg = d.headingDeg = 200;
    c.pitchDeg = 0;
    d.pitchDeg = 60;
    const Pose m = interpolatePose(c, d, 0.5);
    EXPECT_NEAR(m.pitchDeg, 30.0, 1e-9);
    EXPECT_NEAR(headingDifference(m.headingDeg, 200.0), 0.0, 1e-9);
    EXPECT_NEAR(m.rollDeg, 0.0, 1e-9);
    // Pure roll through +-180 also takes the short way.
    Pose e, f;
    e.rollDeg = 170;
    f.rollDeg = -170;
    const Pose r = interpolatePose(e, f, 0.5);
    EXPECT_NEAR(std::fabs(r.rollDeg), 180.0, 1e-9);
    EXPECT_NEAR(r.pitchDeg, 0.0, 1e-9);
}

TEST(Pose, InterpolateThroughVerticalFoldsRollIntoHeading) {
    Pose a, b;
    a.headingDeg = 30;
    a.pitchDeg = 90;
    b = a;
    const Pose p = interpolatePose(a, b, 0.5);
    EXPECT_NEAR(p.pitchDeg, 90.0, 1e-6);
    EXPECT_EQ(p.rollDeg, 0.0);
    // Same body axes as the input.
    const glm::dmat3 in = attitudeMatrix(a.headingDeg, a.pitchDeg, a.rollDeg);
    const glm::dmat3 out = attitudeMatrix(p.headingDeg, p.pitchDeg, p.rollDeg);
    for (int c = 0; c < 3; ++c)
        expectNear(out[c], in[c], 1e-6, "vertical attitude round-trips");
}
