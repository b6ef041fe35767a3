// SurfaceModel: the shared Eulerian height query (inverse of the horizontal displacement).
#include "ocean/SurfaceModel.h"

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

double SurfaceModel::heightAt(const glm::dvec2& xy, double t) const {
    // Fixed point x0 <- xy - d_xy(x0): a contraction while |grad d_xy| < 1, i.e. while the surface does not
    // fold (the Gerstner steepness limit and FFT choppiness keep it so). 8 iterations reach ~1e-6 m for
    // steepness 0.5; stop early when the step is below 1e-9 m.
    glm::dvec2 x0 = xy;
    for (int i = 0; i < 16; ++i) {
        const glm::dvec3 d = displacementAt(x0, t);
        const glm::dvec2 next = xy - glm::dvec2(d.x, d.y);
        const double step = glm::length(next - x0);
        x0 = next;
        if (step < 1e-9)
            break;
    }
    return displacementAt(x0, t).z;
}

void SurfaceModel::heightsAt(const std::vector<glm::dvec2>& points, double t,
                             std::vector<double>& out) const {
    out.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i)
        out[i] = heightAt(points[i], t);
}

} // namespace pacifica::ocean
