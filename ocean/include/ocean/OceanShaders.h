// OceanShaders: the ocean's GLSL sources, embedded into the library at build time (ocean/shaders/*).
#pragma once

#include <string_view>

namespace pacifica::ocean {

/// Text of an embedded shader file by name (e.g. "ocean.vert"); throws std::out_of_range if unknown.
std::string_view shaderText(std::string_view name);

} // namespace pacifica::ocean
