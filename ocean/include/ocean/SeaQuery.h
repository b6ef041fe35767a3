// SeaQuery: the sea's answers for many points at once, at game rates -- the radar altimeter of every
// aircraft, where each shell meets the water, the buoyancy points of every hull. For each point: the
// Eulerian height (ocean + effects), the surface's unit normal, the horizontal displacement of the water now
// above it and the velocity of that water. Exception-free (Status, as Ocean.h), ECS-free, allocation-free
// once made: a query in a frame loop does not touch the heap.
//
//   SeaQuery query;
//   query.init(ocean, {.fields = SeaField::Height | SeaField::Velocity, .threads = 0});   // once
//   each simulation step:
//     query.update(t, effects);                          // the FFT sea: samples its tiles at t (~ms)
//     query.sample(points, samples, SeaField::Height | SeaField::Velocity);
//     query.heights(points, heights);                    // the heights alone
//
// PATHS per model (docs/ACCURACY.md "The sea's CPU queries" gives the error and the cost of each):
//   - octaves: the height map's octaves at the point (no horizontal displacement): exact.
//   - Gerstner: the sum of the waves at the grid point that Newton's method finds under the point: exact.
//   - FFT: FftSampledSea (the tiles inverse-transformed on the CPU at t, interpolated: SeaQueryDesc::
//     fftInterpolation), or the direct sum over every component (fftDirectSum: the reference, ~1 ms a
//     point).
// The effects (explosions, wakes) add the analytic field E(x, t) (EffectTypes.h effectsAt): its height, its
// slopes (tilting the normal) and dE/dt (the vertical velocity, by central difference).
#pragma once

#include "ocean/EffectTypes.h"
#include "ocean/FftSampled.h"
#include "ocean/Jobs.h"
#include "ocean/Ocean.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <span>

namespace pacifica::ocean {

/// What a query answers (a bit mask: SeaField::Height | SeaField::Normal ...).
struct SeaField {
    static constexpr unsigned Height = 1u;       ///< SeaSample::height
    static constexpr unsigned Normal = 2u;       ///< SeaSample::normal
    static constexpr unsigned Displacement = 4u; ///< SeaSample::displacement
    static constexpr unsigned Velocity = 8u;     ///< SeaSample::velocity
    static constexpr unsigned All = 15u;
};

/// The sea at one world point (x, y) at the query's time. Fields not asked for are left as they were.
struct SeaSample {
    double height = 0.0;        ///< metres above mean sea level: the surface above (x, y), effects included
    glm::dvec3 normal{0, 0, 1}; ///< unit normal of the surface there (the effects' slopes included)
    /// Horizontal displacement of the water now above (x, y) from its rest position x0: (x, y) - x0 (0 for
    /// the octave model), metres.
    glm::dvec2 displacement{0.0};
    /// Velocity of that water (the orbital velocity a floating body follows), m/s; the effects add dE/dt to
    /// z.
    glm::dvec3 velocity{0.0};
};

struct SeaQueryDesc {
    /// The fields sample() may be asked for: the FFT sea samples the velocity's transforms only if asked.
    unsigned fields = SeaField::Height | SeaField::Normal;
    /// Threads of the query's own pool (the caller's included): 1 = the calling thread only, 0 = one per
    /// hardware thread. Ignored when `jobs` is set (the host's job system).
    unsigned threads = 1;
    JobSystem jobs;
    /// Points per job: a batch smaller than this runs on the calling thread.
    size_t pointsPerJob = 512;
    /// FFT: the direct sum over every component instead of the sampled tiles (the reference; ~10 ms a point,
    /// and it allocates per point: not for a frame loop).
    bool fftDirectSum = false;
    FftSampledSea::Interpolation fftInterpolation = FftSampledSea::Interpolation::Bicubic;
    /// FFT: transform the tiles again only when the time has moved this many seconds from the last transform;
    /// in between, update() extrapolates them by their time derivative (FftSampledSea::extrapolateTo: 0.08 ms
    /// instead of 6-11 ms, errors in docs/ACCURACY.md). 0: transform at every new time.
    double fftResampleInterval = 0.0;
};

/// Counts since init() (for a host's HUD or log).
struct SeaQueryCounters {
    uint64_t updates = 0;  ///< update() calls that succeeded
    uint64_t points = 0;   ///< points answered
    uint64_t rejected = 0; ///< points refused (not finite)
};

class SeaQuery {
public:
    SeaQuery() noexcept;
    ~SeaQuery();
    SeaQuery(const SeaQuery&) = delete;
    SeaQuery& operator=(const SeaQuery&) = delete;
    SeaQuery(SeaQuery&&) noexcept;
    SeaQuery& operator=(SeaQuery&&) noexcept;

    /// Binds the ocean (its surface is shared, not copied) and allocates everything the queries need (the
    /// FFT's tiles, the pool). Any earlier state is dropped. InvalidArgument names a bad field.
    Status init(const OceanComponent& ocean, const SeaQueryDesc& desc = {}) noexcept;
    /// Moves the queries to time t (finite) with these effects: their spans must stay valid until the next
    /// update() (update(t, {}) lets them go). The FFT sea samples its tiles here, only when t changes.
    Status update(double t, const EffectsView& effects = {}) noexcept;
    /// Samples every point (`samples` as long as `points`), the fields in `fields` (a subset of the desc's).
    /// A point that is not finite gets NaN in every asked field and is counted: the Status is then
    /// InvalidArgument saying how many and the first index, and every other point is answered.
    Status sample(std::span<const glm::dvec2> points, std::span<SeaSample> samples,
                  unsigned fields = SeaField::Height) noexcept;
    /// The heights alone (as sample() with SeaField::Height).
    Status heights(std::span<const glm::dvec2> points, std::span<double> heights) noexcept;

    double time() const noexcept;
    const SeaQueryCounters& counters() const noexcept;

    struct Impl; ///< implementation detail (SeaQuery.cpp)

private:
    std::unique_ptr<Impl> mImpl;
};

} // namespace pacifica::ocean
