// OceanConstants: physical and shading constants shared by the CPU maths and the GLSL shaders.
// The shaders receive them as #defines generated from these values (OceanShaders.cpp), so there is
// exactly one source of truth.
#pragma once

#include <string>

namespace pacifica::ocean {

inline constexpr double GRAVITY = 9.81;  ///< m/s^2, deep-water dispersion w^2 = g k
inline constexpr double WATER_F0 = 0.02; ///< Schlick reflectance at normal incidence, n = 1.33
inline constexpr float DEEP_WATER_COLOR[3] = {0.0045f, 0.019f, 0.032f}; ///< scene-linear upwelling radiance
inline constexpr float FOG_DENSITY = 1.0f / 60000.0f; ///< 1/m, exponential distance fog (overridable)
inline constexpr int MAX_OCTAVES = 8;
inline constexpr double EARTH_RADIUS = 6371000.0; ///< m, mean radius (IUGG) for the curvature drop

/// How far the sea surface at horizontal distance d from the camera lies below the camera's tangent plane
/// on a spherical Earth: d^2 / (2 R) (the small-angle sagitta; error < 1e-4 relative up to 100 km). The
/// vertex shader applies the same drop, so from 15 km the horizon sits 3.9 degrees below eye level.
inline double curvatureDrop(double d) {
    return d * d / (2.0 * EARTH_RADIUS);
}

/// GLSL #define lines for the constants above (plus MAX_OCTAVES), prepended to every ocean shader.
std::string shaderConstantDefines();

} // namespace pacifica::ocean
