// OceanHost: the registry adapter and throwing wrappers over Ocean.h (OceanHost.h).
#include "ocean/OceanHost.h"

#include <vector>

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

void render(OceanRenderer& renderer, ecs::Registry& registry, const OceanFrame& frame) {
    std::vector<OceanInstance> oceans;
    registry.view<OceanComponent>().each([&](ecs::Entity e, OceanComponent& ocean) {
        oceans.push_back({oceanId(e), &ocean});
    });
    const RegistryEffects effects(registry);
    throwIfFailed(renderer.render({oceans, effects.view()}, frame));
}

PassClock passClock(gl::GpuTimer::Clock clock) {
    return clock == gl::GpuTimer::Clock::TimerQuery ? PassClock::TimerQuery : PassClock::WallAroundFinish;
}

} // namespace pacifica::ocean
