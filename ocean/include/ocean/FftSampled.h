// FftSampled: the FFT sea at one time on each tile's own N x N grid, inverse-transformed on the CPU, for
// queries at game rates -- the radar altimeter of every aircraft, where each shell meets the water, the
// buoyancy points of every hull. The direct sum over every spectral component (FftCascades::displacementAt,
// O(N^2) per point) stays the reference; this evaluates the same components once per time on the lattice
// (O(N^2 log N) per tile) and interpolates between its points, so a query costs a few grid reads.
//
//   FftSampledSea sampled(*cascades, t);            // ~ms per tile, once per simulation step
//   double h = sampled.heightAt({x, y});            // Eulerian height, as SurfaceModel::heightAt
//   sampled.heightsAt(points, heights);             // a span of points at once
//
// The transform is KissFFT's (Debian's libkissfft-dev, BSD-3-Clause, in single precision), not FFTW: FFTW is
// GPL-2, which a game embedding this library could not ship without a commercial licence. The interpolation
// is the knob (docs/ACCURACY.md "The FFT sea's CPU queries"): bilinear, or Keys' cubic convolution (the
// Catmull-Rom spline; R. Keys, "Cubic convolution interpolation for digital image processing", IEEE Trans.
// ASSP 29(6), 1981), whose error falls with the fourth power of the grid spacing over the wavelength.
#pragma once

#include "ocean/FftOcean.h"

#include <glm/glm.hpp>

#include <span>
#include <vector>

namespace pacifica::ocean {

class FftSampledSea {
public:
    enum class Interpolation { Bilinear, Bicubic };

    /// Samples every tile of `sea` (both draws of every cascade) at time t (finite; std::invalid_argument
    /// otherwise) on `threads` threads (0: one per hardware thread; 1: the calling thread only). The tiles
    /// are independent, so the result does not depend on the thread count. Keeps a reference to `sea`, which
    /// must outlive it.
    FftSampledSea(const FftCascades& sea, double t, Interpolation interpolation = Interpolation::Bicubic,
                  unsigned threads = 0);

    double time() const { return mTime; }
    Interpolation interpolation() const { return mInterpolation; }
    /// (dx, dy, h) at grid point xy, as FftCascades::displacementAt(xy, time()).
    glm::dvec3 displacementAt(const glm::dvec2& xy) const;
    /// The Eulerian height above xy, as FftCascades::heightAt(xy, time()).
    double heightAt(const glm::dvec2& xy) const;
    /// heightAt of every point; `heights` must be as long as `points` (std::invalid_argument otherwise).
    void heightsAt(std::span<const glm::dvec2> points, std::span<double> heights) const;

private:
    /// One tile's (lambda Dx, lambda Dy, h) at x = (a, b) L / N, row b, column a.
    struct Tile {
        int n = 0;
        double size = 0.0;
        std::vector<glm::vec3> values;
    };
    static Tile sampleTile(const FftOcean& tile, double t);
    /// The tile's interpolant at xy and, when ddx is given, its x and y derivatives (per metre) into ddx,
    /// ddy.
    glm::dvec3 sample(const Tile& tile, const glm::dvec2& xy, glm::dvec3* ddx, glm::dvec3* ddy) const;
    glm::dvec3 displacementAndSlopes(const glm::dvec2& xy, glm::dvec3* ddx, glm::dvec3* ddy) const;

    const FftCascades& mSea;
    double mTime = 0.0;
    Interpolation mInterpolation = Interpolation::Bicubic;
    std::vector<Tile> mFirst, mSecond; // draws A and B of every cascade
};

} // namespace pacifica::ocean
