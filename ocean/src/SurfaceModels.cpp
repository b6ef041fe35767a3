// makeSurfaceModel: the CPU surface model an OceanDesc selects.
#include "ocean/SurfaceModels.h"

#include "ocean/FftOcean.h"
#include "ocean/GerstnerWaves.h"
#include "ocean/HeightOctaves.h"

#include <stdexcept>
#include <string>

namespace pacifica::ocean {

std::shared_ptr<const SurfaceModel> makeSurfaceModel(const OceanDesc& desc) {
    switch (desc.model) {
    case SurfaceKind::Octaves:
        return std::make_shared<HeightOctaves>(desc.octaves);
    case SurfaceKind::Gerstner:
        return std::make_shared<GerstnerWaves>(desc.gerstner);
    case SurfaceKind::Fft:
        return std::make_shared<FftCascades>(desc.fft);
    default:
        break;
    }
    throw std::invalid_argument(std::string("OceanDesc.model: surface model '") + toString(desc.model) +
                                "' is not available in this build");
}

} // namespace pacifica::ocean
