// What a display transform did to an image, in numbers: clipping, crushing, hue shift and chroma kept in
// Oklab, contrast kept, and the generated test chart with its exposure sweep (monotonicity). Sources are
// scene-linear Rec.709 RGB; outputs are sRGB display code values (decoded with the sRGB EOTF before they
// are compared). Oklab: B. Ottosson 2020, "A perceptual color space for image processing" (its hue is
// exposure-invariant, since Oklab takes cube roots of LMS, so source hue is comparable at any exposure).
//
// STEP BY STEP
//   1. SourceCensus c = census(rgb, n);                  // NaN / Inf / negative counts
//   2. TransformMetrics m = measure(rgb, code, n);       // after applying a transform to rgb -> code
//   3. Chart chart = testChart(); ... sweepMetrics(chart, codeOfChart)
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace pacifica::tonemap {

/// Linear Rec.709 / sRGB primaries (D65) -> Oklab {L, a, b} (Ottosson 2020, M1 and M2).
std::array<float, 3> linearToOklab(float r, float g, float b);

struct SourceCensus {
    size_t pixels = 0;
    size_t nan = 0;      ///< pixels with a NaN channel
    size_t inf = 0;      ///< pixels with an infinite channel (and no NaN)
    size_t negative = 0; ///< finite pixels with a channel below 0
    float maxValue = 0;  ///< largest finite channel value
};
SourceCensus census(const float* rgb, size_t pixels);

/// Thresholds used by measure(), stated in reports.
constexpr float CLIP_CODE = 254.5f / 255.0f; ///< a channel at the 8-bit display maximum
constexpr float CRUSH_CODE = 0.5f / 255.0f;  ///< every channel rounds to 8-bit 0 ...
constexpr float CRUSH_SOURCE_Y = 1e-4f;      ///< ... while the source luminance is above this
constexpr float CHROMATIC_SOURCE = 0.05f;    ///< source Oklab C / L above this: a chromatic pixel
constexpr float CHROMATIC_OUTPUT = 0.01f;    ///< output C / L above this: its hue is defined

struct TransformMetrics {
    size_t pixels = 0;          ///< finite source pixels measured
    double clipped = 0;         ///< fraction with any output channel >= CLIP_CODE
    double crushed = 0;         ///< fraction with every channel < CRUSH_CODE where the source was lit
    size_t chromatic = 0;       ///< chromatic source pixels whose output is chromatic too
    double desaturated = 0;     ///< fraction of chromatic source pixels whose output became neutral
    double hueShiftMean = 0;    ///< degrees, |hue_out - hue_src| over `chromatic`
    double hueShiftP95 = 0;     ///< degrees
    double chromaRatio = 0;     ///< mean (C/L)_out / (C/L)_src over `chromatic`
    double contrastKept = 0;    ///< std of log2 Y_out / std of log2 Y_src over lit pixels (1 = all kept)
    double neutralDrift = 0;    ///< mean output C / L over neutral source pixels (0 = greys stay grey)
    size_t nonFiniteOutput = 0; ///< output pixels with NaN/Inf (must be 0)
};

/// src: scene-linear RGB, code: sRGB code values of the same pixels, both interleaved RGB.
/// Non-finite source pixels are skipped (census() counts them).
TransformMetrics measure(const float* src, const float* code, size_t pixels);
/// The same for any display: code = its code values (clipping, crushing), linear = the same pixels decoded to
/// display-linear Rec.709 RGB (relative or absolute: colour metrics are scale-free), e.g. from
/// ColorPipeline::decodeDisplayCpu() and xyzToLinearRec709().
TransformMetrics measure(const float* src, const float* code, const float* linear, size_t pixels);
/// CIE XYZ (D65) -> linear Rec.709, in place on interleaved RGB (IEC 61966-2-1 matrix, inverted).
void xyzToLinearRec709(float* rgb, size_t pixels);

/// The generated test chart (scene-linear Rec.709): rows of saturated hues swept over exposure, a grey ramp,
/// and sky and skin patches. Built in code, licence-clean.
struct Chart {
    int width = 0, height = 0;
    std::vector<float> rgb;        ///< width * height * 3, top row first
    std::vector<float> evs;        ///< the sweep's exposures, EV relative to 0.18 mid grey, left to right
    std::vector<std::string> hues; ///< one per sweep row, top to bottom
    int cell = 0;                  ///< square cell size in pixels of the sweep
    /// Sample position (centre) of sweep row `h`, exposure `e`.
    size_t sweepPixel(size_t h, size_t e) const;
};
Chart testChart(int cell = 16);

/// Over the chart's exposure sweep after a transform: luminance reversals (output Y drops by more than
/// 1e-4 from one exposure step to the next brighter one) and hue flips (output hue jumps by more than 30
/// degrees between neighbouring steps while both are chromatic).
struct SweepMetrics {
    int luminanceReversals = 0;
    int hueFlips = 0;
    float whereMidGreyLands = 0; ///< code value of 0.18 grey on the ramp
};
SweepMetrics sweepMetrics(const Chart& chart, const float* code);
/// With the chart's output decoded to display-linear Rec.709 (`linear`), for any display.
SweepMetrics sweepMetrics(const Chart& chart, const float* code, const float* linear);

} // namespace pacifica::tonemap
