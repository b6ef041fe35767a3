// Diagnostic sheet pieces (Sheets.h).
#include "tonemap/Sheets.h"

#include <algorithm>
#include <cmath>

namespace pacifica::tonemap {

Canvas::Canvas(int w, int h, float background)
    : width(w), height(h), rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, background) {}

void Canvas::blit(const float* src, int w, int h, int x, int y) {
    for (int row = 0; row < h; ++row) {
        const int cy = y + row;
        if (cy < 0 || cy >= height)
            continue;
        for (int col = 0; col < w; ++col) {
            const int cx = x + col;
            if (cx < 0 || cx >= width)
                continue;
            const size_t s =
                (static_cast<size_t>(row) * static_cast<size_t>(w) + static_cast<size_t>(col)) * 3;
            const size_t d =
                (static_cast<size_t>(cy) * static_cast<size_t>(width) + static_cast<size_t>(cx)) * 3;
            std::copy_n(src + s, 3, rgb.begin() + static_cast<std::ptrdiff_t>(d));
        }
    }
}

void Canvas::fillRect(int x, int y, int w, int h, const std::array<float, 3>& c) {
    for (int row = std::max(0, y); row < std::min(height, y + h); ++row)
        for (int col = std::max(0, x); col < std::min(width, x + w); ++col)
            std::copy_n(c.begin(), 3,
                        rgb.begin() + static_cast<std::ptrdiff_t>(
                                          (static_cast<size_t>(row) * static_cast<size_t>(width) +
                                           static_cast<size_t>(col)) *
                                          3));
}

std::vector<float> downscaleBox(const std::vector<float>& rgb, int w, int h, int tw, int& th) {
    th = std::max(1, static_cast<int>(std::lround(static_cast<double>(h) * tw / w)));
    std::vector<float> out(static_cast<size_t>(tw) * static_cast<size_t>(th) * 3, 0.0f);
    for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x) {
            const int x0 = x * w / tw, x1 = std::max(x0 + 1, (x + 1) * w / tw);
            const int y0 = y * h / th, y1 = std::max(y0 + 1, (y + 1) * h / th);
            double s[3] = {0, 0, 0};
            for (int yy = y0; yy < y1; ++yy)
                for (int xx = x0; xx < x1; ++xx)
                    for (size_t k = 0; k < 3; ++k)
                        s[k] +=
                            rgb[(static_cast<size_t>(yy) * static_cast<size_t>(w) + static_cast<size_t>(xx)) *
                                    3 +
                                k];
            const double n = static_cast<double>((x1 - x0) * (y1 - y0));
            for (size_t k = 0; k < 3; ++k)
                out[(static_cast<size_t>(y) * static_cast<size_t>(tw) + static_cast<size_t>(x)) * 3 + k] =
                    static_cast<float>(s[k] / n);
        }
    return out;
}

const std::vector<StopBand> FALSE_COLOUR_BANDS = {
    {-1e9f, -8.0f, {0.05f, 0.0f, 0.1f}, "< -8"},     {-8.0f, -6.0f, {0.3f, 0.0f, 0.5f}, "-8..-6"},
    {-6.0f, -4.0f, {0.1f, 0.1f, 0.8f}, "-6..-4"},    {-4.0f, -2.0f, {0.0f, 0.55f, 0.9f}, "-4..-2"},
    {-2.0f, -0.5f, {0.0f, 0.6f, 0.45f}, "-2..-0.5"}, {-0.5f, 0.5f, {0.5f, 0.5f, 0.5f}, "0 (grey)"},
    {0.5f, 2.0f, {0.45f, 0.8f, 0.2f}, "0.5..2"},     {2.0f, 4.0f, {0.95f, 0.9f, 0.1f}, "2..4"},
    {4.0f, 6.0f, {1.0f, 0.55f, 0.0f}, "4..6"},       {6.0f, 8.0f, {0.95f, 0.1f, 0.1f}, "6..8"},
    {8.0f, 12.0f, {1.0f, 0.5f, 0.8f}, "8..12"},      {12.0f, 1e9f, {1.0f, 1.0f, 1.0f}, "> 12"},
};

std::vector<float> falseColourStops(const float* s, size_t pixels) {
    std::vector<float> out(pixels * 3);
    for (size_t i = 0; i < pixels; ++i) {
        const float y = 0.2126f * s[3 * i] + 0.7152f * s[3 * i + 1] + 0.0722f * s[3 * i + 2];
        const float stops = std::isfinite(y) && y > 0.0f ? std::log2(y / 0.18f) : -1e9f;
        const StopBand* band = &FALSE_COLOUR_BANDS.front();
        for (const StopBand& b : FALSE_COLOUR_BANDS)
            if (stops >= b.lo && stops < b.hi)
                band = &b;
        if (stops >= FALSE_COLOUR_BANDS.back().lo)
            band = &FALSE_COLOUR_BANDS.back();
        std::copy_n(band->colour.begin(), 3, out.begin() + static_cast<std::ptrdiff_t>(3 * i));
    }
    return out;
}

Histogram histogram(const float* code, size_t pixels, int bins) {
    Histogram h;
    h.bins = bins;
    h.pixels = pixels;
    for (auto& c : h.counts)
        c.assign(static_cast<size_t>(bins), 0);
    for (size_t i = 0; i < pixels; ++i)
        for (size_t k = 0; k < 3; ++k) {
            const float v = code[3 * i + k];
            const float c = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
            const int b = std::min(bins - 1, static_cast<int>(c * static_cast<float>(bins)));
            ++h.counts[k][static_cast<size_t>(b)];
        }
    return h;
}

void plotHistogram(Canvas& canvas, int x, int y, int w, int h, const Histogram& hst) {
    canvas.fillRect(x, y, w, h, {0.05f, 0.05f, 0.05f});
    size_t peak = 1;
    for (const auto& c : hst.counts)
        for (size_t n : c)
            peak = std::max(peak, n);
    const double logPeak = std::log1p(static_cast<double>(peak));
    static const std::array<std::array<float, 3>, 3> tint = {
        {{1, 0.2f, 0.2f}, {0.2f, 1, 0.2f}, {0.3f, 0.4f, 1}}};
    for (int col = 0; col < w; ++col) {
        const size_t b = static_cast<size_t>(col) * static_cast<size_t>(hst.bins) / static_cast<size_t>(w);
        for (size_t k = 0; k < 3; ++k) {
            const int bar = static_cast<int>(std::lround(
                static_cast<double>(h) * std::log1p(static_cast<double>(hst.counts[k][b])) / logPeak));
            for (int row = h - bar; row < h; ++row) {
                float* p = &canvas.rgb[(static_cast<size_t>(y + row) * static_cast<size_t>(canvas.width) +
                                        static_cast<size_t>(x + col)) *
                                       3];
                if (y + row < 0 || y + row >= canvas.height || x + col < 0 || x + col >= canvas.width)
                    continue;
                for (size_t c = 0; c < 3; ++c)
                    p[c] = std::min(1.0f, p[c] + 0.55f * tint[k][c]); // additive: overlaps turn white
            }
        }
    }
}

std::vector<float> wipe(const float* a, const float* b, int w, int h) {
    std::vector<float> out(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3;
            const float* src = x < w / 2 ? a : b;
            for (size_t k = 0; k < 3; ++k)
                out[i + k] = x == w / 2 - 1 || x == w / 2 ? 1.0f : src[i + k];
        }
    return out;
}

std::vector<float> difference(const float* a, const float* b, size_t pixels, float gain, float& maxDiff) {
    std::vector<float> out(pixels * 3);
    maxDiff = 0.0f;
    for (size_t i = 0; i < pixels * 3; ++i) {
        const float d = std::fabs(a[i] - b[i]);
        maxDiff = std::max(maxDiff, d);
        out[i] = std::min(1.0f, d * gain);
    }
    return out;
}

} // namespace pacifica::tonemap
