// Time: the fixed-step simulation clock and phase wrapping. The simulation advances in whole ticks of a
// fixed step (Fiedler, "Fix Your Timestep!", 2004), and simulation time is always derived as tick * step so
// it is reproducible and never drifts, however long the game runs. wrapPhase() brings large phase values
// into [0, period) in double precision before they are handed to the GPU as floats.
// Header-only, plain C++20.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace pacifica {

/// Turns variable real frame times into a whole number of fixed simulation steps.
///
/// Usage, once per frame:
/// @code
/// FixedStepClock clock(1.0 / 60.0);
/// const int steps = clock.advance(realDtSeconds);
/// for (int i = 0; i < steps; ++i) simulate(clock.step());
/// render(clock.time(), clock.alpha()); // alpha: how far we are into the next step, for interpolation
/// @endcode
///
/// time() is computed as tick() * step() — one multiplication, one rounding — never by adding step to a
/// running total. Summing 1/60 a billion times drifts by 0.41 s (each addition rounds
/// to the spacing of doubles near the running total, ~4e-9 s at 1.7e7 s, and the errors do not cancel;
/// tests/unit/test_time.cpp measures it), whereas tick * step is within half an ulp of the exact product.
class FixedStepClock {
public:
    /// Default cap on the steps taken by one advance().
    static constexpr int DEFAULT_MAX_STEPS_PER_ADVANCE = 8;

    /// stepSeconds must be finite and > 0; otherwise throws std::invalid_argument naming the value.
    explicit FixedStepClock(double stepSeconds) : mStep(stepSeconds) {
        if (!std::isfinite(stepSeconds) || stepSeconds <= 0.0)
            throw std::invalid_argument(
                "FixedStepClock::FixedStepClock(): step must be finite and > 0, got " +
                std::to_string(stepSeconds));
    }

    /// Adds realDtSeconds of real time and takes as many whole steps as fit, at most maxStepsPerAdvance().
    /// When more would fit, the excess whole steps are dropped (counted in droppedSeconds()) so a slow frame
    /// cannot trigger ever longer catch-up frames (the "spiral of death"); the fraction of a step left over
    /// is kept for alpha(). Returns the number of steps taken. A negative, NaN or infinite realDtSeconds
    /// throws std::invalid_argument naming the value, and changes nothing.
    int advance(double realDtSeconds) {
        if (!std::isfinite(realDtSeconds) || realDtSeconds < 0.0)
            throw std::invalid_argument("FixedStepClock::advance(): real dt must be finite and >= 0, got " +
                                        std::to_string(realDtSeconds));
        mAccumulator += realDtSeconds;
        int steps = 0;
        while (mAccumulator >= mStep && steps < mMaxStepsPerAdvance) {
            mAccumulator -= mStep; // real-time bookkeeping only: time() does not depend on it
            ++steps;
        }
        if (mAccumulator >= mStep) {
            const double kept = std::fmod(mAccumulator, mStep); // exact, in [0, step)
            mDroppedSeconds += mAccumulator - kept;
            mAccumulator = kept;
        }
        mTick += steps;
        return steps;
    }

    /// Number of steps taken since construction (or set by jumpTo()).
    std::int64_t tick() const noexcept { return mTick; }

    /// Simulation time in seconds: tick() * step(), by one multiplication (no drift, see class comment).
    double time() const noexcept { return static_cast<double>(mTick) * mStep; }

    /// The fixed step in seconds.
    double step() const noexcept { return mStep; }

    /// Fraction of a step accumulated but not yet taken, in [0, 1): blend factor between the previous and
    /// the current simulation state for rendering.
    double alpha() const noexcept {
        const double a = mAccumulator / mStep;
        return a < 1.0 ? a : std::nextafter(1.0, 0.0); // guards the rounding of the division
    }

    /// Sets the clock to the step nearest to `seconds` (tick = llround(seconds / step)) and clears the
    /// accumulator. Throws std::invalid_argument if seconds is not finite or the tick would not fit 64 bits.
    void jumpTo(double seconds) {
        const double ticks = seconds / mStep;
        if (!std::isfinite(ticks) || std::fabs(ticks) >= 9.0e18)
            throw std::invalid_argument("FixedStepClock::jumpTo(): time out of range, got " +
                                        std::to_string(seconds));
        mTick = std::llround(ticks);
        mAccumulator = 0.0;
    }

    /// Cap on the steps one advance() may take; at least 1.
    int maxStepsPerAdvance() const noexcept { return mMaxStepsPerAdvance; }
    /// Sets the cap; throws std::invalid_argument if maxSteps < 1.
    void setMaxStepsPerAdvance(int maxSteps) {
        if (maxSteps < 1)
            throw std::invalid_argument("FixedStepClock::setMaxStepsPerAdvance(): must be >= 1, got " +
                                        std::to_string(maxSteps));
        mMaxStepsPerAdvance = maxSteps;
    }

    /// Total real time discarded by the cap, in seconds (for diagnostics: non-zero means frames were slow).
    double droppedSeconds() const noexcept { return mDroppedSeconds; }

private:
    double mStep;
    double mAccumulator = 0.0;
    double mDroppedSeconds = 0.0;
    std::int64_t mTick = 0;
    int mMaxStepsPerAdvance = DEFAULT_MAX_STEPS_PER_ADVANCE;
};

/// x modulo period, in [0, period), computed in double. Used to wrap each wave's phase (omega * t + phi0)
/// before it is converted to float for the GPU, where a phase of 1e6 rad would keep only ~0.06 rad of
/// precision. std::fmod is exact (the result is representable; C11 F.10.7.1); for negative x one addition
/// of period follows, rounded once (exact when the result has no more significant bits than period, e.g.
/// wrapPhase(-0.25, 1) == 0.75). If that addition rounds up to period itself, 0 is returned (same phase).
/// Throws std::invalid_argument if x is not finite or period is not finite and > 0.
inline double wrapPhase(double x, double period) {
    if (!std::isfinite(period) || period <= 0.0)
        throw std::invalid_argument("wrapPhase(): period must be finite and > 0, got " +
                                    std::to_string(period));
    if (!std::isfinite(x))
        throw std::invalid_argument("wrapPhase(): x must be finite, got " + std::to_string(x));
    double r = std::fmod(x, period); // exact, sign of x, |r| < period
    if (r < 0.0)
        r += period;
    return r < period ? r + 0.0 : 0.0; // + 0.0 turns fmod's -0.0 (x = -2 * period) into +0.0
}

} // namespace pacifica
