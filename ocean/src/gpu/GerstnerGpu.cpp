// GerstnerGpu: binds the Gerstner-sum uniforms (ocean/shaders/gerstner.glsl). The per-wave constants are
// packed once; per bind only the phase offsets change, computed and wrapped in double by
// GerstnerWaves::phaseOffsets so the shader's float phases stay small.
#include <epoxy/gl.h>

#include "gpu/GerstnerGpu.h"

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
}

} // namespace pacifica::ocean
