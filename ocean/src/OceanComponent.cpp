// OceanComponent: the component's CPU side -- an ocean made from its description (every field validated,
// naming it) and its heights queried -- apart from the renderer (OceanRenderer.cpp), so a program that
// only builds or queries oceans links no GL pass.
#include "ocean/Ocean.h"

#include "Guarded.h"
#include "ocean/SurfaceModels.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace pacifica::ocean {

namespace {

void validateEffectGrids(const EffectGridDesc& g) {
    auto check = [](bool ok, const std::string& what) {
        if (!ok)
            throw std::invalid_argument("OceanDesc.effectGrids." + what);
    };
    for (const auto& [name, rings, segments, exponent] :
         {std::tuple{"explosion", g.explosionRings, g.explosionSegments, g.explosionExponent},
          std::tuple{"wake", g.wakeRings, g.wakeSegments, g.wakeExponent}}) {
        check(rings >= 1 && rings <= 1024,
              std::string(name) + "Rings must be in [1, 1024], got " + std::to_string(rings));
        check(segments >= 3 && segments <= 4096,
              std::string(name) + "Segments must be in [3, 4096], got " + std::to_string(segments));
        check(std::isfinite(exponent) && exponent >= 0.25 && exponent <= 8.0,
              std::string(name) + "Exponent must be in [0.25, 8], got " + std::to_string(exponent));
    }
    check(g.maxExplosionGrids >= 0 && g.maxExplosionGrids <= 4096 && g.maxWakeGrids >= 0 &&
              g.maxWakeGrids <= 4096,
          "maxExplosionGrids and maxWakeGrids must be in [0, 4096]");
    check(std::isfinite(g.minAngularSize) && g.minAngularSize >= 0.0,
          "minAngularSize must be finite and >= 0, got " + std::to_string(g.minAngularSize));
    check(std::isfinite(g.minAmplitudePixels) && g.minAmplitudePixels >= 0.0,
          "minAmplitudePixels must be finite and >= 0, got " + std::to_string(g.minAmplitudePixels));
}

OceanComponent buildOcean(const OceanDesc& desc) {
    validateLighting(desc.lighting); // names the field (ocean/include/ocean/Lighting.h)
    validateEffectGrids(desc.effectGrids);
    validate(desc.effectField);
    RadialGrid::validate(desc.grid); // names the field
    OceanComponent c;
    c.desc = desc;
    c.surface = makeSurfaceModel(desc);
    return c;
}

} // namespace

Status makeOcean(const OceanDesc& desc, OceanComponent& out) noexcept {
    return guarded([&] { out = buildOcean(desc); });
}

Status heightsAt(const OceanComponent& ocean, const EffectsView& effects, std::span<const glm::dvec2> points,
                 double t, std::span<double> heights) noexcept {
    return guarded([&] {
        if (!ocean.surface)
            throw std::invalid_argument(
                "heightsAt(): the OceanComponent has no surface (made by makeOcean?)");
        if (points.size() != heights.size())
            throw std::invalid_argument(
                "heightsAt(): points and heights differ in size: " + std::to_string(points.size()) + " vs " +
                std::to_string(heights.size()));
        requireFinite(std::isfinite(t), "heightsAt(): time");
        for (size_t i = 0; i < points.size(); ++i)
            requireFinite(std::isfinite(points[i].x) && std::isfinite(points[i].y),
                          "heightsAt(): points[" + std::to_string(i) + "]");
        std::vector<double> out(points.size()); // `heights` stays as it was if a query throws
        for (size_t i = 0; i < points.size(); ++i)
            out[i] = ocean.surface->heightAt(points[i], t) +
                     (effects.empty() ? 0.0 : effectsAt(effects, points[i], t).x);
        std::copy(out.begin(), out.end(), heights.begin());
    });
}

} // namespace pacifica::ocean
