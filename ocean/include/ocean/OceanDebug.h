// OceanDebug: hooks into OceanRenderer for tests and accuracy reports. They read GPU results back (they wait
// for the GPU), take Pacifica's registry and throw on error (std::invalid_argument for an entity without an
// OceanComponent): not for a host's frame loop.
#pragma once

#include "engine/Ecs.h"
#include "ocean/Ocean.h"

#include <array>
#include <vector>

namespace pacifica::ocean::debug {

/// The camera-relative positions the sea's vertex shader produces for every grid vertex of `ocean`
/// (transform feedback, nothing drawn), in RadialGrid vertex order. For tests and accuracy reports that
/// compare the GPU with the CPU's double-precision queries.
struct DisplacedVertex {
    glm::vec3 position; ///< camera-relative displaced position (vRel)
    glm::vec2 grid;     ///< camera-relative undisplaced grid point (vGrid)
};
std::vector<DisplacedVertex> displacedVertices(OceanRenderer& renderer, ecs::Registry& registry,
                                               ecs::Entity ocean, const OceanFrame& frame);

/// The displaced vertices of every drawn secondary grid of one effect kind (transform feedback, nothing
/// drawn), instance after instance, each instance in the grid's vertex order. Effects are gathered from
/// the registry at frame.time as render() does. For tests comparing the GPU with oceanHeightAt().
struct EffectVertex {
    glm::vec3 position; ///< camera-relative displaced position (vRel)
    glm::vec2 local;    ///< the displaced point relative to its grid's centre (vLocal)
    glm::dvec2 centre;  ///< the world centre of its grid
};
std::vector<EffectVertex> effectVertices(OceanRenderer& renderer, ecs::Registry& registry, ecs::Entity ocean,
                                         const OceanFrame& frame, EffectKind kind);

/// The tiles of each kind the last tiled compute shading lit (OceanDesc::shadeTiles): edge between sea and
/// sky, sea only, open sky only, sky with the sea beyond the grid. Reads the GPU's counts back, so it waits
/// for the frame. All 0 when no frame was shaded by tiles.
std::array<int, 4> shadeTileCounts(OceanRenderer& renderer);

} // namespace pacifica::ocean::debug
