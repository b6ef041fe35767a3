// Png: 8- and 16-bit PNG files through libpng, written atomically (engine/AtomicFile.h). Its own target
// (pacifica_png), so a host that only takes screenshots -- the game -- links libpng, not OpenImageIO and the
// hundreds of libraries behind it; Capture.h (OpenImageIO: EXR, reading) includes it.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

namespace pacifica::capture {

/// An image could not be written or read. what() is "<path>: <what failed>[: <the library's reason>]".
class CaptureError : public std::runtime_error {
public:
    CaptureError(const std::filesystem::path& file, const std::string& message);

    /// The file the error is about (the final path for writes, not the temp file).
    const std::filesystem::path& file() const { return mFile; }

private:
    std::filesystem::path mFile;
};

/// How hard the lossless writers compress: zlib's default level 6 for PNG and OpenEXR's default level 4 for
/// EXR (Small), or level 1 (Fast: a 640x360 RGBA frame's EXR in 22 instead of 35 ms and 1.11x the bytes, its
/// PNG in 13 instead of 45 ms and 1.26x; docs/PERFORMANCE.md). Pixels are identical either way.
enum class Compression { Small, Fast };

/// Writes an 8-bit PNG from display-encoded (already sRGB) values with 1 to 4 interleaved channels, top row
/// first: each value is clamped to [0, 1] (NaN becomes 0) and quantised as round(v * 255); no transfer
/// function is applied here. The file is tagged sRGB. Atomic like writeExrHalf(); throws CaptureError.
void writePng8(const std::filesystem::path& path, int width, int height, int channels,
               const float* displayTopDown, Compression compression = Compression::Small);

/// Writes a 16-bit PNG of code values in [0, 1] (clamped, NaN -> 0, round(v * 65535)), 1 to 4 channels, top
/// row first, untagged (e.g. Rec.2100 PQ codes for an HDR display). Atomic like writeExrHalf(); throws
/// CaptureError.
void writePng16(const std::filesystem::path& path, int width, int height, int channels,
                const float* codeTopDown);

} // namespace pacifica::capture
