// Space: camera-relative rendering. The world lives in double-precision ENU metres (engine/Pose.h), far
// beyond what a float can hold to the centimetre (float spacing is 1 m at 1e7 m). So positions are made
// relative to the camera in double and only the small differences become floats; the view matrix is a pure
// rotation and the GPU never sees an absolute position. The projection is reverse-Z with an infinite far
// plane, which keeps depth precision nearly uniform from a metre to the horizon.
//
// STEP BY STEP
// 1. Once per frame: CameraFrame cam = makeCameraFrame(cameraPose, fovY, aspect, 0.1f);
// 2. For every object or tile: glm::vec3 rel = toCameraRelative(objectWorld, cam.origin); upload rel (or a
//    model matrix with translation rel) and cam.viewProj.
// 3. GL state for the projection: glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); glClearDepth(0.0);
//    glDepthFunc(GL_GREATER) (or GL_GEQUAL). A depth texture of GL_DEPTH_COMPONENT32F keeps all the gain.
#pragma once

#include "engine/Pose.h"

#include <glm/glm.hpp>

namespace pacifica {

/// Mean Earth radius (IUGG), metres: the one the ocean drops the sea with for the horizon
/// (ocean::EARTH_RADIUS) and the cameras aim with (lookAtPose, engine/CameraPoses.h).
inline constexpr double EARTH_RADIUS = 6371000.0;

/// Where a world point is drawn, seen from `camera`: its z lowered by the Earth's curvature over the
/// horizontal distance d, d^2 / (2 R) (the ocean's curvature drop, OceanConstants.h curvatureDrop).
double drawnZ(const glm::dvec3& world, const glm::dvec3& camera, double earthRadius = EARTH_RADIUS);

/// world - cameraWorld, subtracted in double and only then rounded to float, so nearby points keep
/// sub-millimetre precision however far the camera is from the origin.
glm::vec3 toCameraRelative(const glm::dvec3& world, const glm::dvec3& cameraWorld);

/// World-to-eye rotation of a pose, with zero translation (apply it to camera-relative positions).
/// OpenGL eye convention: the camera looks along -Z_eye, +Y_eye is the body's up, +X_eye the body's right.
glm::mat4 viewRotation(const Pose& pose);

/// Reverse-Z perspective projection with an infinite far plane, for glClipControl(GL_LOWER_LEFT,
/// GL_ZERO_TO_ONE): window depth = zNear / distance along the view axis, i.e. 1 at zNear, falling to 0 at
/// infinity. Clear depth to 0 and test with GL_GREATER. Float depth is densest near 0, which reverse-Z puts
/// at the far distances, cancelling the 1/z crowding (N. Reed, "Depth Precision Visualized", NVIDIA
/// GameWorks blog, 2015; E. Persson, "Creating vast game worlds", SIGGRAPH 2012; infinite far plane:
/// Upchurch & Desbrun, "Tightening the Precision of Perspective Rendering", JGT 16(1), 2012).
/// Throws std::invalid_argument unless 0 < fovYRadians < pi, aspect > 0 and zNear > 0 (all finite).
glm::mat4 perspectiveReverseZInfinite(float fovYRadians, float aspect, float zNear);

/// Everything the renderer needs about the camera for one frame.
struct CameraFrame {
    glm::dvec3 origin{0.0};   ///< camera position in world metres; subtract it with toCameraRelative()
    glm::mat4 view{1.0f};     ///< viewRotation(pose): rotation only
    glm::mat4 proj{1.0f};     ///< perspectiveReverseZInfinite(fovY, aspect, zNear)
    glm::mat4 viewProj{1.0f}; ///< proj * view, for camera-relative positions
    float fovY = 1.0f;        ///< vertical field of view, radians
    float aspect = 1.0f;      ///< width / height
    float zNear = 0.1f;       ///< near plane distance, metres
};

/// Builds the frame's camera from a pose and projection parameters (validated as in
/// perspectiveReverseZInfinite()).
CameraFrame makeCameraFrame(const Pose& pose, float fovYRadians, float aspect, float zNear);

} // namespace pacifica
