// OceanHost: what Pacifica's own hosts (the game, the replay, the benches: exceptions on, engine's ECS) add
// on top of the exception-free component API of Ocean.h. A host on another entity system, or built with
// -fno-exceptions, does not include it.
//
//   auto e = registry.create();
//   registry.emplace<OceanComponent>(e, makeOcean(desc));   // throws std::invalid_argument naming the field
//   render(renderer, registry, frame);                       // every OceanComponent, Explosion,
//   Ship+ShipTrail
//
// The adapter lists the registry's oceans (id = the entity's handle), explosions and wakes in its view order
// and calls OceanRenderer::render(); an error Status becomes an exception (OceanError, or
// std::invalid_argument for InvalidArgument), as everywhere else in these hosts.
#pragma once

#include "engine/Ecs.h"
#include "engine/gl/GpuTimer.h"
#include "ocean/Effects.h"
#include "ocean/Ocean.h"

#include <stdexcept>

namespace pacifica::ocean {

/// A failed Status as an exception: what OceanHost's wrappers throw for any code but InvalidArgument.
class OceanError : public std::runtime_error {
public:
    explicit OceanError(Status status) : std::runtime_error(status.message), mCode(status.code) {}
    ErrorCode code() const { return mCode; }

private:
    ErrorCode mCode;
};

/// Throws for a failed status (std::invalid_argument for InvalidArgument, OceanError otherwise).
void throwIfFailed(const Status& status);

/// makeOcean() that returns the component and throws std::invalid_argument naming the field.
OceanComponent makeOcean(const OceanDesc& desc);

/// Renders every OceanComponent of the registry with its effects (RegistryEffects) and its SpotLight
/// components (those validateSpotLight() refuses left out); throws on error.
void render(OceanRenderer& renderer, ecs::Registry& registry, const OceanFrame& frame);

/// The ocean's pass clock for an engine GpuTimer's.
PassClock passClock(gl::GpuTimer::Clock clock);

/// The OceanInstance id of an entity (its index and generation).
std::uint64_t oceanId(ecs::Entity e);

} // namespace pacifica::ocean
