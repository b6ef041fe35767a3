// ImageInputs: the images the tools read as ocean inputs, from any file OpenImageIO reads (PNG, EXR, ...):
// `pacifica replay --height-map FILE` (a painted octave height map into an ocean::OctaveImage, the tools'
// side of HeightOctavesDesc.images) and `--env FILE` (an HDR lat-long environment into an
// ocean::EnvironmentMap). The ocean library reads no files. Every error is an exception whose message starts
// with the file.
#pragma once

#include "ocean/HeightOctaves.h"
#include "ocean/Lighting.h"

#include <filesystem>
#include <memory>

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

/// --env: reads an HDR lat-long image and validates it into an EnvironmentMap (alpha dropped). Throws
/// std::runtime_error naming the file: "FILE: pixel (x,y) is NaN", "FILE: expected 3 (RGB) or 4 (RGBA)
/// channels, got 1" (capture::CaptureError "FILE: ..." when it cannot be read).
std::shared_ptr<const ocean::EnvironmentMap> loadEnvironment(const std::filesystem::path& file);

} // namespace pacifica::tools
