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
// is the knob (docs/ACCURACY.md "The sea's CPU queries"): bilinear, or Keys' cubic convolution (the
// Catmull-Rom spline; R. Keys, "Cubic convolution interpolation for digital image processing", IEEE Trans.
// ASSP 29(6), 1981), whose error falls with the fourth power of the grid spacing over the wavelength.
#pragma once

#include "ocean/FftOcean.h"
#include "ocean/Jobs.h"

#include <glm/glm.hpp>

#include <memory>
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
    /// Not sampled yet (resample() before any query): allocates every buffer now, once. `velocity`: sample
    /// the time derivative too (velocityAt; two more transforms per tile).
    FftSampledSea(const FftCascades& sea, Interpolation interpolation, bool velocity);
    ~FftSampledSea();
    FftSampledSea(FftSampledSea&&) noexcept;
    FftSampledSea& operator=(FftSampledSea&&) = delete;

    /// Samples every tile at time t (finite; std::invalid_argument otherwise), one job per tile on `jobs`,
    /// into the buffers it has: allocates nothing.
    void resample(double t, const JobSystem& jobs = {});

    /// The field at time t (finite) from the last sampled one by its time derivative: values + (t -
    /// sampledTime()) velocity per lattice point, one job per tile (0.08 ms for the default sea, against a
    /// resample's 11 ms with the derivative; docs/ACCURACY.md). Over dt the error grows as a dt^2 / 2 (a =
    /// w^2 A, the waves' vertical acceleration): RMS 0.3 mm after 1/60 s, 9 mm (max 33 mm) after 0.1 s for
    /// the default sea. Needs hasVelocity() (std::logic_error).
    void extrapolateTo(double t, const JobSystem& jobs = {});

    /// The time the queries answer for; sampledTime(): the one the tiles were last transformed at.
    double time() const { return mTime; }
    double sampledTime() const { return mSampledTime; }
    bool sampled() const { return mSampled; }
    bool hasVelocity() const { return mVelocity; }
    Interpolation interpolation() const { return mInterpolation; }
    /// (dx, dy, h) at grid point xy, as FftCascades::displacementAt(xy, time()).
    glm::dvec3 displacementAt(const glm::dvec2& xy) const;
    /// The grid point whose image lies above world point xy (as SurfaceModel::lagrangianPointAt);
    /// `displacement`, if given, receives displacementAt() there.
    glm::dvec2 lagrangianPointAt(const glm::dvec2& xy, glm::dvec3* displacement = nullptr) const;
    /// The Eulerian height above xy, as FftCascades::heightAt(xy, time()).
    double heightAt(const glm::dvec2& xy) const;
    /// Unit normal of the displaced surface at the image of grid point xy, as FftCascades::normalAt (the
    /// interpolant's own slopes).
    glm::dvec3 normalAt(const glm::dvec2& xy) const;
    /// d/dt (dx, dy, h) at grid point xy (SurfaceModel::velocityAt), from the sampled time derivative of
    /// every component: d/dt htilde = i w (h0 e^{i w t} - conj(h0(-k)) e^{-i w t}). std::logic_error
    /// without hasVelocity().
    glm::dvec3 velocityAt(const glm::dvec2& xy) const;
    /// heightAt of every point; `heights` must be as long as `points` (std::invalid_argument otherwise).
    void heightsAt(std::span<const glm::dvec2> points, std::span<double> heights) const;

private:
    struct Tile; // one tile's lattice values and its transform's buffers (FftSampled.cpp)
    static void sampleTile(const FftOcean& sea, double t, Tile& tile);
    /// The tile's interpolant of `values` at xy and, when ddx is given, its x and y derivatives (per metre).
    glm::dvec3 sample(const Tile& tile, const std::vector<glm::vec3>& values, const glm::dvec2& xy,
                      glm::dvec3* ddx, glm::dvec3* ddy) const;
    glm::dvec3 displacementAndSlopes(const glm::dvec2& xy, glm::dvec3* ddx, glm::dvec3* ddy) const;
    void requireSampled(const char* what) const;

    const FftCascades& mSea;
    double mTime = 0.0, mSampledTime = 0.0;
    bool mSampled = false;
    bool mVelocity = false;
    Interpolation mInterpolation = Interpolation::Bicubic;
    std::vector<const FftOcean*> mSources;     // draws A of every cascade, then draws B
    std::vector<std::unique_ptr<Tile>> mTiles; // the same order
    size_t mCascades = 0;
};

} // namespace pacifica::ocean
