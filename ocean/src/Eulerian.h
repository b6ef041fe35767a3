// Eulerian (internal): the height of a displaced surface above a world point -- the grid point whose image
// lies above it, found by Newton's method -- for any displacement function (SurfaceModel::heightAt, the
// sampled FFT sea).
#pragma once

#include <glm/glm.hpp>

namespace pacifica::ocean {

/// The height above xy of the surface P(x0) = x0 + displacementAt(x0) (displacementAt returns (dx, dy, h)).
template <class Displacement>
double eulerianHeight(const Displacement& displacementAt, const glm::dvec2& xy) {
    // Solve F(x0) = x0 + d_xy(x0) - xy = 0 for the grid point whose image lies above xy. Newton's method with
    // a central-difference Jacobian (h = 1 mm) and step halving: the plain fixed point x0 <- xy - d_xy(x0)
    // contracts only by |grad d_xy|, which tends to 1 at the steepness limit (Gerstner Q k A -> 1, sharp
    // crests), where it would need thousands of iterations. Stops at |F| < 1e-9 m.
    auto residual = [&](const glm::dvec2& x0) {
        const glm::dvec3 d = displacementAt(x0);
        return x0 + glm::dvec2(d.x, d.y) - xy;
    };
    glm::dvec2 x0 = xy;
    glm::dvec2 f = residual(x0);
    for (int i = 0; i < 32 && glm::length(f) > 1e-9; ++i) {
        constexpr double h = 1e-3;
        const glm::dvec2 fx =
            (residual(x0 + glm::dvec2(h, 0.0)) - residual(x0 - glm::dvec2(h, 0.0))) / (2.0 * h);
        const glm::dvec2 fy =
            (residual(x0 + glm::dvec2(0.0, h)) - residual(x0 - glm::dvec2(0.0, h))) / (2.0 * h);
        const double det = fx.x * fy.y - fy.x * fx.y;
        glm::dvec2 step = -f; // fixed-point step where the Jacobian is singular (a fold)
        if (std::abs(det) > 1e-12)
            step = -glm::dvec2(fy.y * f.x - fy.x * f.y, -fx.y * f.x + fx.x * f.y) / det;
        double scale = 1.0;
        glm::dvec2 next = x0 + step, fn = residual(next);
        while (glm::length(fn) >= glm::length(f) && scale > 1e-4) { // step halving keeps |F| decreasing
            scale *= 0.5;
            next = x0 + step * scale;
            fn = residual(next);
        }
        x0 = next;
        f = fn;
    }
    return displacementAt(x0).z;
}

} // namespace pacifica::ocean
