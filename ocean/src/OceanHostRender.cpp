// OceanHostRender: OceanHost.h's registry adapter -- every OceanComponent, Explosion, Ship+ShipTrail and
// SpotLight of the registry drawn by one OceanRenderer::render() -- and the pass clock's translation.
#include "ocean/OceanHost.h"

#include <vector>

namespace pacifica::ocean {

void render(OceanRenderer& renderer, ecs::Registry& registry, const OceanFrame& frame) {
    std::vector<OceanInstance> oceans;
    registry.view<OceanComponent>().each([&](ecs::Entity e, OceanComponent& ocean) {
        oceans.push_back({oceanId(e), &ocean});
    });
    const RegistryEffects effects(registry);
    // A light the component would refuse (NaN position, zero axis...) is left out, not the frame, and
    // counted (OceanStats::spotsRejected).
    std::vector<SpotLight> spots;
    int rejected = 0;
    registry.view<SpotLight>().each([&](ecs::Entity, SpotLight& s) {
        try {
            validateSpotLight(s, spots.size());
            spots.push_back(s);
        } catch (const std::invalid_argument&) {
            ++rejected;
        }
    });
    throwIfFailed(renderer.render({oceans, effects.view(), spots, rejected}, frame));
}

PassClock passClock(gl::GpuTimer::Clock clock) {
    return clock == gl::GpuTimer::Clock::TimerQuery ? PassClock::TimerQuery : PassClock::WallAroundFinish;
}

} // namespace pacifica::ocean
