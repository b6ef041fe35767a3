// Unit tests for engine/Time.h: the fixed-step clock (step counting, the catch-up cap, drift-free time,
// jumpTo, alpha, argument checks) and wrapPhase.
#include "engine/Time.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

using pacifica::FixedStepClock;
using pacifica::wrapPhase;

TEST(FixedStepClock, TimeIsTickTimesStepWithNoDriftAfter1e9Steps) {
    const double step = 1.0 / 60.0;
    FixedStepClock clock(step);
    double naive = 0.0; // what a clock that sums its steps would report
    const std::int64_t n = 1'000'000'000;
    std::int64_t taken = 0;
    for (std::int64_t i = 0; i < n; ++i) {
        taken += clock.advance(step); // accumulator goes step -> 0 each time: exactly one step per call
        naive += step;
    }
    ASSERT_EQ(taken, n);
    ASSERT_EQ(clock.tick(), n);
    // Exactly the correctly rounded product: no error accumulates however long the clock runs.
    EXPECT_EQ(clock.time(), 1e9 * (1.0 / 60.0));
    // Evidence that the alternative drifts: the running sum is off by 0.41 s with g++ 12 (each of
    // the 1e9 additions rounds to the double spacing near the total, 2^-29..2^-28 s, with a consistent
    // bias inside each binade). The bound 1e-6 s is many orders below the observed drift.
    const double naiveError = std::fabs(naive - 1e9 / 60.0);
    EXPECT_GT(naiveError, 1e-6) << "naive sum " << naive;
    // And the product itself is within one rounding of the exact 1e9/60 = 16666666.666... s.
    EXPECT_LE(std::fabs(clock.time() - 1e9 / 60.0), 4e-9);
}

TEST(FixedStepClock, AdvanceCountsWholeStepsAndKeepsRemainder) {
    FixedStepClock clock(0.25); // exactly representable, so the expected values are exact
    EXPECT_EQ(clock.step(), 0.25);
    EXPECT_EQ(clock.advance(0.1), 0);
    EXPECT_EQ(clock.tick(), 0);
    EXPECT_NEAR(clock.alpha(), 0.4, 1e-12);
    EXPECT_EQ(clock.advance(0.2), 1); // 0.3 accumulated
    EXPECT_EQ(clock.tick(), 1);
    EXPECT_NEAR(clock.alpha(), 0.2, 1e-12);
    EXPECT_EQ(clock.advance(0.7), 3); // 0.05 + 0.7 = 0.75: three steps, nothing left over
    EXPECT_EQ(clock.tick(), 4);
    EXPECT_NEAR(clock.alpha(), 0.0, 1e-12);
}

TEST(FixedStepClock, AdvanceCapsStepsAndDropsExcess) {
    FixedStepClock clock(0.5);
    EXPECT_EQ(clock.maxStepsPerAdvance(), FixedStepClock::DEFAULT_MAX_STEPS_PER_ADVANCE);
    EXPECT_EQ(clock.maxStepsPerAdvance(), 8);
    // A 100.25 s hitch would need 200 steps: only 8 are taken, the rest dropped, the fraction kept.
    EXPECT_EQ(clock.advance(100.25), 8);
    EXPECT_EQ(clock.tick(), 8);
    EXPECT_EQ(clock.time(), 4.0);
    EXPECT_DOUBLE_EQ(clock.alpha(), 0.5);
    EXPECT_DOUBLE_EQ(clock.droppedSeconds(), 96.0);
    // The next normal frame is not a catch-up frame.
    EXPECT_EQ(clock.advance(0.25), 1);
    EXPECT_EQ(clock.alpha(), 0.0);

    clock.setMaxStepsPerAdvance(2);
    EXPECT_EQ(clock.advance(10.0), 2);
    EXPECT_THROW(clock.setMaxStepsPerAdvance(0), std::invalid_argument);
}

TEST(FixedStepClock, AlphaStaysInUnitInterval) {
    FixedStepClock clock(1.0 / 60.0);
    double dt = 0.001;
    for (int i = 0; i < 100000; ++i) {
        clock.advance(dt);
        const double a = clock.alpha();
        ASSERT_GE(a, 0.0);
        ASSERT_LT(a, 1.0);
        dt = std::fmod(dt * 1.618 + 0.0007, 0.05); // irregular frame times
    }
}

TEST(FixedStepClock, BadInputsThrowAndNameTheValue) {
    FixedStepClock clock(0.01);
    try {
        clock.advance(-0.5);
        FAIL() << "negative dt accepted";
    } catch (const std::invalid_argument& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind("FixedStepClock::advance():", 0), 0u) << msg;
        EXPECT_NE(msg.find("-0.5"), std::string::npos) << msg;
    }
    EXPECT_THROW(clock.advance(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(clock.advance(std::numeric_limits<double>::infinity()), std::invalid_argument);
    EXPECT_EQ(clock.tick(), 0); // rejected calls change nothing
    EXPECT_EQ(clock.advance(0.0), 0);

    EXPECT_THROW(FixedStepClock(0.0), std::invalid_argument);
    EXPECT_THROW(FixedStepClock(-1.0), std::invalid_argument);
    EXPECT_THROW(FixedStepClock(std::numeric_limits<double>::infinity()), std::invalid_argument);
    EXPECT_THROW(FixedStepClock(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(clock.jumpTo(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
    EXPECT_THROW(clock.jumpTo(1e300), std::invalid_argument);
}

TEST(FixedStepClock, JumpToSetsNearestTick) {
    FixedStepClock clock(1.0 / 60.0);
    clock.advance(0.01); // leftover accumulator is cleared by the jump
    clock.jumpTo(1e6);
    EXPECT_EQ(clock.tick(), 60'000'000);
    EXPECT_NEAR(clock.time(), 1e6, 1e-9);
    EXPECT_EQ(clock.alpha(), 0.0);
    clock.jumpTo(10.0 + 0.4 / 60.0); // rounds to the nearest tick
    EXPECT_EQ(clock.tick(), 600);
    clock.jumpTo(10.0 + 0.6 / 60.0);
    EXPECT_EQ(clock.tick(), 601);
}

TEST(WrapPhase, ExactValuesAndNegativeInputs) {
    EXPECT_EQ(wrapPhase(-0.25, 1.0), 0.75);
    EXPECT_EQ(wrapPhase(0.25, 1.0), 0.25);
    EXPECT_EQ(wrapPhase(1.0, 1.0), 0.0);
    EXPECT_EQ(wrapPhase(-3.0, 1.0), 0.0);
    EXPECT_FALSE(std::signbit(wrapPhase(-2.0, 1.0))); // +0, not -0
    EXPECT_EQ(wrapPhase(-7.5, 2.0), 0.5);
    // A tiny negative x whose wrapped value rounds up to the period itself comes back as 0 (same phase).
    const double r = wrapPhase(-1e-30, 1.0);
    EXPECT_GE(r, 0.0);
    EXPECT_LT(r, 1.0);
    EXPECT_THROW(wrapPhase(1.0, 0.0), std::invalid_argument);
    EXPECT_THROW(wrapPhase(std::numeric_limits<double>::infinity(), 1.0), std::invalid_argument);
}

TEST(WrapPhase, LargePhaseAgainstExtendedPrecisionReference) {
    const double twoPi = 2.0 * 3.14159265358979323846;
    const double x = 1e6 + 0.5;
    const double wrapped = wrapPhase(x, twoPi);
    // Reference with the true 2*pi in long double (64-bit mantissa on x86): x mod 2pi. The result differs
    // from the double computation by k * (2pi - double(2pi)) ~ 159155 * 2.4e-16 ~ 4e-11, well inside 1e-9.
    const long double twoPiL = 6.283185307179586476925286766559L;
    const long double k = std::floor(static_cast<long double>(x) / twoPiL);
    const long double expected = static_cast<long double>(x) - k * twoPiL;
    EXPECT_NEAR(wrapped, static_cast<double>(expected), 1e-9);
    EXPECT_GE(wrapped, 0.0);
    EXPECT_LT(wrapped, twoPi);
    // Negative phases land in the same place modulo the period.
    EXPECT_NEAR(wrapPhase(-x, twoPi), twoPi - wrapped, 1e-9);
    // Why wrap in double: float spacing at 1e6 is 0.0625 rad, so an unwrapped phase 1e6 + 0.53 handed to
    // the GPU as float is off by 0.03 rad, while the wrapped one keeps ~1e-7 rad.
    const double x2 = 1e6 + 0.53;
    const double floatError =
        std::fabs(std::fmod(static_cast<double>(static_cast<float>(x2)), twoPi) - wrapPhase(x2, twoPi));
    EXPECT_GT(floatError, 0.02);
    EXPECT_LT(std::fabs(static_cast<double>(static_cast<float>(wrapPhase(x2, twoPi))) - wrapPhase(x2, twoPi)),
              1e-6);
}
