// GerstnerGpu (internal): the GPU side of GerstnerWaves — no textures and no per-frame GPU work, only
// uniforms: each wave's direction, wavenumber, amplitude, applied steepness and fade distances, and its
// phase offset theta0_i wrapped in double for the current camera and time (ocean/shaders/gerstner.glsl).
#pragma once

#include "gpu/SurfaceGpu.h"
#include "ocean/GerstnerWaves.h"

#include <memory>

namespace pacifica::ocean {

class GerstnerGpu final : public SurfaceGpu {
public:
    /// Throws std::invalid_argument if waves is null.
    explicit GerstnerGpu(std::shared_ptr<const GerstnerWaves> waves);
    std::vector<std::string> glslFiles() const override { return {"gerstner.glsl"}; }
    /// Nothing to do: the sum is evaluated in the shaders.
    SurfaceGpuStats update(double, const glm::dvec3&) override { return {}; }
    /// Sets uGerstnerCount, uGerstnerWave[], uGerstnerExtra[] (with this frame's phase offsets) and
    /// uGerstnerMinJacobian with glProgramUniform*; binds no texture units.
    void bind(unsigned program, int firstUnit, double time, const glm::dvec3& cameraWorld) override;
    int unitsUsed() const override { return 0; }

private:
    std::shared_ptr<const GerstnerWaves> mWaves;
    std::vector<float> mWave;  ///< 4 floats per wave: D.x, D.y, k, A (constant)
    std::vector<float> mExtra; ///< 4 floats per wave: Q, theta0 (set per bind), fade ends
    std::vector<float>
        mMemory; ///< 4 floats per wave: theta0 at the foam lattice time (per bind), cos, sin of w s
};

} // namespace pacifica::ocean
