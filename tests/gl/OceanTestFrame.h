// OceanTestFrame.h: the OceanFrame several GL tests render (test_effects_gl, test_compute_shading_gl): a
// camera at `camera` (world ENU metres) looking along heading / pitch (degrees) with a 60 degree vertical
// field of view and a 5 cm near plane, at time t, into `framebuffer` of width x height pixels.
#pragma once

#include "engine/Pose.h"
#include "engine/Space.h"
#include "ocean/Ocean.h"

#include <numbers>

namespace pacifica::gltest {

inline ocean::OceanFrame oceanFrameAt(const glm::dvec3& camera, double headingDeg, double pitchDeg, double t,
                                      unsigned framebuffer, int width, int height) {
    Pose pose;
    pose.position = camera;
    pose.headingDeg = headingDeg;
    pose.pitchDeg = pitchDeg;
    return ocean::makeOceanFrame(pose, static_cast<float>(60.0 * std::numbers::pi / 180.0), width, height, t,
                                 framebuffer);
}

} // namespace pacifica::gltest
