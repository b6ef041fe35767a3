// Space implementation: camera-relative positions, the rotation-only view matrix and the reverse-Z
// infinite projection (derivations next to each function).
#include "engine/Space.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace pacifica {

double drawnZ(const glm::dvec3& world, const glm::dvec3& camera, double earthRadius) {
    const double d = std::hypot(world.x - camera.x, world.y - camera.y);
    return world.z - d * d / (2.0 * earthRadius);
}

glm::vec3 toCameraRelative(const glm::dvec3& world, const glm::dvec3& cameraWorld) {
    return glm::vec3(world - cameraWorld);
}

glm::mat4 viewRotation(const Pose& pose) {
    const glm::dmat3 body = attitudeMatrix(pose.headingDeg, pose.pitchDeg, pose.rollDeg);
    const glm::dvec3 forward = body[0], right = body[1], up = body[2];
    // The eye axes expressed in world are (right, up, -forward); the world-to-eye rotation is the transpose
    // of the matrix with those columns, i.e. they become its rows.
    const glm::dmat3 eyeToWorld(right, up, -forward);
    return glm::mat4(glm::mat3(glm::transpose(eyeToWorld))); // 4th column (translation) stays (0,0,0,1)
}

glm::mat4 perspectiveReverseZInfinite(float fovYRadians, float aspect, float zNear) {
    if (!(std::isfinite(fovYRadians) && fovYRadians > 0.0f && fovYRadians < 3.14159265f))
        throw std::invalid_argument("perspectiveReverseZInfinite(): fovY must be in (0, pi) radians, got " +
                                    std::to_string(fovYRadians));
    if (!(std::isfinite(aspect) && aspect > 0.0f))
        throw std::invalid_argument("perspectiveReverseZInfinite(): aspect must be > 0, got " +
                                    std::to_string(aspect));
    if (!(std::isfinite(zNear) && zNear > 0.0f))
        throw std::invalid_argument("perspectiveReverseZInfinite(): zNear must be > 0, got " +
                                    std::to_string(zNear));
    // Reed 2015: a [0,1]-depth projection mapping near -> 1 and far -> 0 has z_clip = A z_eye + B with
    // A = n / (far - n), B = far n / (far - n), and w_clip = -z_eye. As far -> infinity, A -> 0 and B -> n,
    // so depth = z_clip / w_clip = n / -z_eye: exactly 1 at z_eye = -n, -> 0 as z_eye -> -infinity.
    const float f = 1.0f / std::tan(0.5f * fovYRadians);
    glm::mat4 p(0.0f); // glm is column-major: p[column][row]
    p[0][0] = f / aspect;
    p[1][1] = f;
    p[2][3] = -1.0f; // w_clip = -z_eye
    p[3][2] = zNear; // z_clip = zNear
    return p;
}

CameraFrame makeCameraFrame(const Pose& pose, float fovYRadians, float aspect, float zNear) {
    CameraFrame frame;
    frame.origin = pose.position;
    frame.view = viewRotation(pose);
    frame.proj = perspectiveReverseZInfinite(fovYRadians, aspect, zNear);
    frame.viewProj = frame.proj * frame.view;
    frame.fovY = fovYRadians;
    frame.aspect = aspect;
    frame.zNear = zNear;
    return frame;
}

} // namespace pacifica
