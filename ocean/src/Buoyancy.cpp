// Buoyancy: a hull's points and the plane through the sea's heights there (Buoyancy.h).
#include "ocean/Buoyancy.h"

#include <cmath>
#include <numbers>

namespace pacifica::ocean {

namespace {
constexpr double DEG = std::numbers::pi / 180.0;
constexpr double OFFSETS[3] = {-1.0, 0.0, 1.0};
} // namespace

void hullPoints(const glm::dvec2& centre, double headingDeg, double length, double halfBeam,
                std::span<glm::dvec2, HULL_POINTS> out) {
    const glm::dvec2 ahead(std::sin(headingDeg * DEG), std::cos(headingDeg * DEG)), right(ahead.y, -ahead.x);
    size_t k = 0;
    for (double a : OFFSETS)
        for (double c : OFFSETS)
            out[k++] = centre + a * HULL_ALONG * length * ahead + c * HULL_ACROSS * halfBeam * right;
}

HullPose floatHull(std::span<const double, HULL_POINTS> heights, double length, double halfBeam) {
    // Least squares for h = z + b x + c y over the symmetric grid x in {-X, 0, X}, y in {-Y, 0, Y}: the
    // normal equations are diagonal, z = mean h, b = sum h x / (6 X^2), c = sum h y / (6 Y^2).
    const double along = HULL_ALONG * length, across = HULL_ACROSS * halfBeam;
    double mean = 0.0, b = 0.0, c = 0.0;
    size_t k = 0;
    for (double a : OFFSETS)
        for (double x : OFFSETS) {
            const double h = heights[k++];
            mean += h / HULL_POINTS;
            b += h * a / (6.0 * along);
            c += h * x / (6.0 * across);
        }
    return {mean, std::atan(b) / DEG, -std::atan(c) / DEG};
}

} // namespace pacifica::ocean
