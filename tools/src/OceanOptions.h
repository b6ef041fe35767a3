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
    std::string quality = "high"; ///< low | medium | high | reference (ocean/Presets.h); other knobs override
    std::string model = "octaves"; ///< octaves | gerstner | fft
    int rings = 0;                 ///< 0 = the default radial grid
    int segments = 0;
    double steepness = -1.0;     ///< Gerstner steepness scale; < 0 = default
    std::string grid = "radial"; ///< radial | projected
    std::string vertexFilter =
        "bilinear";            ///< octaves: nearest | bilinear | hardware-bilinear | packed-4tap | trilinear
    bool combined = false;     ///< octaves: sum the displaced octaves in a compute pass first (§18.2.5)
    bool noCull = false;       ///< disable the per-vertex frustum test (§18.2.5)
    bool noViewSector = false; ///< tessellate the full circle instead of the view sector
    int fftSize = 0;           ///< 0 = default N
};

/// Adds --model, --grid, --grid-rings, --grid-segments, --vertex-filter, --combined, --no-cull,
/// --no-view-sector, --gerstner-steepness, --fft-size to a (sub)command.
void addOceanOptions(CLI::App& app, OceanOptions& options);

/// The OceanDesc the options describe. Throws UsageError (Replay.h) naming the option for bad values.
ocean::OceanDesc toOceanDesc(const OceanOptions& options);

} // namespace pacifica::tools
