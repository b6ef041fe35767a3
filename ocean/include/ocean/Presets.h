// Presets: quality levels picked from the Pareto front of the accuracy sweep (docs/ACCURACY.md, measured on
// llvmpipe and on an NVIDIA H100 at 1920x1080). Each is an OceanDesc for the octave model; choose another
// surface model or override single knobs afterwards. low, medium and high use the packed 4-tap vertex filter
// (listing 18-2: the same bilinear heights from one fetch, bit-identical pixels, cheaper); reference keeps
// the seed's bilinear path. Frame times per preset: docs/PERFORMANCE.md (`./pacifica bench frame`).
//
//   level      grid (rings x segments)  lighting octaves  culling   H100 1080p  image RMSE vs reference
//   low        64 x 128                 3                 on        ~2.8 ms     ~0.0033
//   medium     128 x 256                4                 on        ~3.1 ms     ~0.0024
//   high       256 x 512 (default)      5                 on        ~3.8 ms     ~0.0016
//   reference  512 x 1024               5                 off       ~5.2 ms     0 (it is the reference)
#pragma once

#include "ocean/Ocean.h"

#include <string>

namespace pacifica::ocean {

enum class Quality { Low, Medium, High, Reference };

/// "low", "medium", "high", "reference".
const char* toString(Quality quality);
/// Parses a name from toString(); throws std::invalid_argument listing the valid names.
Quality parseQuality(const std::string& name);

/// The OceanDesc of a quality level (octave model).
OceanDesc oceanPreset(Quality quality);

} // namespace pacifica::ocean
