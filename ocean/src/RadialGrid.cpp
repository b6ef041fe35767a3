// RadialGrid: vertex and index generation for the camera-centred radial grid (GPU Gems 2 §18.2.3).
#include "ocean/RadialGrid.h"

#include <cmath>
#include <numbers>
#include <string>

namespace pacifica::ocean {
namespace {

void require(bool ok, const std::string& message) {
    if (!ok)
        throw std::invalid_argument(message);
}

} // namespace

RadialGrid::RadialGrid(const RadialGridDesc& desc) : mDesc(desc) {
    require(desc.rings >= 2 && desc.rings <= 8192,
            "RadialGridDesc.rings must be in [2, 8192], got " + std::to_string(desc.rings));
    require(desc.segments >= 3 && desc.segments <= 16384,
            "RadialGridDesc.segments must be in [3, 16384], got " + std::to_string(desc.segments));
    require(std::isfinite(desc.rMin) && desc.rMin > 0.0,
            "RadialGridDesc.rMin must be finite and > 0, got " + std::to_string(desc.rMin));
    require(std::isfinite(desc.rMax) && desc.rMax > desc.rMin,
            "RadialGridDesc.rMax must be finite and > rMin, got " + std::to_string(desc.rMax));
    require(std::isfinite(desc.skirtRadius) && (desc.skirtRadius == 0.0 || desc.skirtRadius > desc.rMax),
            "RadialGridDesc.skirtRadius must be 0 or > rMax, got " + std::to_string(desc.skirtRadius));

    // §18.2.3: r_0 = a0 = r_min; r_{N-1} = a0 + a1 (N-1)^4 = r_max.
    const double n1 = static_cast<double>(desc.rings - 1);
    mA0 = desc.rMin;
    mA1 = (desc.rMax - desc.rMin) / (n1 * n1 * n1 * n1);

    const int m = desc.segments;
    require(desc.skirtRings >= 1 && desc.skirtRings <= 256,
            "RadialGridDesc.skirtRings must be in [1, 256], got " + std::to_string(desc.skirtRings));
    const int skirt = desc.skirtRadius > 0.0 ? desc.skirtRings : 0;
    const int ringCount = desc.rings + skirt;
    mVertices.reserve(static_cast<size_t>(3 * (1 + ringCount * m)));
    mVertices.insert(mVertices.end(), {1.0f, 0.0f, 0.0f}); // centre
    for (int i = 0; i < ringCount; ++i) {
        // Skirt ring s = 1..K at rMax * (skirtRadius / rMax)^(s / K): geometric, ending exactly at
        // skirtRadius.
        const double r = i < desc.rings       ? radius(i)
                         : i == ringCount - 1 ? desc.skirtRadius
                                              : desc.rMax * std::pow(desc.skirtRadius / desc.rMax,
                                                                     double(i - desc.rings + 1) / skirt);
        for (int j = 0; j < m; ++j) {
            const double theta = 2.0 * std::numbers::pi * j / m;
            mVertices.push_back(static_cast<float>(std::cos(theta)));
            mVertices.push_back(static_cast<float>(std::sin(theta)));
            mVertices.push_back(static_cast<float>(r));
        }
    }
    auto ringVertex = [m](int ring, int seg) { return static_cast<uint32_t>(1 + ring * m + (seg % m)); };
    for (int j = 0; j < m; ++j) // centre fan
        mIndices.insert(mIndices.end(), {0u, ringVertex(0, j), ringVertex(0, j + 1)});
    for (int i = 0; i + 1 < ringCount; ++i) {
        for (int j = 0; j < m; ++j) {
            const uint32_t a = ringVertex(i, j), b = ringVertex(i, j + 1);
            const uint32_t c = ringVertex(i + 1, j), d = ringVertex(i + 1, j + 1);
            mIndices.insert(mIndices.end(), {a, c, d, a, d, b});
        }
    }
}

double RadialGrid::radius(int ring) const {
    const double i = static_cast<double>(ring);
    return mA0 + mA1 * (i * i) * (i * i);
}

} // namespace pacifica::ocean
