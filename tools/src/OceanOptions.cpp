// OceanOptions: command-line ocean knobs -> OceanDesc.
#include "OceanOptions.h"

#include "Replay.h"

#include <CLI/CLI.hpp>

namespace pacifica::tools {

void addOceanOptions(CLI::App& app, OceanOptions& o) {
    app.add_option("--model", o.model, "surface model: octaves (GPU Gems 2 height maps), gerstner, fft")
        ->default_val("octaves");
    app.add_option("--grid-rings", o.rings, "radial grid rings N (default 256)");
    app.add_option("--grid-segments", o.segments, "radial grid segments M (default 512)");
    app.add_option("--gerstner-steepness", o.steepness,
                   "Gerstner steepness scale (clamped to the fold limit)");
}

ocean::OceanDesc toOceanDesc(const OceanOptions& o) {
    ocean::OceanDesc d;
    if (o.model == "octaves")
        d.model = ocean::SurfaceKind::Octaves;
    else if (o.model == "gerstner")
        d.model = ocean::SurfaceKind::Gerstner;
    else if (o.model == "fft")
        d.model = ocean::SurfaceKind::Fft;
    else
        throw UsageError("--model must be one of octaves, gerstner, fft; got '" + o.model + "'");
    if (o.rings != 0)
        d.grid.rings = o.rings;
    if (o.segments != 0)
        d.grid.segments = o.segments;
    if (o.steepness >= 0.0)
        d.gerstner.steepnessScale = o.steepness;
    try {
        (void)ocean::RadialGrid(d.grid); // validate here so the message names the option
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--grid-rings/--grid-segments: ") + e.what());
    }
    return d;
}

} // namespace pacifica::tools
