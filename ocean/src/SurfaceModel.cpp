// SurfaceModel: the shared Eulerian height query (inverse of the horizontal displacement).
#include "ocean/SurfaceModel.h"

#include "ocean/OceanConstants.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pacifica::ocean {

const char* toString(SurfaceKind kind) {
    switch (kind) {
    case SurfaceKind::Octaves:
        return "octaves";
    case SurfaceKind::Gerstner:
        return "gerstner";
    case SurfaceKind::Fft:
        return "fft";
    }
    return "?";
}

int64_t foamStepIndex(double t) {
    if (!std::isfinite(t))
        throw std::invalid_argument("foamStepIndex(): time must be finite");
    return static_cast<int64_t>(std::floor(t / FOAM_MEMORY_STEP));
}

double foamStepTime(int64_t j) {
    return static_cast<double>(j) * FOAM_MEMORY_STEP;
}

glm::dvec3 aperiodicMixTerm(double tile, int set, int j) {
    const double twoPi = 2.0 * std::numbers::pi;
    const double k = twoPi / (FFT_MIX_WAVELENGTHS[j] * tile);
    const double a = FFT_MIX_DIRECTIONS_DEG[j] * std::numbers::pi / 180.0;
    // Phases from the golden ratio's fractional parts, a different set per tiled field.
    const double phase = twoPi * std::fmod(0.5 + 0.6180339887498949 * (j + FFT_MIX_TERMS * set), 1.0);
    return {k * std::sin(a), k * std::cos(a), phase};
}

glm::dvec2 aperiodicMixWeights(double tile, int set, const glm::dvec2& xy) {
    double theta = 0.0;
    for (int j = 0; j < FFT_MIX_TERMS; ++j) {
        const glm::dvec3 m = aperiodicMixTerm(tile, set, j);
        theta += std::sin(m.x * xy.x + m.y * xy.y + m.z); // the argument's rounding: ~1e-16 of it
    }
    theta *= FFT_MIX_AMPLITUDE;
    return {std::cos(theta), std::sin(theta)};
}

glm::dvec2 SurfaceModel::lagrangianPointAt(const glm::dvec2& xy, double t, glm::dvec3* displacement) const {
    // Solve F(x0) = x0 + d_xy(x0) - xy = 0 for the grid point whose image lies above xy. Newton's method with
    // the model's analytic Jacobian I + grad d_xy (displacementAndGradient) or, without one, central
    // differences (h = 1 mm), and step halving: the plain fixed point x0 <- xy - d_xy(x0) contracts only by
    // |grad d_xy|, which tends to 1 at the steepness limit (Gerstner Q k A -> 1, sharp crests), where it
    // would need thousands of iterations. Stops at |F| < 1e-9 m.
    if (kind() == SurfaceKind::Octaves) { // no horizontal displacement
        if (displacement)
            *displacement = displacementAt(xy, t);
        return xy;
    }
    glm::dvec3 last(0.0); // displacementAt() of the last residual() taken
    glm::dmat2 lastGrad(0.0);
    const bool analytic = displacementAndGradient(xy, t, last, lastGrad); // x0 = xy's evaluation when true
    auto residual = [&](const glm::dvec2& x0) {
        if (analytic)
            displacementAndGradient(x0, t, last, lastGrad);
        else
            last = displacementAt(x0, t);
        return x0 + glm::dvec2(last.x, last.y) - xy;
    };
    glm::dvec2 x0 = xy;
    glm::dvec2 f = analytic ? glm::dvec2(last.x, last.y) : residual(x0);
    glm::dvec3 atX0 = last;
    glm::dmat2 gradX0 = lastGrad;
    for (int i = 0; i < 32 && glm::length(f) > 1e-9; ++i) {
        glm::dvec2 fx, fy; // dF/dx, dF/dy
        if (analytic) {
            fx = glm::dvec2(1.0, 0.0) + gradX0[0];
            fy = glm::dvec2(0.0, 1.0) + gradX0[1];
        } else {
            constexpr double h = 1e-3;
            fx = (residual(x0 + glm::dvec2(h, 0.0)) - residual(x0 - glm::dvec2(h, 0.0))) / (2.0 * h);
            fy = (residual(x0 + glm::dvec2(0.0, h)) - residual(x0 - glm::dvec2(0.0, h))) / (2.0 * h);
        }
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
        atX0 = last;
        gradX0 = lastGrad;
    }
    if (displacement)
        *displacement = atX0;
    return x0;
}

double SurfaceModel::heightAt(const glm::dvec2& xy, double t) const {
    glm::dvec3 d;
    lagrangianPointAt(xy, t, &d);
    return d.z;
}

glm::dvec3 SurfaceModel::velocityAt(const glm::dvec2& xy, double t) const {
    // Central difference in time at the fixed grid point; t +- h is exact enough in double at any t the
    // models take (their phases are wrapped after the sum).
    return (displacementAt(xy, t + VELOCITY_STEP) - displacementAt(xy, t - VELOCITY_STEP)) /
           (2.0 * VELOCITY_STEP);
}

void SurfaceModel::heightsAt(const std::vector<glm::dvec2>& points, double t,
                             std::vector<double>& out) const {
    out.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i)
        out[i] = heightAt(points[i], t);
}

} // namespace pacifica::ocean
