// OceanHostRender: OceanHost.h's registry adapter -- every OceanComponent, Explosion and Ship+ShipTrail of
// the registry drawn by one OceanRenderer::render() -- and the pass clock's translation.
#include "ocean/OceanHost.h"

#include <vector>

namespace pacifica::ocean {

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
