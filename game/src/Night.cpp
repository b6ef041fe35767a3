// Night: the night sortie's sea and the carrier's lamps (game/Night.h).
#include "game/Night.h"

#include <cmath>
#include <numbers>

namespace pacifica::game {

namespace {

constexpr double DEG = std::numbers::pi / 180.0;

glm::dvec3 direction(double compassDeg, double elevationDeg) {
    const double az = compassDeg * DEG, el = elevationDeg * DEG;
    return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

} // namespace

ocean::OceanDesc nightSea(ocean::OceanDesc d) {
    d.lighting.fogDensity = NIGHT_FOG_DENSITY;
    d.lighting = ocean::moonlit(d.lighting, direction(NIGHT_MOON_AZIMUTH_DEG, NIGHT_MOON_ELEVATION_DEG),
                                NIGHT_MOON_PHASE_DEG);
    d.lighting = ocean::exposed(d.lighting, NIGHT_EXPOSURE_EV);
    return d;
}

std::vector<ocean::SpotLight> carrierLights(const World& world, double exposureScale) {
    std::vector<ocean::SpotLight> lamps;
    if (world.ships().empty() || !world.ships()[0].spec.carrier)
        return lamps;
    const ShipState& carrier = world.ships()[0];
    const double heading = carrier.pose.headingDeg, length = carrier.spec.length;
    const glm::dvec2 at(carrier.pose.position);
    const glm::dvec2 ahead(std::sin(heading * DEG), std::cos(heading * DEG)), right(ahead.y, -ahead.x);
    auto lamp = [&](glm::dvec2 offset, double height, double azimuthDeg, double elevationDeg, double angleDeg,
                    float intensity, double range) {
        ocean::SpotLight s;
        s.position = glm::dvec3(at + ahead * offset.x + right * offset.y, carrier.pose.position.z + height);
        s.direction = direction(heading + azimuthDeg, elevationDeg);
        s.frustumDeg = angleDeg;
        s.color = {1.0f, 0.93f, 0.8f}; // sodium-white deck lighting
        s.intensity = static_cast<float>(intensity * exposureScale);
        s.range = range;
        lamps.push_back(s);
    };
    // Intensities in the sun's units (ocean::SpotLight: 1 ~ 5000 cd). Floodlights on the island (starboard,
    // amidships), ~2e5 cd each, down across the deck, fore and aft.
    lamp({0.05 * length, 0.12 * length}, 45.0, -60.0, -40.0, 30.0, 40.0f, 800.0);
    lamp({-0.15 * length, 0.12 * length}, 45.0, -120.0, -40.0, 30.0, 40.0f, 800.0);
    // The stern light on the wake.
    lamp({-0.5 * length, 0.0}, 22.0, 180.0, -20.0, 18.0, 40.0f, 1000.0);
    // The bow searchlight (~1e8 cd, a large naval searchlight), sweeping.
    const double sweep = 30.0 * std::sin(2.0 * std::numbers::pi * world.time() / 40.0);
    lamp({0.5 * length, 0.0}, 28.0, sweep, -2.0, 3.5, 2.0e4f, 5000.0);
    return lamps;
}

} // namespace pacifica::game
