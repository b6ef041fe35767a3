// OceanOptions: command-line ocean knobs -> OceanDesc.
#include "OceanOptions.h"

#include "Replay.h"
#include "ocean/Presets.h"

#include <CLI/CLI.hpp>

namespace pacifica::tools {

void addOceanOptions(CLI::App& app, OceanOptions& o) {
    app.add_option("--quality", o.quality, "quality preset: low, medium, high, reference (docs/ACCURACY.md)")
        ->default_val("high");
    app.add_option("--model", o.model, "surface model: octaves (GPU Gems 2 height maps), gerstner, fft")
        ->default_val("octaves");
    app.add_option("--grid-rings", o.rings, "radial grid rings N (default 256)");
    app.add_option("--grid-segments", o.segments, "radial grid segments M (default 512)");
    app.add_option("--gerstner-steepness", o.steepness,
                   "Gerstner steepness scale (clamped to the fold limit)");
    app.add_option("--grid", o.grid, "grid: radial (GPU Gems 2 §18.2.3) or projected (Johanson 2004)")
        ->default_val("radial");
    app.add_option("--vertex-filter", o.vertexFilter,
                   "octave vertex filter: nearest, bilinear, hardware-bilinear, packed-4tap, trilinear")
        ->default_val("bilinear");
    app.add_flag("--combined", o.combined, "octaves: combine displaced octaves in a compute pass first");
    app.add_flag("--no-cull", o.noCull, "displace every vertex (no per-vertex frustum test)");
    app.add_flag("--no-view-sector", o.noViewSector, "tessellate the full circle, not just the view sector");
    app.add_option("--fft-size", o.fftSize, "FFT grid N (power of two, 16..1024)");
}

ocean::OceanDesc toOceanDesc(const OceanOptions& o) {
    ocean::OceanDesc d;
    try {
        d = ocean::oceanPreset(ocean::parseQuality(o.quality));
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--quality: ") + e.what());
    }
    if (o.model == "octaves")
        d.model = ocean::SurfaceKind::Octaves;
    else if (o.model == "gerstner")
        d.model = ocean::SurfaceKind::Gerstner;
    else if (o.model == "fft")
        d.model = ocean::SurfaceKind::Fft;
    else
        throw UsageError("--model must be one of octaves, gerstner, fft; got '" + o.model + "'");
    if (o.grid == "radial")
        d.gridKind = ocean::GridKind::Radial;
    else if (o.grid == "projected")
        d.gridKind = ocean::GridKind::Projected;
    else
        throw UsageError("--grid must be radial or projected; got '" + o.grid + "'");
    bool filterFound = false;
    for (ocean::VertexFilter f :
         {ocean::VertexFilter::Nearest, ocean::VertexFilter::Bilinear, ocean::VertexFilter::HardwareBilinear,
          ocean::VertexFilter::Packed4Tap, ocean::VertexFilter::Trilinear}) {
        if (o.vertexFilter == ocean::toString(f)) {
            d.octaves.vertexFilter = f;
            filterFound = true;
        }
    }
    if (!filterFound)
        throw UsageError("--vertex-filter must be one of nearest, bilinear, hardware-bilinear, packed-4tap, "
                         "trilinear; got '" +
                         o.vertexFilter + "'");
    d.octaves.combinedDisplacement = o.combined;
    d.cullVertices = !o.noCull;
    d.viewSector = !o.noViewSector;
    if (o.fftSize != 0)
        d.fft.size = o.fftSize;
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
