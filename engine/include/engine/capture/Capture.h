// Capture: writes rendered frames to disk — linear half-float OpenEXR for analysis and golden images, 8-bit
// sRGB PNG for people (engine/capture/Png.h, through libpng) — and reads images back for tests and tools. It
// is the only engine code that links OpenImageIO (which costs every linked process ~0.2 s at start-up), so
// this header exposes no OIIO types. Writes are atomic (temp file in the same directory, then rename), so a
// crash or a full disk never leaves a half-written frame under the final name, and every EXR write returns a
// hash of the exact half bits written, so determinism checks compare one number instead of two files.
//
// Usage:
//   1. Read back the frame (RGBA float, top row first) and fill a Metadata with what produced it:
//        pacifica::capture::Metadata meta;
//        meta.strings.push_back({"flight", "demo_flight.csv"});
//        meta.numbers.push_back({"time_s", 12.5});
//   2. uint64_t hash = pacifica::capture::writeExrHalf("out/frame_0001.exr", w, h, 4, pixels.data(), meta);
//      (header attributes appear as "pacifica:flight", "pacifica:time_s"; throws CaptureError on failure)
//   3. For a picture to look at, run the display transform first, then
//        pacifica::capture::writePng8("out/frame_0001.png", w, h, 4, displayPixels.data());
//   4. In tests: pacifica::capture::Image img = pacifica::capture::readImage("out/frame_0001.exr");
#pragma once

#include "engine/capture/Png.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pacifica::capture {

/// Extra header data for an EXR: each name is written as the attribute "pacifica:<name>".
struct Metadata {
    std::vector<std::pair<std::string, std::string>> strings; ///< written as string attributes
    std::vector<std::pair<std::string, double>> numbers;      ///< written as double attributes
};

/// XXH64 (seed 0) of the half values' raw bits, in memory order (little-endian on every supported host).
uint64_t hashHalfPixels(const uint16_t* halfBits, size_t count);

/// XXH64 (seed 0) of a file's bytes, read in blocks; std::nullopt when it cannot be opened or read.
std::optional<uint64_t> hashFileBytes(const std::filesystem::path& path);

/// Converts floats to IEEE 754 binary16 bits, rounding to nearest, ties to even; out-of-range values become
/// +-infinity, NaN stays NaN.
std::vector<uint16_t> toHalf(const float* data, size_t count);

/// Writes a half-float OpenEXR (ZIP compression) of width x height pixels with 3 (RGB) or 4 (RGBA)
/// interleaved channels, top row first. Metadata becomes header attributes named "pacifica:<name>".
/// Returns hashHalfPixels() of exactly the half data written. Atomic: the file appears complete under
/// `path` or not at all. Throws CaptureError (naming `path`) on bad arguments or any I/O failure.
uint64_t writeExrHalf(const std::filesystem::path& path, int width, int height, int channels,
                      const float* pixelsTopDown, const Metadata& metadata,
                      Compression compression = Compression::Small);

/// An image read back from disk.
struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels; ///< width * height * channels, interleaved, top row first
    /// Every header attribute as text (numbers in shortest round-trip form), e.g. "pacifica:time_s".
    std::map<std::string, std::string> attributes;
};

/// The most samples (pixels x channels) readImage() reads: a 16384 x 8192 RGBA lat-long environment (a 16k
/// HDR sky), 2 GiB of floats. A header declaring more (an EXR of 65535 x 65535) is refused before any pixel
/// memory is allocated.
inline constexpr int64_t MAX_READ_SAMPLES = int64_t(16384) * 8192 * 4;

/// Whether a header's width x height x channels is positive and at most MAX_READ_SAMPLES, checked factor by
/// factor so that no product overflows (a header may declare 2^31 x 2^31).
constexpr bool samplesWithinLimit(int64_t width, int64_t height, int64_t channels) {
    return width > 0 && height > 0 && channels > 0 && width <= MAX_READ_SAMPLES &&
           height <= MAX_READ_SAMPLES / width && channels <= MAX_READ_SAMPLES / (width * height);
}

/// Reads any image OpenImageIO understands (first subimage, all channels) as float; built with
/// PACIFICA_CAPTURE_OPENEXR, OpenEXR files only (engine/capture/OpenExr.h). 8-bit files read as value / 255.
/// Throws CaptureError naming the file (also for more than MAX_READ_SAMPLES samples).
Image readImage(const std::filesystem::path& path);

} // namespace pacifica::capture
