// Closed-form tonemappers and transfer functions; the sources are cited in Curves.h.
#include "tonemap/Curves.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pacifica::tonemap {

namespace {

float clamp01(float x) {
    return std::isnan(x) ? 0.0f : std::min(std::max(x, 0.0f), 1.0f);
}

Rgb mul(const float m[3][3], const Rgb& c) {
    return {m[0][0] * c[0] + m[0][1] * c[1] + m[0][2] * c[2],
            m[1][0] * c[0] + m[1][1] * c[1] + m[1][2] * c[2],
            m[2][0] * c[0] + m[2][1] * c[1] + m[2][2] * c[2]};
}

// Hable's constants (Curves.h).
constexpr float HA = 0.15f, HB = 0.50f, HC = 0.10f, HD = 0.20f, HE = 0.02f, HF = 0.30f, HW = 11.2f;
float hablePartial(float x) {
    return ((x * (HA * x + HC * HB) + HD * HE) / (x * (HA * x + HB) + HD * HF)) - HE / HF;
}

constexpr float AGX_MIN_EV = -12.47393f, AGX_MAX_EV = 4.026069f;

Rgb agxCore(const Rgb& c, bool punchy) {
    Rgb v = mul(AGX_INSET, c);
    for (float& x : v)
        x = agxSigmoid(x);
    if (punchy) {
        // ASC CDL v1.2 (slope 1, offset 0) power 1.35 then saturation 1.4 about Rec.709 luma, evaluated as
        // OCIO 2.1's CDLTransform does it: clamped to [0, 1] before the power, not after the saturation
        // (checked against OCIO in test_tonemap_compare; clamping there too differs by 7e-3 on bright blues).
        for (float& x : v)
            x = std::pow(clamp01(x), 1.35f);
        const float luma = 0.2126f * v[0] + 0.7152f * v[1] + 0.0722f * v[2];
        for (float& x : v)
            x = luma + 1.4f * (x - luma);
    }
    v = mul(AGX_OUTSET, v);
    for (float& x : v)
        x = clamp01(std::pow(std::max(x, 0.0f), 2.2f)); // the 2.2 display the sigmoid was fitted for
    return v;
}

Rgb perChannel(const Rgb& c, float (*f)(float)) {
    return {f(c[0]), f(c[1]), f(c[2])};
}

} // namespace

const float AGX_INSET[3][3] = {{0.842479062253094f, 0.0784335999999992f, 0.0792237451477643f},
                               {0.0423282422610123f, 0.878468636469772f, 0.0791661274605434f},
                               {0.0423756549057051f, 0.0784336f, 0.879142973793104f}};
const float AGX_OUTSET[3][3] = {{1.19687900512017f, -0.0980208811401368f, -0.0990297440797205f},
                                {-0.0528968517574562f, 1.15190312990417f, -0.0989611768448433f},
                                {-0.0529716355144438f, -0.0980434501171241f, 1.15107367264116f}};

float clampCurve(float x) {
    return clamp01(x);
}

float reinhardExtended(float x) {
    if (std::isnan(x) || x <= 0.0f)
        return 0.0f;
    if (x >= REINHARD_WHITE)
        return 1.0f;
    return clamp01(x * (1.0f + x / (REINHARD_WHITE * REINHARD_WHITE)) / (1.0f + x));
}

float hable(float x) {
    if (std::isnan(x) || x <= 0.0f)
        return 0.0f;
    if (std::isinf(x))
        return 1.0f;
    return clamp01(hablePartial(2.0f * x) / hablePartial(HW));
}

float agxSigmoid(float x) {
    // log2 encoding, normalised to [0, 1] over AgX's EV range; below the range (and 0, negatives, NaN) -> 0.
    float e = std::isnan(x) || x <= 0.0f ? AGX_MIN_EV : std::log2(x);
    e = std::min(std::max(e, AGX_MIN_EV), AGX_MAX_EV);
    const float t = (e - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV);
    const float t2 = t * t, t4 = t2 * t2;
    return 15.5f * t4 * t2 - 40.14f * t4 * t + 31.96f * t4 - 6.868f * t2 * t + 0.4298f * t2 + 0.1191f * t -
           0.00232f;
}

Rgb agxBase(const Rgb& c) {
    return agxCore(c, false);
}

Rgb agxPunchy(const Rgb& c) {
    return agxCore(c, true);
}

Rgb pbrNeutral(const Rgb& in) {
    constexpr float START = 0.8f - 0.04f, DESATURATION = 0.15f;
    Rgb c = in;
    for (float& x : c)
        x = std::isnan(x) ? 0.0f : std::min(std::max(x, 0.0f), 3.0e38f);
    const float x = std::min({c[0], c[1], c[2]});
    const float offset = x < 0.08f ? x - 6.25f * x * x : 0.04f;
    for (float& v : c)
        v -= offset;
    const float peak = std::max({c[0], c[1], c[2]});
    if (peak < START) {
        for (float& v : c)
            v = clamp01(v);
        return c;
    }
    constexpr float D = 1.0f - START;
    const float newPeak = 1.0f - D * D / (peak + D - START);
    for (float& v : c)
        v *= newPeak / peak;
    const float g = 1.0f - 1.0f / (DESATURATION * (peak - newPeak) + 1.0f);
    for (float& v : c)
        v = clamp01(v + (newPeak - v) * g);
    return c;
}

float srgbEncode(float v) {
    v = clamp01(v);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float c) {
    c = clamp01(c);
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

namespace {
constexpr double PQ_M1 = 2610.0 / 16384.0, PQ_M2 = 2523.0 / 4096.0 * 128.0, PQ_C1 = 3424.0 / 4096.0,
                 PQ_C2 = 2413.0 / 4096.0 * 32.0, PQ_C3 = 2392.0 / 4096.0 * 32.0;
}

float pqEncode(float nits) {
    if (std::isnan(nits) || nits <= 0.0f)
        return 0.0f;
    const double y = std::min(static_cast<double>(nits), 10000.0) / 10000.0;
    const double p = std::pow(y, PQ_M1);
    return static_cast<float>(std::pow((PQ_C1 + PQ_C2 * p) / (1.0 + PQ_C3 * p), PQ_M2));
}

float pqDecode(float code) {
    if (std::isnan(code) || code <= 0.0f)
        return 0.0f;
    const double e = std::pow(std::min(static_cast<double>(code), 1.0), 1.0 / PQ_M2);
    const double y = std::pow(std::max(e - PQ_C1, 0.0) / (PQ_C2 - PQ_C3 * e), 1.0 / PQ_M1);
    return static_cast<float>(10000.0 * y);
}

const std::vector<Tonemapper>& tonemappers() {
    static const std::vector<Tonemapper> all = {
        {"agx", "AgX base (Sobotka, minimal Rec.709 fit)", "Sobotka AgX; Wrensch 2023 minimal fit", false,
         agxBase, nullptr},
        {"agx-punchy", "AgX punchy (Sobotka look: CDL power 1.35, sat 1.4)",
         "Sobotka AgX punchy look; Wrensch 2023", false, agxPunchy, nullptr},
        {"pbr-neutral", "Khronos PBR Neutral", "KhronosGroup/ToneMapping PBR_Neutral (Apache-2.0)", false,
         pbrNeutral, nullptr},
        {"hable", "Hable filmic (Uncharted 2, bias 2, W 11.2)", "Hable 2010, Filmic Tonemapping Operators",
         true, [](const Rgb& c) { return perChannel(c, hable); }, hable},
        {"reinhard", "Reinhard extended (per channel, W 8)", "Reinhard et al. 2002, eq. 4", true,
         [](const Rgb& c) { return perChannel(c, reinhardExtended); }, reinhardExtended},
        {"clamp", "Clamp (no tonemap)", "min(max(x, 0), 1)", true,
         [](const Rgb& c) { return perChannel(c, clampCurve); }, clampCurve},
    };
    return all;
}

const Tonemapper& tonemapper(const std::string& id) {
    std::string valid;
    for (const Tonemapper& t : tonemappers()) {
        if (t.id == id)
            return t;
        valid += (valid.empty() ? "" : ", ") + t.id;
    }
    throw std::invalid_argument("unknown tonemapper '" + id + "'; valid: " + valid);
}

} // namespace pacifica::tonemap
