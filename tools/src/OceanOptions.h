// OceanOptions: the command-line knobs that select and tune the ocean (surface model, grid, quality), shared
// by `pacifica replay` and the benchmarks, mapped onto ocean::OceanDesc.
#pragma once

#include "ocean/Ocean.h"

#include <string>

namespace CLI {
class App;
}

namespace pacifica::tools {

struct OceanOptions {
    std::string model = "octaves"; ///< octaves | gerstner | fft
    int rings = 0;                 ///< 0 = the default radial grid
    int segments = 0;
    double steepness = -1.0; ///< Gerstner steepness scale; < 0 = default
};

/// Adds --model, --grid-rings, --grid-segments, --gerstner-steepness to a (sub)command.
void addOceanOptions(CLI::App& app, OceanOptions& options);

/// The OceanDesc the options describe. Throws UsageError (Replay.h) naming the option for bad values.
ocean::OceanDesc toOceanDesc(const OceanOptions& options);

} // namespace pacifica::tools
