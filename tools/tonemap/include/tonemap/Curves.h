// Closed-form display transforms (the CPU references of the tonemappers `pacifica tonemap` ships as
// generated OCIO configs) and the transfer functions the comparison needs. Input: scene-linear Rec.709 RGB
// (the renderer's working space, 0.18 = mid grey). Output of a tonemapper: display-linear Rec.709 RGB in
// [0, 1] for an SDR display; encode it with srgbEncode() for code values. Every formula names its source.
//
// STEP BY STEP
//   1. const Tonemapper& t = tonemapper("hable");        // or tonemappers() for all, in report order
//   2. std::array<float,3> d = t.apply({r, g, b});        // display-linear, [0, 1]
//   3. code = srgbEncode(d[i]);                           // sRGB display code value
#pragma once

#include <array>
#include <string>
#include <vector>

namespace pacifica::tonemap {

using Rgb = std::array<float, 3>;

/// A closed-form tonemapper with the facts a report states about it.
struct Tonemapper {
    std::string id;          ///< short name used in files: "agx", "agx-punchy", "pbr-neutral", ...
    std::string name;        ///< the report's label, naming the variant exactly
    std::string source;      ///< citation of the equations
    bool perChannel = false; ///< true: the same 1D curve on R, G and B (a 1D LUT represents it)
    Rgb (*apply)(const Rgb&) = nullptr;
    /// For perChannel curves: the curve itself, scene-linear -> display-linear.
    float (*curve)(float) = nullptr;
};

/// All shipped closed-form tonemappers, in report order: AgX base, AgX punchy, Khronos PBR Neutral, Hable,
/// Reinhard extended, clamp.
const std::vector<Tonemapper>& tonemappers();
/// Throws std::invalid_argument listing the valid ids for an unknown one.
const Tonemapper& tonemapper(const std::string& id);

// --- the curves (exposed for tests and the LUT baker) ---------------------------------------------------
/// No tonemapping: min(max(x, 0), 1).
float clampCurve(float x);
/// Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images", eq. 4, applied per channel with
/// white point W = REINHARD_WHITE: x (1 + x / W^2) / (1 + x), clamped to [0, 1] (x >= W maps to >= 1).
constexpr float REINHARD_WHITE = 8.0f;
float reinhardExtended(float x);
/// Hable 2010, "Filmic Tonemapping Operators" (Uncharted 2): f(x) = ((x(Ax+CB)+DE)/(x(Ax+B)+DF)) - E/F with
/// A .15 B .50 C .10 D .20 E .02 F .30; output f(2x) / f(11.2) (exposure bias 2, white 11.2), clamped.
float hable(float x);
/// AgX after Sobotka (github.com/sobotka/AgX), in the minimal Rec.709 form fitted by B. Wrensch 2023
/// ("Minimal AgX implementation", iolite-engine.com): inset matrix, log2 encoding over [-12.47393, 4.026069]
/// EV, a 6th-order polynomial sigmoid, outset (inverse) matrix, power 2.2 to display-linear.
Rgb agxBase(const Rgb& c);
/// AgX with Sobotka's "punchy" look applied after the sigmoid: ASC CDL power 1.35, saturation 1.4
/// (Rec.709 luma weights, clamped before the power as OCIO's CDLTransform does), as in the minimal AgX
/// above. (Blender 4's "Punchy" is a different look.)
Rgb agxPunchy(const Rgb& c);
/// The encoding and sigmoid stages of agxBase for one channel already in AgX's inset space: log2, normalise,
/// polynomial. Exposed because the generated OCIO config bakes exactly this into a 1D LUT.
float agxSigmoid(float x);
/// 3x3 matrices of agxBase, row-major (out[i] = sum_j m[i][j] in[j]).
extern const float AGX_INSET[3][3];
extern const float AGX_OUTSET[3][3];
/// Khronos PBR Neutral (KhronosGroup/ToneMapping, PBR_Neutral/README.md, Apache-2.0): start compression
/// 0.76, desaturation 0.15, toe x - x^2 / (4 * 0.04) below 0.08.
Rgb pbrNeutral(const Rgb& c);

// --- transfer functions ----------------------------------------------------------------------------------
/// IEC 61966-2-1 sRGB: display-linear [0, 1] -> code value (piecewise, 12.92 below 0.0031308).
float srgbEncode(float linear);
/// The inverse of srgbEncode().
float srgbDecode(float code);
/// SMPTE ST 2084 (PQ) inverse EOTF: absolute luminance in cd/m^2 -> code value in [0, 1]
/// (m1 = 2610/16384, m2 = 2523/4096 * 128, c1 = 3424/4096, c2 = 2413/4096 * 32, c3 = 2392/4096 * 32).
float pqEncode(float nits);
/// SMPTE ST 2084 EOTF: code value -> cd/m^2.
float pqDecode(float code);

} // namespace pacifica::tonemap
