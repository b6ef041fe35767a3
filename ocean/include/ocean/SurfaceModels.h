// SurfaceModels: builds the CPU surface model an OceanDesc selects.
#pragma once

#include "ocean/Ocean.h"

#include <memory>

namespace pacifica::ocean {

/// Validates the selected model's description (std::invalid_argument naming the field) and builds it.
std::shared_ptr<const SurfaceModel> makeSurfaceModel(const OceanDesc& desc);

} // namespace pacifica::ocean
