// Lighting: how the sea and the sky are lit and fogged (scene-linear HDR). The shading itself lives in
// ocean/shaders/ocean.frag and sky.glsl; ocean/src/gpu/LightingGpu.cpp sets these values as uniforms.
#pragma once

#include <glm/glm.hpp>

namespace pacifica::ocean {

struct LightingDesc {
    glm::dvec3 sunDirection{0.35, -0.55, 0.30}; ///< towards the sun, world ENU (normalised on use)
    float sunIntensity = 40.0f;         ///< scene-linear radiance scale of the sun's specular highlight
    float skyIntensity = 1.0f;          ///< scale of the procedural sky radiance
    float fogDensity = 1.0f / 60000.0f; ///< 1/m
    float normalTilt = 0.15f;           ///< §18.2.6: tilt of the lighting normal toward the viewer
};

} // namespace pacifica::ocean
