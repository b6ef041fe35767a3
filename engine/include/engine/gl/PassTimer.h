// PassTimer: where a frame's GPU time goes, pass by pass, without stalling the pipeline. A frame is a
// sequence of marks; the time between one mark and the next is added to the pass the later mark names, so
// a frame of sky, sea and effects costs four timestamps whatever the number of passes. On hardware the
// marks are GL_TIMESTAMP queries (glQueryCounter: allowed inside a GpuTimer's GL_TIME_ELAPSED span, so the
// two nest), read back a few frames later from a ring; on software rasterisers (llvmpipe), whose timer
// queries are wrong (docs/PLATFORM.md), each mark is steady_clock after glFinish. Every figure must be
// reported with clockName().
#pragma once

#include "engine/gl/GpuTimer.h"

#include <chrono>
#include <optional>
#include <vector>

namespace pacifica::gl {

class PassTimer {
public:
    /// passCount: the number of pass indices mark() accepts; ringFrames: frames in flight before
    /// beginFrame() has to wait for the oldest one's timestamps.
    PassTimer(GpuTimer::Clock clock, int passCount, int ringFrames = 4);

    void beginFrame();
    /// Ends the span since the previous mark (or beginFrame) and adds it to `pass`; a pass marked twice in
    /// a frame (two oceans) sums its spans.
    void mark(int pass);
    void endFrame();
    /// Milliseconds per pass of the newest frame finished since the last call, if any (TimerQuery: never
    /// blocks, lags the frames still in flight; wall clock: the frame just ended).
    std::optional<std::vector<double>> poll();
    /// Waits for every frame still in flight (call once at the end of a run); poll() then has the last.
    void drain();

    GpuTimer::Clock clock() const { return mClock; }
    const char* clockName() const;
    int passCount() const { return mPassCount; }

private:
    struct Slot {
        std::vector<Query> queries; // timestamps, grown on demand
        std::vector<int> passOf;    // the pass each timestamp ends (-1: the frame's start)
        int used = 0;
        bool pending = false;
    };
    void collect(Slot& slot);
    bool available(const Slot& slot) const;

    GpuTimer::Clock mClock;
    int mPassCount;
    std::vector<Slot> mRing;
    int mNext = 0;
    bool mOpen = false;
    std::chrono::steady_clock::time_point mLast{};
    std::vector<double> mWallMs;
    std::optional<std::vector<double>> mLatest;
};

} // namespace pacifica::gl
