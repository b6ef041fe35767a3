// OceanHost: the throwing wrappers over Ocean.h and the entity ids (OceanHost.h); the registry's render
// adapter, which draws, is in OceanHostRender.cpp, so a program that only makes oceans links no renderer.
#include "ocean/OceanHost.h"

namespace pacifica::ocean {

void throwIfFailed(const Status& status) {
    if (status.ok())
        return;
    if (status.code == ErrorCode::InvalidArgument)
        throw std::invalid_argument(status.message);
    throw OceanError(status);
}

OceanComponent makeOcean(const OceanDesc& desc) {
    OceanComponent c;
    throwIfFailed(makeOcean(desc, c));
    return c;
}

std::uint64_t oceanId(ecs::Entity e) {
    return (static_cast<std::uint64_t>(e.generation) << 32) | e.index;
}

} // namespace pacifica::ocean
