// Writes the shipped tonemappers as an OCIO 2.1 config with the LUT files it references, so they run through
// the same OCIO CPU and GPU processors as any studio config. Per-channel curves (Hable, Reinhard, clamp) and
// AgX's sigmoid are CLF LUT1Ds over the half-float domain (one entry per half value: exact at half inputs,
// no shaper needed); AgX's matrices, CDL look and 2.2 power are OCIO transforms. Khronos PBR Neutral is
// chromatic (it uses max and min of RGB), so it is a 3D LUT (.spi3d, tetrahedral) behind a log2 shaper
// (AllocationTransform lg2 over [SHAPER_MIN_EV, SHAPER_MAX_EV] stops of scene-linear) holding sRGB code
// values. Every view ends in sRGB code values (IEC 61966-2-1 encoding, ExponentWithLinear 2.4 / 0.055).
//
// STEP BY STEP
//   1. GeneratedConfig g = writeTonemapConfig(dir, 33);       // writes dir/pacifica-tonemappers.ocio + LUTs
//   2. ColorPipeline p = ColorPipeline::fromFile(g.path); p.select("sRGB", g.views.at("hable"));
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace pacifica::tonemap {

constexpr float SHAPER_MIN_EV = -12.0f; ///< log2 of the smallest scene-linear value the 3D LUT resolves
constexpr float SHAPER_MAX_EV = 10.0f;  ///< log2 of the largest (1024 = 12.5 stops over mid grey)

struct GeneratedConfig {
    std::filesystem::path path; ///< the .ocio file
    std::string display = "sRGB";
    std::map<std::string, std::string> views; ///< tonemapper id -> view name
    /// The HDR display: Rec.2100 PQ (Rec.2020 primaries, SMPTE ST 2084), ACES 1.1 output transform for a
    /// 1000 cd/m^2 display (OCIO built-ins), entered from linear Rec.709 through ACES2065-1.
    std::string hdrDisplay = "Rec.2100-PQ";
    std::string hdrView = "ACES 1.1 - HDR Video (1000 nits & Rec.2020 lim)";
};

/// Writes the config and its LUTs into `dir` (created if missing). lut3dSize: edge of PBR Neutral's 3D LUT
/// (2..129). Files are written whole to a temporary name and renamed. Throws std::runtime_error naming the
/// file on I/O failure, std::invalid_argument on a bad size.
GeneratedConfig writeTonemapConfig(const std::filesystem::path& dir, int lut3dSize = 33);

} // namespace pacifica::tonemap
