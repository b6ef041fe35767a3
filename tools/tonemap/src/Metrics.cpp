// Image metrics of a display transform and the generated test chart (Metrics.h).
#include "tonemap/Metrics.h"

#include "tonemap/Curves.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace pacifica::tonemap {

namespace {

float luminance(float r, float g, float b) {
    return 0.2126f * r + 0.7152f * g + 0.0722f * b; // Rec.709 / ITU-R BT.709 luma weights on linear RGB
}

bool finite3(const float* p) {
    return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

/// {C / L, hue in degrees} of an Oklab colour; C / L = 0 when L is ~0.
std::array<float, 2> chromaHue(const std::array<float, 3>& lab) {
    const float c = std::hypot(lab[1], lab[2]);
    const float rel = lab[0] > 1e-6f ? c / lab[0] : 0.0f;
    return {rel, std::atan2(lab[2], lab[1]) * 180.0f / std::numbers::pi_v<float>};
}

float hueDistance(float a, float b) {
    float d = std::fabs(a - b);
    return d > 180.0f ? 360.0f - d : d;
}

double stddev(const std::vector<float>& v) {
    if (v.size() < 2)
        return 0.0;
    double mean = 0.0;
    for (float x : v)
        mean += x;
    mean /= static_cast<double>(v.size());
    double s = 0.0;
    for (float x : v)
        s += (x - mean) * (x - mean);
    return std::sqrt(s / static_cast<double>(v.size() - 1));
}

} // namespace

std::array<float, 3> linearToOklab(float r, float g, float b) {
    // Ottosson 2020: linear sRGB -> LMS (M1 folded with the sRGB -> XYZ matrix), cube root, -> Lab (M2).
    const float l = 0.4122214708f * r + 0.5363325363f * g + 0.0514459929f * b;
    const float m = 0.2119034982f * r + 0.6806995451f * g + 0.1073969566f * b;
    const float s = 0.0883024619f * r + 0.2817188376f * g + 0.6299787005f * b;
    const float l_ = std::cbrt(l), m_ = std::cbrt(m), s_ = std::cbrt(s);
    return {0.2104542553f * l_ + 0.7936177850f * m_ - 0.0040720468f * s_,
            1.9779984951f * l_ - 2.4285922050f * m_ + 0.4505937099f * s_,
            0.0259040371f * l_ + 0.7827717662f * m_ - 0.8086757660f * s_};
}

SourceCensus census(const float* rgb, size_t pixels) {
    SourceCensus c;
    c.pixels = pixels;
    for (size_t i = 0; i < pixels; ++i) {
        const float* p = rgb + 3 * i;
        if (std::isnan(p[0]) || std::isnan(p[1]) || std::isnan(p[2]))
            ++c.nan;
        else if (!finite3(p))
            ++c.inf;
        else {
            if (p[0] < 0.0f || p[1] < 0.0f || p[2] < 0.0f)
                ++c.negative;
            c.maxValue = std::max({c.maxValue, p[0], p[1], p[2]});
        }
    }
    return c;
}

namespace {
std::vector<float> srgbDecoded(const float* code, size_t values) {
    std::vector<float> out(values);
    for (size_t i = 0; i < values; ++i)
        out[i] = std::isfinite(code[i]) ? srgbDecode(code[i]) : code[i];
    return out;
}
} // namespace

void xyzToLinearRec709(float* p, size_t pixels) {
    for (size_t i = 0; i < pixels; ++i, p += 3) {
        const float x = p[0], y = p[1], z = p[2];
        p[0] = 3.2404542f * x - 1.5371385f * y - 0.4985314f * z;
        p[1] = -0.9692660f * x + 1.8760108f * y + 0.0415560f * z;
        p[2] = 0.0556434f * x - 0.2040259f * y + 1.0572252f * z;
    }
}

TransformMetrics measure(const float* src, const float* code, size_t pixels) {
    const std::vector<float> linear = srgbDecoded(code, pixels * 3);
    return measure(src, code, linear.data(), pixels);
}

SweepMetrics sweepMetrics(const Chart& chart, const float* code) {
    const std::vector<float> linear = srgbDecoded(code, chart.rgb.size());
    return sweepMetrics(chart, code, linear.data());
}

TransformMetrics measure(const float* src, const float* code, const float* linear, size_t pixels) {
    TransformMetrics m;
    size_t clipped = 0, crushed = 0, chromaticSource = 0, desaturated = 0, neutral = 0;
    double chromaRatioSum = 0.0, neutralSum = 0.0;
    std::vector<float> hueShifts, logSrc, logOut;
    for (size_t i = 0; i < pixels; ++i) {
        const float* s = src + 3 * i;
        const float* o = code + 3 * i;
        if (!finite3(s))
            continue;
        if (!finite3(o) || !finite3(linear + 3 * i)) {
            ++m.nonFiniteOutput;
            continue;
        }
        ++m.pixels;
        const float sr = std::max(s[0], 0.0f), sg = std::max(s[1], 0.0f), sb = std::max(s[2], 0.0f);
        const float ys = luminance(sr, sg, sb);
        const float maxCode = std::max({o[0], o[1], o[2]});
        if (maxCode >= CLIP_CODE)
            ++clipped;
        if (maxCode < CRUSH_CODE && ys > CRUSH_SOURCE_Y)
            ++crushed;
        const float* li = linear + 3 * i;
        const float lr = std::max(li[0], 0.0f), lg = std::max(li[1], 0.0f), lb = std::max(li[2], 0.0f);
        const float yo = luminance(lr, lg, lb);
        if (ys > CRUSH_SOURCE_Y) {
            logSrc.push_back(std::log2(ys));
            logOut.push_back(std::log2(std::max(yo, 1e-6f)));
        }
        const auto labS = linearToOklab(sr, sg, sb);
        if (labS[0] <= 1e-4f)
            continue;
        const auto chS = chromaHue(labS);
        const auto chO = chromaHue(linearToOklab(lr, lg, lb));
        if (chS[0] > CHROMATIC_SOURCE) {
            ++chromaticSource;
            if (chO[0] > CHROMATIC_OUTPUT) {
                hueShifts.push_back(hueDistance(chS[1], chO[1]));
                chromaRatioSum += chO[0] / chS[0];
            } else {
                ++desaturated;
            }
        } else if (chS[0] < 0.005f) {
            ++neutral;
            neutralSum += chO[0];
        }
    }
    const double n = m.pixels ? static_cast<double>(m.pixels) : 1.0;
    m.clipped = static_cast<double>(clipped) / n;
    m.crushed = static_cast<double>(crushed) / n;
    m.chromatic = hueShifts.size();
    m.desaturated =
        chromaticSource ? static_cast<double>(desaturated) / static_cast<double>(chromaticSource) : 0;
    if (!hueShifts.empty()) {
        double sum = 0.0;
        for (float h : hueShifts)
            sum += h;
        m.hueShiftMean = sum / static_cast<double>(hueShifts.size());
        const size_t k = std::min(hueShifts.size() - 1, static_cast<size_t>(0.95 * hueShifts.size()));
        std::nth_element(hueShifts.begin(), hueShifts.begin() + static_cast<std::ptrdiff_t>(k),
                         hueShifts.end());
        m.hueShiftP95 = hueShifts[k];
        m.chromaRatio = chromaRatioSum / static_cast<double>(hueShifts.size());
    }
    const double sdSrc = stddev(logSrc);
    m.contrastKept = sdSrc > 0.0 ? stddev(logOut) / sdSrc : 1.0;
    m.neutralDrift = neutral ? neutralSum / static_cast<double>(neutral) : 0.0;
    return m;
}

size_t Chart::sweepPixel(size_t h, size_t e) const {
    const size_t y = h * static_cast<size_t>(cell) + static_cast<size_t>(cell) / 2;
    const size_t x = e * static_cast<size_t>(cell) + static_cast<size_t>(cell) / 2;
    return y * static_cast<size_t>(width) + x;
}

Chart testChart(int cell) {
    Chart c;
    c.cell = cell;
    for (int ev = -8; ev <= 10; ++ev)
        c.evs.push_back(static_cast<float>(ev));
    // Saturated hues every 30 degrees of HSV hue: primaries, secondaries and the six between them.
    static const char* names[] = {"red",  "orange", "yellow", "chartreuse", "green",   "spring green",
                                  "cyan", "azure",  "blue",   "violet",     "magenta", "rose"};
    std::vector<std::array<float, 3>> colours;
    for (int i = 0; i < 12; ++i) {
        const float h = static_cast<float>(i) / 2.0f; // sextant position 0..6
        auto channel = [&](float offset) {
            float k = std::fmod(h + offset, 6.0f);
            return 1.0f - std::clamp(std::min(k, 4.0f - k), 0.0f, 1.0f); // HSV -> RGB with S = V = 1
        };
        colours.push_back({channel(5.0f), channel(3.0f), channel(1.0f)});
        c.hues.push_back(names[i]);
    }
    const int cols = static_cast<int>(c.evs.size());
    const int sweepRows = static_cast<int>(colours.size()) + 1; // + grey ramp
    c.width = cols * cell;
    c.height = (sweepRows + 1) * cell; // + patch row
    c.rgb.assign(static_cast<size_t>(c.width) * static_cast<size_t>(c.height) * 3, 0.0f);
    auto fill = [&](int x0, int y0, int w, int h, std::array<float, 3> v) {
        for (int y = y0; y < y0 + h; ++y)
            for (int x = x0; x < x0 + w; ++x)
                for (int k = 0; k < 3; ++k)
                    c.rgb[(static_cast<size_t>(y) * static_cast<size_t>(c.width) + static_cast<size_t>(x)) *
                              3 +
                          static_cast<size_t>(k)] = v[static_cast<size_t>(k)];
    };
    for (int row = 0; row < sweepRows; ++row) {
        const std::array<float, 3> base = row < static_cast<int>(colours.size())
                                              ? colours[static_cast<size_t>(row)]
                                              : std::array{1.f, 1.f, 1.f};
        const float y = luminance(base[0], base[1], base[2]);
        for (int e = 0; e < cols; ++e) {
            // Scaled so the patch's luminance is 0.18 * 2^EV: every row crosses mid grey at EV 0.
            const float k = 0.18f * std::exp2(c.evs[static_cast<size_t>(e)]) / y;
            fill(e * cell, row * cell, cell, cell, {base[0] * k, base[1] * k, base[2] * k});
        }
    }
    // Patches: sky, light skin, dark skin, sea, sun glint (scene-linear Rec.709; skin after Macbeth
    // ColorChecker 2005 patches 1-2 linearised, sky a clear daylight zenith, glint a specular sun on water).
    const std::array<std::array<float, 3>, 5> patches = {{{0.20f, 0.35f, 0.70f},
                                                          {0.40f, 0.27f, 0.21f},
                                                          {0.17f, 0.10f, 0.07f},
                                                          {0.01f, 0.04f, 0.06f},
                                                          {60.0f, 55.0f, 48.0f}}};
    const int pw = c.width / static_cast<int>(patches.size());
    for (size_t i = 0; i < patches.size(); ++i)
        fill(static_cast<int>(i) * pw, sweepRows * cell, pw, cell, patches[i]);
    return c;
}

SweepMetrics sweepMetrics(const Chart& chart, const float* code, const float* linear) {
    SweepMetrics m;
    for (size_t h = 0; h <= chart.hues.size(); ++h) {
        float prevY = -1.0f, prevHue = 0.0f;
        bool prevChromatic = false;
        for (size_t e = 0; e < chart.evs.size(); ++e) {
            const float* o = code + 3 * chart.sweepPixel(h, e);
            const float* li = linear + 3 * chart.sweepPixel(h, e);
            const float lr = std::max(li[0], 0.0f), lg = std::max(li[1], 0.0f), lb = std::max(li[2], 0.0f);
            const float y = luminance(lr, lg, lb);
            if (prevY >= 0.0f && y < prevY - 1e-4f)
                ++m.luminanceReversals;
            prevY = y;
            const auto ch = chromaHue(linearToOklab(lr, lg, lb));
            const bool chromatic = ch[0] > CHROMATIC_OUTPUT;
            if (h < chart.hues.size() && chromatic && prevChromatic && hueDistance(ch[1], prevHue) > 30.0f)
                ++m.hueFlips;
            prevChromatic = chromatic;
            prevHue = ch[1];
            if (h == chart.hues.size() && chart.evs[e] == 0.0f)
                m.whereMidGreyLands = o[1];
        }
    }
    return m;
}

} // namespace pacifica::tonemap
