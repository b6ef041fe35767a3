// GerstnerGpu: binds the Gerstner-sum uniforms (ocean/shaders/gerstner.glsl). The per-wave constants are
// packed once; per bind only the phase offsets change, computed and wrapped in double by
// GerstnerWaves::phaseOffsets so the shader's float phases stay small.
#include <epoxy/gl.h>

#include "gpu/GerstnerGpu.h"

#include "ocean/OceanConstants.h"

#include <cmath>

#include <stdexcept>

namespace pacifica::ocean {

GerstnerGpu::GerstnerGpu(std::shared_ptr<const GerstnerWaves> waves) : mWaves(std::move(waves)) {
    if (!mWaves)
        throw std::invalid_argument("GerstnerGpu::GerstnerGpu(): waves is null");
    for (const GerstnerWave& w : mWaves->waves()) {
        const glm::dvec2 d = GerstnerWaves::direction(w);
        mWave.insert(mWave.end(),
                     {static_cast<float>(d.x), static_cast<float>(d.y),
                      static_cast<float>(GerstnerWaves::wavenumber(w)), static_cast<float>(w.amplitude)});
        // The living whitecaps step each wave's phase back by w_i FOAM_MEMORY_STEP per lattice time.
        const double stepAngle = std::sqrt(GRAVITY * GerstnerWaves::wavenumber(w)) * FOAM_MEMORY_STEP;
        mMemory.insert(mMemory.end(), {0.0f, static_cast<float>(std::cos(stepAngle)),
                                       static_cast<float>(std::sin(stepAngle)), 0.0f});
        mExtra.insert(mExtra.end(),
                      {static_cast<float>(w.steepness), 0.0f,
                       static_cast<float>(GerstnerWaves::DISPLACEMENT_FADE_WAVELENGTHS * w.wavelength),
                       static_cast<float>(GerstnerWaves::LIGHTING_FADE_WAVELENGTHS * w.wavelength)});
    }
}

void GerstnerGpu::bind(unsigned prog, int /*firstUnit*/, double time, const glm::dvec3& cameraWorld) {
    const std::vector<float> theta0 = mWaves->phaseOffsets(glm::dvec2(cameraWorld), time);
    for (size_t i = 0; i < theta0.size(); ++i)
        mExtra[i * 4 + 1] = theta0[i];
    const GLsizei n = static_cast<GLsizei>(theta0.size());
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uGerstnerCount"), n);
    if (n > 0) {
        glProgramUniform4fv(prog, glGetUniformLocation(prog, "uGerstnerWave"), n, mWave.data());
        glProgramUniform4fv(prog, glGetUniformLocation(prog, "uGerstnerExtra"), n, mExtra.data());
    }
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uGerstnerMinJacobian"),
                       static_cast<float>(GerstnerWaves::MIN_LIGHTING_JACOBIAN));
    // Living whitecaps: the phases at the last lattice time t_j <= t and the decay since, both in double.
    const bool memory = mWaves->foamMemory();
    glProgramUniform1i(prog, glGetUniformLocation(prog, "uGerstnerFoamMemory"), memory ? 1 : 0);
    if (memory && n > 0) {
        const int64_t j = foamStepIndex(time);
        const std::vector<float> thetaJ = mWaves->phaseOffsets(glm::dvec2(cameraWorld), foamStepTime(j));
        for (size_t i = 0; i < thetaJ.size(); ++i)
            mMemory[i * 4] = thetaJ[i];
        glProgramUniform4fv(prog, glGetUniformLocation(prog, "uGerstnerMemory"), n, mMemory.data());
        glProgramUniform1f(prog, glGetUniformLocation(prog, "uGerstnerFoamDecay"),
                           static_cast<float>(std::exp(-(time - foamStepTime(j)) / FOAM_DECAY_TIME)));
    }
}

} // namespace pacifica::ocean
