// HeightMapFile: `pacifica replay --height-map FILE`: reads a painted octave height map from an image file
// (PNG, EXR, anything OpenImageIO reads) into an ocean::OctaveImage. The ocean library reads no files; this
// is the tools' side of HeightOctavesDesc.images.
#pragma once

#include "ocean/HeightOctaves.h"

#include <filesystem>

namespace pacifica::tools {

/// Reads FILE as a height map (channel 0, i.e. red or grey; other channels are ignored):
///   - the image is seen from above with north up: columns run east, the top row is the tile's north edge;
///   - width W is a power of two in [16, 1024] and the height is W * F: F >= 1 square frames stacked top to
///     bottom (frame 0 topmost) that span the octave's loop period; F = 1 is a still map;
///   - the values are normalised to zero mean and unit RMS over all frames, so the octave's amplitude is
///     its RMS height in metres as for a generated map (image value ranges are arbitrary: 8-bit PNGs read
///     as 0..1, EXRs hold anything);
///   - it must tile: the right column continues into the left one and the bottom row of a frame into its
///     top row (the loader cannot check how seamless a painting is; a seam shows as a crease).
/// Throws std::runtime_error "FILE: <what is wrong>" for a file that is missing or unreadable (from
/// capture::readImage), the wrong shape, a non-finite value, a flat map, or slopes beyond the GPU maps'
/// half-float range (ocean::makeOctaveMap()).
ocean::OctaveImage loadHeightMap(const std::filesystem::path& file);

} // namespace pacifica::tools
