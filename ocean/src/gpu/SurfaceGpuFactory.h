// makeSurfaceGpu (internal): builds the GPU side matching a CPU surface model.
#pragma once

#include "gpu/SurfaceGpu.h"
#include "ocean/SurfaceModel.h"

#include <memory>

namespace pacifica::ocean {

std::unique_ptr<SurfaceGpu> makeSurfaceGpu(const std::shared_ptr<const SurfaceModel>& model);

} // namespace pacifica::ocean
