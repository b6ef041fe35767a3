// SurfaceProbe (internal, for tests and the accuracy benchmark): evaluates a surface model's GLSL
// modelDisplacement()/modelLighting() at arbitrary camera-relative points with transform feedback, so the
// GPU path can be compared with the model's double-precision CPU evaluation point by point.
#pragma once

#include "gpu/SurfaceGpu.h"

#include <glm/glm.hpp>

#include <vector>

namespace pacifica::ocean {

struct ProbeResult {
    std::vector<glm::vec3> displacement; ///< modelDisplacement(rel) per point
    std::vector<glm::vec3> lighting;     ///< modelLighting(rel) per point
    std::vector<glm::vec2> foam; ///< modelFoamInputs(rel) (H, J); (displacement z, 1) for a model without
};

/// Needs a current GL 4.5 context. Calls gpu.update(time, camera) first (FFT models compute their maps).
ProbeResult probeSurface(SurfaceGpu& gpu, const std::vector<glm::vec2>& rel, const glm::dvec3& cameraWorld,
                         double time);

} // namespace pacifica::ocean
