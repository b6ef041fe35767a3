// RadialGrid: vertex and index generation for the camera-centred radial grid (GPU Gems 2 §18.2.3).
#include "ocean/RadialGrid.h"

#include "GridOrder.h"

#include <algorithm>
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

void RadialGrid::validate(const RadialGridDesc& desc) {
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
    require(desc.skirtRings >= 1 && desc.skirtRings <= 256,
            "RadialGridDesc.skirtRings must be in [1, 256], got " + std::to_string(desc.skirtRings));
    require(std::isfinite(desc.minRingPixels) && desc.minRingPixels >= 0.0 && desc.minRingPixels <= 1000.0,
            "RadialGridDesc.minRingPixels must be in [0, 1000], got " + std::to_string(desc.minRingPixels));
}

RadialGrid::RadialGrid(const RadialGridDesc& desc) : mDesc(desc) {
    validate(desc);

    // §18.2.3: r_0 = a0 = r_min; r_{N-1} = a0 + a1 (N-1)^4 = r_max.
    const double n1 = static_cast<double>(desc.rings - 1);
    mA0 = desc.rMin;
    mA1 = (desc.rMax - desc.rMin) / (n1 * n1 * n1 * n1);

    const int m = desc.segments;
    const int skirt = desc.skirtRadius > 0.0 ? desc.skirtRings : 0;
    const int ringsTotal = desc.rings + skirt;
    // Rings are padded to a stride for vertex reuse (GridOrder.h); the padding repeats the ring's last
    // vertex.
    mRingStride = ringStrideFor(m);
    mVertices.reserve(static_cast<size_t>(2 * (1 + ringsTotal * mRingStride)));
    mVertices.insert(mVertices.end(), {0.5f, 0.0f}); // centre
    for (int i = 0; i < ringsTotal; ++i) {
        // Skirt ring s = 1..K at rMax * (skirtRadius / rMax)^(s / K): geometric, ending exactly at
        // skirtRadius.
        const double r = i < desc.rings        ? radius(i)
                         : i == ringsTotal - 1 ? desc.skirtRadius
                                               : desc.rMax * std::pow(desc.skirtRadius / desc.rMax,
                                                                      double(i - desc.rings + 1) / skirt);
        // M + 1 columns u = j / M: the sector's two edges are separate vertices (for a full circle they
        // coincide), so the same mesh serves any view sector.
        for (int j = 0; j < mRingStride; ++j) {
            mVertices.push_back(static_cast<float>(double(std::min(j, m)) / m));
            mVertices.push_back(static_cast<float>(r));
        }
    }
    std::vector<int> all(static_cast<size_t>(ringsTotal));
    for (int i = 0; i < ringsTotal; ++i)
        all[static_cast<size_t>(i)] = i;
    mIndices = indicesFor(all);
}

int RadialGrid::ringCount() const {
    return mDesc.rings + (mDesc.skirtRadius > 0.0 ? mDesc.skirtRings : 0);
}

int RadialGrid::ringStrideFor(int segments) {
    return gridorder::rowStride(segments + 1);
}

double RadialGrid::ringRadius(int ring) const {
    return mVertices[2 * static_cast<size_t>(vertexIndex(ring, 0)) + 1];
}

uint32_t RadialGrid::vertexIndex(int ring, int column) const {
    return static_cast<uint32_t>(1 + ring * mRingStride + column);
}

size_t RadialGrid::indexedVertexCount() const {
    return 1 + static_cast<size_t>(ringCount()) * static_cast<size_t>(mDesc.segments + 1);
}

std::vector<uint32_t> RadialGrid::indicesFor(const std::vector<int>& rings) const {
    const int m = mDesc.segments;
    auto ringVertex = [this](int ring, int col) { return vertexIndex(ring, col); };
    std::vector<uint32_t> out;
    if (rings.empty())
        return out;
    out.reserve(static_cast<size_t>(3 * m) + (rings.size() - 1) * static_cast<size_t>(6 * m));
    for (int j = 0; j < m; ++j) // centre fan
        out.insert(out.end(), {0u, ringVertex(rings.front(), j), ringVertex(rings.front(), j + 1)});
    gridorder::appendQuadsInBlocks(out, rings, m, ringVertex);
    return out;
}

std::vector<RadialGrid::IndexRange> RadialGrid::rangesFrom(size_t ringsDrawn, size_t firstPair) const {
    // indicesFor()'s layout: the centre fan (3 M indices), then per block of columns every ring pair's quads
    // (6 indices a quad), ring pair after ring pair outward (GridOrder.h).
    const size_t m = static_cast<size_t>(mDesc.segments);
    const size_t pairs = ringsDrawn > 0 ? ringsDrawn - 1 : 0;
    const size_t total = ringsDrawn > 0 ? 3 * m + 6 * m * pairs : 0;
    if (firstPair == 0 || total == 0)
        return {{0, total}};
    std::vector<IndexRange> out;
    if (firstPair >= pairs)
        return out;
    size_t offset = 3 * m;
    for (size_t j0 = 0; j0 < m; j0 += gridorder::BLOCK_COLUMNS) {
        const size_t width = std::min<size_t>(gridorder::BLOCK_COLUMNS, m - j0);
        out.push_back({offset + 6 * width * firstPair, 6 * width * (pairs - firstPair)});
        offset += 6 * width * pairs;
    }
    return out;
}

std::vector<int> RadialGrid::ringsFor(const RingView& view, double minPixels) const {
    const int total = ringCount();
    std::vector<int> out;
    out.reserve(static_cast<size_t>(total));
    if (!(minPixels > 0.0) || !(view.pixelsPerRadian > 0.0) || !std::isfinite(view.height)) {
        for (int i = 0; i < total; ++i)
            out.push_back(i);
        return out;
    }
    // Depression angle of the sea point at radius r seen from height h above it: the sea drops r^2 / 2R.
    const double h = std::max(std::abs(view.height), 1e-3);
    const double k = view.earthRadius > 0.0 ? 0.5 / view.earthRadius : 0.0;
    auto depression = [&](double r) { return std::atan2(h + k * r * r, r); };
    const double minAngle = minPixels / view.pixelsPerRadian;
    const int last = mDesc.rings - 1;
    out.push_back(0);
    double kept = depression(radius(0));
    // Keep chords short too (each kept ring within RING_MAX_RATIO of the previous one's radius): near the
    // horizon the rings crowd into a few pixels, and long chords there moved the horizon by a pixel and
    // bent the perspective interpolation of the lighting's grid coordinate (image RMSE x10 without it).
    constexpr double RING_MAX_RATIO = 1.1;
    double keptRadius = radius(0);
    for (int i = 1; i < last; ++i) {
        const double d = depression(radius(i));
        if (std::abs(kept - d) >= minAngle || radius(i + 1) > RING_MAX_RATIO * keptRadius) {
            out.push_back(i);
            kept = d;
            keptRadius = radius(i);
        }
    }
    for (int i = last; i < total; ++i)
        out.push_back(i);
    return out;
}

ViewSector computeViewSector(const CameraFrame& camera, double guardRad) {
    // The frustum is the cone of positive combinations of its 4 corner rays; its horizontal projection is the
    // cone spanned by the projected corners: an arc if they fit in a half-plane, else the whole circle.
    const glm::dmat4 invViewProj = glm::inverse(glm::dmat4(camera.viewProj));
    double az[4];
    int n = 0;
    const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
        const glm::dvec4 p = invViewProj * glm::dvec4(c[0], c[1], 0.5, 1.0);
        const glm::dvec3 dir = glm::dvec3(p) / p.w;
        const double horizontal = std::hypot(dir.x, dir.y);
        if (!(horizontal > 1e-9 * glm::length(dir)))
            return {0.0, std::numbers::pi}; // a corner looks straight up or down: all azimuths
        az[n++] = std::atan2(dir.y, dir.x);
    }
    std::sort(az, az + 4);
    double gap = az[0] + 2.0 * std::numbers::pi - az[3], gapEnd = az[0];
    for (int i = 1; i < 4; ++i) {
        if (az[i] - az[i - 1] > gap) {
            gap = az[i] - az[i - 1];
            gapEnd = az[i];
        }
    }
    if (gap <= std::numbers::pi)
        return {0.0, std::numbers::pi}; // the projected cone is the whole plane (nadir or zenith in view)
    const double arc = 2.0 * std::numbers::pi - gap; // from gapEnd counter-clockwise
    const double half = arc / 2.0 + guardRad;
    if (half >= std::numbers::pi)
        return {0.0, std::numbers::pi};
    return {std::remainder(gapEnd + arc / 2.0, 2.0 * std::numbers::pi), half};
}

double hiddenDiscRadius(const CameraFrame& camera, double verticalReach) {
    // The frustum's side planes from the rows of the camera-relative view-projection M (Gribb & Hartmann
    // 2001): inside is n . x + d >= 0 for (n, d) = row3 +- row0 (left, right), row3 +- row1 (bottom, top).
    // Over the solid disc |x.xy| <= R at a height z, n . x + d peaks at |n.xy| R + n.z z + d, so the disc
    // lies outside the plane while that is < 0. The sea there is at z in [-h - a - drop, -h + a] below the
    // camera (h its height above mean sea level, a the reach, drop = r^2 / 2R >= 0 only lowers it): for a
    // plane with n.z > 0 the worst point is the highest, z = -h + a; a plane with n.z <= 0 cannot exclude
    // the point under the camera and is skipped (safe: it only keeps rings).
    const glm::dmat4 m(camera.viewProj);
    const double z = -camera.origin.z + std::max(verticalReach, 0.0);
    double best = 0.0;
    for (int axis = 0; axis < 2; ++axis)
        for (double sign : {1.0, -1.0}) {
            const glm::dvec4 p(m[0][3] + sign * m[0][axis], m[1][3] + sign * m[1][axis],
                               m[2][3] + sign * m[2][axis], m[3][3] + sign * m[3][axis]);
            const double horizontal = std::hypot(p.x, p.y);
            const double atCentre = p.z * z + p.w;
            if (!(p.z > 0.0) || !(atCentre < 0.0) || !(horizontal > 0.0))
                continue;
            best = std::max(best, -atCentre / horizontal);
        }
    // Float: the GPU's vertices are float, rounded by ~6e-8 of their radius.
    return std::isfinite(best) ? best * (1.0 - 1e-6) : 0.0;
}

glm::dvec2 sectorPosition(double u, double r, const ViewSector& sector, double guardDistance) {
    // Same formula as ocean.vert: a horizontal displacement of up to g turns a point at radius r by at most
    // asin(g / r) (by anything when r <= g), so the half-width grows by that much near the camera.
    const double half = r <= guardDistance
                            ? std::numbers::pi
                            : std::min(std::numbers::pi, sector.halfWidth + std::asin(guardDistance / r));
    const double theta = sector.center + (2.0 * u - 1.0) * half;
    return {r * std::cos(theta), r * std::sin(theta)};
}

double RadialGrid::radius(int ring) const {
    const double i = static_cast<double>(ring);
    return mA0 + mA1 * (i * i) * (i * i);
}

} // namespace pacifica::ocean
