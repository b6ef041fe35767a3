// makeSurfaceGpu: the GPU twin of a CPU surface model.
#include "gpu/SurfaceGpuFactory.h"

#include "gpu/FftGpu.h"
#include "gpu/GerstnerGpu.h"
#include "gpu/OctavesGpu.h"

#include <stdexcept>
#include <string>

namespace pacifica::ocean {

std::unique_ptr<SurfaceGpu> makeSurfaceGpu(const std::shared_ptr<const SurfaceModel>& model) {
    switch (model->kind()) {
    case SurfaceKind::Octaves:
        return std::make_unique<OctavesGpu>(std::static_pointer_cast<const HeightOctaves>(model));
    case SurfaceKind::Gerstner:
        return std::make_unique<GerstnerGpu>(std::static_pointer_cast<const GerstnerWaves>(model));
    case SurfaceKind::Fft:
        return std::make_unique<FftGpu>(std::static_pointer_cast<const FftCascades>(model));
    default:
        break;
    }
    throw std::invalid_argument(std::string("makeSurfaceGpu(): no GPU implementation for surface model '") +
                                toString(model->kind()) + "'");
}

} // namespace pacifica::ocean
