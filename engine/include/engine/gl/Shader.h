// Shader: compiles and links GLSL programs from named sources, so compile and link errors name the
// shader file and line ("ocean.vert:42: error: ..."), not a source-string index.
//
// Each stage is a list of sources concatenated in order after a `#version 450 core` line; source N starts
// at line N * 100000 + 1 (`#line`), and the driver's "N:LINE" / "N(LINE)" locations in the info log are
// rewritten to "name:LINE" — the line alone tells the source, since Mesa reports source 0 for semantic
// errors.
#pragma once

#include "engine/gl/GlObjects.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace pacifica::gl {

class ShaderError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct ShaderSource {
    std::string name; ///< shown in error messages: a file name, or e.g. "<defines>"
    std::string text;
};

enum class ShaderStage { Vertex, Fragment, Compute };

struct StageSources {
    ShaderStage stage;
    std::vector<ShaderSource> sources;
};

/// Compiles every stage and links them. Throws ShaderError with the driver log mapped to source names.
/// feedbackVaryings: outputs captured by transform feedback (interleaved), e.g. for GPU-vs-CPU readbacks.
Program buildProgram(const std::vector<StageSources>& stages, const std::string& programName,
                     const std::vector<std::string>& feedbackVaryings = {});

/// Rewrites driver log locations "N:L(" (Mesa) and "N(L)" (NVIDIA) into "name:L". Exposed for tests.
std::string mapShaderLog(const std::string& log, const std::vector<ShaderSource>& sources);

} // namespace pacifica::gl
