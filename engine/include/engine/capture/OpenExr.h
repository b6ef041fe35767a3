// OpenExr: half-float OpenEXR files through the OpenEXR library itself, without OpenImageIO. Capture.h's
// writeExrHalf()/readImage() use it when the project is configured with PACIFICA_CAPTURE_OPENEXR=ON (a
// render-farm build whose shared-library closure is ~1/5 of OpenImageIO's, docs/SCALE.md); the default
// build writes through OpenImageIO and the tests check that each reads what the other wrote.
//
// The files are the same as OpenImageIO's in everything a reader sees: channels R,G,B(,A) as HALF, ZIP
// compression at the given zlib level, increasing-y line order, a data window of (0,0)-(w-1,h-1), and the
// metadata as "pacifica:<name>" string and double attributes. Their bytes differ (OpenImageIO adds its own
// attributes), so frame hashes are of the half pixels, never of the file.
#pragma once

#include "engine/capture/Capture.h"

#include <cstdint>
#include <filesystem>

namespace pacifica::capture::openexr {

/// Writes width x height pixels of 3 (RGB) or 4 (RGBA) interleaved half channels, top row first, to `file`
/// directly (not atomic: writeExrHalf() writes a temp file and renames it). Errors throw CaptureError naming
/// `reportAs` (the final path) with the library's reason.
void writeHalf(const std::filesystem::path& file, const std::filesystem::path& reportAs, int width,
               int height, int channels, const uint16_t* halfBitsTopDown, const Metadata& metadata,
               Compression compression);

/// True when the file starts with OpenEXR's magic number (76 2f 31 01); false when it does not or cannot be
/// read.
bool isOpenExr(const std::filesystem::path& file);

/// Reads an OpenEXR file (scanline or tiled, its first part) as float, top row first. Channels come in the
/// order R, G, B, A when the file has R, G and B, otherwise in the file's (alphabetical) order. Attributes:
/// string, double, float and int ones as text, and "compression" as OpenImageIO names it ("zip", "piz", ...).
/// Refuses more than MAX_READ_SAMPLES samples before allocating pixel memory (OpenEXR has read the header and
/// its line-offset table by then); throws CaptureError naming `file`.
Image read(const std::filesystem::path& file);

} // namespace pacifica::capture::openexr
