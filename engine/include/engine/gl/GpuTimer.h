// GpuTimer: measures GPU time of a span of GL commands without stalling the pipeline — a ring of
// GL_TIME_ELAPSED queries read back a few frames later. On software rasterisers (llvmpipe) timer queries
// return wrong values (docs/PLATFORM.md), so there it times with std::chrono::steady_clock around
// glFinish instead. Every figure must be reported with clockName().
#pragma once

#include "engine/gl/GlContext.h"
#include "engine/gl/GlObjects.h"

#include <chrono>
#include <optional>
#include <vector>

namespace pacifica::gl {

class GpuTimer {
public:
    enum class Clock { TimerQuery, WallAroundFinish };

    /// ringSize: how many spans can be in flight before begin() has to wait for the oldest result.
    explicit GpuTimer(const ContextInfo& info, int ringSize = 4);
    /// Forces a clock (tests; or timer queries known broken on a driver).
    GpuTimer(Clock clock, int ringSize = 4);

    void begin();
    void end();
    /// The newest finished measurement in milliseconds, if any (never blocks in TimerQuery mode).
    std::optional<double> poll();
    /// Waits for every span still in flight and collects it (call once at the end of a run).
    void drain();
    /// Every measurement collected so far (ms), in order.
    const std::vector<double>& samples() const { return mSamples; }
    Clock clock() const { return mClock; }
    const char* clockName() const;

private:
    void collect(bool wait);
    Clock mClock;
    std::vector<Query> mQueries;
    std::vector<bool> mPending;
    int mNext = 0;
    bool mOpen = false;
    std::chrono::steady_clock::time_point mStart{};
    std::vector<double> mSamples;
    std::optional<double> mLatest;
};

} // namespace pacifica::gl
