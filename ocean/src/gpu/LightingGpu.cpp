// LightingGpu: lighting uniforms for the sky and sea programs.
#include "gpu/LightingGpu.h"

#include <epoxy/gl.h>

namespace pacifica::ocean {

LightingGpu::LightingGpu() = default;
LightingGpu::~LightingGpu() = default;

void LightingGpu::bind(unsigned prog, int /*firstUnit*/, const LightingDesc& l) {
    const glm::vec3 sun = glm::vec3(glm::normalize(l.sunDirection));
    glProgramUniform3f(prog, glGetUniformLocation(prog, "uSunDir"), sun.x, sun.y, sun.z);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uSkyIntensity"), l.skyIntensity);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uSunIntensity"), l.sunIntensity);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uFogDensity"), l.fogDensity);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "uNormalTilt"), l.normalTilt);
}

} // namespace pacifica::ocean
