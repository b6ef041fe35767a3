// Night: the game's night sortie (--night) -- a moonlit, hazy sea, pre-exposed so the frame stays in half
// float's normal range, and the carrier's lamps: two deck floodlights from the island, a stern light over the
// wake and a bow searchlight sweeping the sea ahead (ocean::SpotLight, their beams in the haze).
#pragma once

#include "game/World.h"

#include <ocean/Lighting.h>
#include <ocean/Ocean.h>

#include <vector>

namespace pacifica::game {

/// Stops the night sortie's lights are pre-exposed by (ocean::exposed): a moonlit sea is ~2e-6 of daylight.
inline constexpr double NIGHT_EXPOSURE_EV = 16.0;
/// The Moon of the night sortie: compass direction, elevation and phase angle, degrees.
inline constexpr double NIGHT_MOON_AZIMUTH_DEG = 200.0, NIGHT_MOON_ELEVATION_DEG = 25.0,
                        NIGHT_MOON_PHASE_DEG = 40.0;
/// The night's haze, 1/m at sea level (~10 km visibility, Koschmieder): the lamps' beams show in it.
inline constexpr float NIGHT_FOG_DENSITY = 4.0e-4f;

/// `day` as the night sortie's sea: moonlit (ocean::moonlit), hazy and pre-exposed by NIGHT_EXPOSURE_EV.
ocean::OceanDesc nightSea(ocean::OceanDesc day);

/// The carrier's lamps (world.ships()[0]) at the world's time, intensities times `exposureScale` (2^EV, the
/// sea's pre-exposure): floodlights on the deck from the island, a stern light on the wake, and a bow
/// searchlight sweeping +-30 degrees about the heading every 40 s. None when the world has no carrier.
std::vector<ocean::SpotLight> carrierLights(const World& world, double exposureScale);

} // namespace pacifica::game
