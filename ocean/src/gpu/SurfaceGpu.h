// SurfaceGpu (internal): the GPU side of a surface model, used by the ocean render system. Each model's
// GLSL file defines, for a camera-relative undisplaced grid point `rel` (metres):
//     vec3 modelDisplacement(vec2 rel);   // (dx, dy, dz) — the exact path the vertex shader uses
//     vec3 modelLighting(vec2 rel);       // (dH/dx, dH/dy, unresolved slope variance) for the fragment
//     shader
// and declares its own uniforms/samplers. bind() sets them for one program; update() does per-frame GPU work
// (FFT compute passes) and reports it, so absent work is provably absent.
#pragma once

#include "engine/gl/GlObjects.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace pacifica::ocean {

struct SurfaceGpuStats {
    int computePasses = 0;
    int uploads = 0;
};

class SurfaceGpu {
public:
    virtual ~SurfaceGpu() = default;
    /// Embedded GLSL file names (in include order) providing modelDisplacement() and modelLighting().
    virtual std::vector<std::string> glslFiles() const = 0;
    /// Per-frame GPU work that does not depend on the program (e.g. FFT of the spectrum at time t).
    virtual SurfaceGpuStats update(double time, const glm::dvec3& cameraWorld) = 0;
    /// Sets the model's uniforms and binds its textures to units [firstUnit, firstUnit + unitsUsed()).
    virtual void bind(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld) = 0;
    virtual int unitsUsed() const = 0;
};

} // namespace pacifica::ocean
