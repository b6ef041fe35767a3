// Image pieces of the comparison's diagnostic sheets, on interleaved float RGB (code values unless noted):
// a canvas to compose on, box downscaling, false colour of scene-linear luminance in stops, per-channel
// histograms and their plot, a wipe and a difference image between two transforms.
//
// STEP BY STEP
//   1. Canvas c(w, h, 0.12f); c.blit(tile, tw, th, x, y);
//   2. falseColourStops(sceneLinear, n) -> code values; FALSE_COLOUR_BANDS for its legend
//   3. Histogram hst = histogram(code, n, 64); plotHistogram(c, x, y, w, h, hst);
//   4. wipe(a, b, w, h) / difference(a, b, n, gain, maxDiff)
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace pacifica::tonemap {

struct Canvas {
    int width = 0, height = 0;
    std::vector<float> rgb;
    Canvas(int w, int h, float background);
    /// Copies a w x h RGB image with its top-left at (x, y), clipped to the canvas.
    void blit(const float* src, int w, int h, int x, int y);
    void fillRect(int x, int y, int w, int h, const std::array<float, 3>& c);
};

/// Box-filtered downscale of an interleaved RGB image to `outWidth` (aspect kept; height returned).
std::vector<float> downscaleBox(const std::vector<float>& rgb, int w, int h, int outWidth, int& outHeight);

/// One band of the false-colour scale: luminance in [lo, hi) stops relative to 0.18 gets `colour`.
struct StopBand {
    float lo, hi;
    std::array<float, 3> colour; ///< sRGB code values
    const char* label;
};
/// 12 bands from below -8 to above +8 stops around mid grey (0 = 0.18; the band [-0.5, 0.5) is grey).
extern const std::vector<StopBand> FALSE_COLOUR_BANDS;
/// Rec.709 luminance of each scene-linear pixel, in stops over 0.18, as the band colours (zero/NaN: lowest).
std::vector<float> falseColourStops(const float* sceneLinear, size_t pixels);

struct Histogram {
    int bins = 0;
    std::array<std::vector<size_t>, 3> counts; ///< per channel, code values [0, 1] in `bins` bins (clamped)
    size_t pixels = 0;
};
Histogram histogram(const float* code, size_t pixels, int bins);
/// Plots the three channels as overlaid translucent bars (log count scale) into the box (x, y, w, h).
void plotHistogram(Canvas& canvas, int x, int y, int w, int h, const Histogram& h0);

/// Left half from a, right half from b, a 2-pixel white divider at the middle.
std::vector<float> wipe(const float* a, const float* b, int w, int h);
/// |a - b| * gain per channel (clamped to 1); maxDiff receives the largest |a - b|.
std::vector<float> difference(const float* a, const float* b, size_t pixels, float gain, float& maxDiff);

} // namespace pacifica::tonemap
