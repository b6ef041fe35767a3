// ImageInputs: reads and checks height maps and environment maps (ImageInputs.h has the file schemes).
#include "ImageInputs.h"

#include "engine/capture/Capture.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pacifica::tools {

ocean::OctaveImage loadHeightMap(const std::filesystem::path& file) {
    const capture::Image image = capture::readImage(file); // CaptureError "FILE: ..." if missing/garbled
    const std::string name = file.string();
    const int w = image.width;
    auto fail = [&](const std::string& what) { return std::runtime_error(name + ": " + what); };
    if (w < 16 || w > 1024 || (w & (w - 1)) != 0)
        throw fail("height map width must be a power of two in [16, 1024], got " + std::to_string(w) + "x" +
                   std::to_string(image.height));
    if (image.height < w || image.height % w != 0)
        throw fail("height map must be W x (W * frames) (square frames stacked top to bottom), got " +
                   std::to_string(w) + "x" + std::to_string(image.height));
    ocean::OctaveImage out;
    out.size = w;
    out.frames = image.height / w;
    if (out.frames > 256)
        throw fail("height map holds " + std::to_string(out.frames) + " frames; at most 256");
    const size_t texels = static_cast<size_t>(w) * static_cast<size_t>(w);
    out.heights.resize(texels * static_cast<size_t>(out.frames));
    double sum = 0.0;
    for (int f = 0; f < out.frames; ++f)
        for (int row = 0; row < w; ++row)
            for (int x = 0; x < w; ++x) {
                const size_t src = (static_cast<size_t>(f) * w + row) * w + x;
                const float v = image.pixels[src * static_cast<size_t>(image.channels)];
                if (!std::isfinite(v))
                    throw fail("pixel (" + std::to_string(x) + "," + std::to_string(f * w + row) + ") is " +
                               (std::isnan(v) ? "NaN" : "infinite"));
                // Top row = north edge: map row y (northward) = W - 1 - row.
                out.heights[static_cast<size_t>(f) * texels + static_cast<size_t>(w - 1 - row) * w + x] = v;
                sum += v;
            }
    const double n = static_cast<double>(out.heights.size());
    const double mean = sum / n;
    double sumSq = 0.0;
    for (float v : out.heights)
        sumSq += (v - mean) * (v - mean);
    const double rms = std::sqrt(sumSq / n);
    if (!(rms > 0.0))
        throw fail("height map is flat (every pixel is " + std::to_string(mean) + "): nothing to displace");
    for (float& v : out.heights)
        v = static_cast<float>((v - mean) / rms);
    try {
        (void)ocean::makeOctaveMap(out, out.frames, name); // half-float range of the derived slopes
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(e.what());
    }
    return out;
}

std::shared_ptr<const ocean::EnvironmentMap> loadEnvironment(const std::filesystem::path& file) {
    const capture::Image image = capture::readImage(file); // CaptureError "FILE: ..." if missing/garbled
    if (image.channels != 3 && image.channels != 4)
        throw std::runtime_error(file.string() + ": expected 3 (RGB) or 4 (RGBA) channels, got " +
                                 std::to_string(image.channels));
    const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
    std::vector<float> rgb(pixels * 3);
    for (size_t p = 0; p < pixels; ++p)
        for (size_t c = 0; c < 3; ++c)
            rgb[p * 3 + c] = image.pixels[p * static_cast<size_t>(image.channels) + c];
    try {
        return std::make_shared<const ocean::EnvironmentMap>(
            ocean::makeEnvironmentMap(image.width, image.height, std::move(rgb)));
    } catch (const ocean::EnvironmentMapError& e) {
        throw std::runtime_error(file.string() + ": " + e.problem());
    }
}

} // namespace pacifica::tools
