// PassTimer implementation: GL_TIMESTAMP queries in a ring of frames, or steady_clock after glFinish.
#include "engine/gl/PassTimer.h"

#include <epoxy/gl.h>

#include <stdexcept>
#include <string>

namespace pacifica::gl {

PassTimer::PassTimer(GpuTimer::Clock clock, int passCount, int ringFrames)
    : mClock(clock), mPassCount(passCount) {
    if (passCount < 1)
        throw std::logic_error("PassTimer::PassTimer(): passCount must be >= 1, got " +
                               std::to_string(passCount));
    if (ringFrames < 1)
        throw std::logic_error("PassTimer::PassTimer(): ringFrames must be >= 1, got " +
                               std::to_string(ringFrames));
    mRing.resize(mClock == GpuTimer::Clock::TimerQuery ? static_cast<size_t>(ringFrames) : 0);
}

const char* PassTimer::clockName() const {
    return mClock == GpuTimer::Clock::TimerQuery ? "GL_TIMESTAMP queries between passes"
                                                 : "wall clock (steady_clock) after glFinish between passes";
}

void PassTimer::beginFrame() {
    if (mOpen)
        throw std::logic_error("PassTimer::beginFrame(): frame already open");
    mOpen = true;
    if (mClock == GpuTimer::Clock::WallAroundFinish) {
        glFinish();
        mLast = std::chrono::steady_clock::now();
        mWallMs.assign(static_cast<size_t>(mPassCount), 0.0);
        return;
    }
    Slot& slot = mRing[static_cast<size_t>(mNext)];
    if (slot.pending) // the ring is full: these results we must have before reusing the queries
        collect(slot);
    slot.used = 0;
    slot.passOf.clear();
    mark(-1);
}

void PassTimer::mark(int pass) {
    if (!mOpen)
        throw std::logic_error("PassTimer::mark(): no open frame");
    if (pass < -1 || pass >= mPassCount || (pass == -1 && mClock == GpuTimer::Clock::WallAroundFinish))
        throw std::logic_error("PassTimer::mark(): pass " + std::to_string(pass) + " outside [0, " +
                               std::to_string(mPassCount) + ")");
    if (mClock == GpuTimer::Clock::WallAroundFinish) {
        glFinish();
        const auto now = std::chrono::steady_clock::now();
        mWallMs[static_cast<size_t>(pass)] += std::chrono::duration<double, std::milli>(now - mLast).count();
        mLast = now;
        return;
    }
    Slot& slot = mRing[static_cast<size_t>(mNext)];
    if (slot.used == static_cast<int>(slot.queries.size()))
        slot.queries.push_back(Query::create(GL_TIMESTAMP));
    glQueryCounter(slot.queries[static_cast<size_t>(slot.used)].id(), GL_TIMESTAMP);
    slot.passOf.push_back(pass);
    ++slot.used;
}

void PassTimer::endFrame() {
    if (!mOpen)
        throw std::logic_error("PassTimer::endFrame(): no open frame");
    mOpen = false;
    if (mClock == GpuTimer::Clock::WallAroundFinish) {
        mLatest = mWallMs;
        return;
    }
    mRing[static_cast<size_t>(mNext)].pending = true;
    mNext = (mNext + 1) % static_cast<int>(mRing.size());
}

bool PassTimer::available(const Slot& slot) const {
    GLint ready = 0; // timestamps complete in order: the frame's last one is the last to arrive
    glGetQueryObjectiv(slot.queries[static_cast<size_t>(slot.used - 1)].id(), GL_QUERY_RESULT_AVAILABLE,
                       &ready);
    return ready != 0;
}

void PassTimer::collect(Slot& slot) {
    std::vector<double> ms(static_cast<size_t>(mPassCount), 0.0);
    GLuint64 previous = 0;
    for (int i = 0; i < slot.used; ++i) {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(slot.queries[static_cast<size_t>(i)].id(), GL_QUERY_RESULT, &ns);
        const int pass = slot.passOf[static_cast<size_t>(i)];
        if (pass >= 0 && ns >= previous)
            ms[static_cast<size_t>(pass)] += static_cast<double>(ns - previous) * 1e-6;
        previous = ns;
    }
    slot.pending = false;
    mLatest = std::move(ms);
}

std::optional<std::vector<double>> PassTimer::poll() {
    if (mClock == GpuTimer::Clock::TimerQuery) {
        // Oldest pending first: the slot right after the newest.
        const int n = static_cast<int>(mRing.size());
        for (int k = 0; k < n; ++k) {
            Slot& slot = mRing[static_cast<size_t>((mNext + k) % n)];
            if (!slot.pending)
                continue;
            if (!available(slot))
                break; // later frames are not ready either
            collect(slot);
        }
    }
    auto v = std::move(mLatest);
    mLatest.reset();
    return v;
}

void PassTimer::drain() {
    if (mClock != GpuTimer::Clock::TimerQuery)
        return;
    const int n = static_cast<int>(mRing.size());
    for (int k = 0; k < n; ++k) {
        Slot& slot = mRing[static_cast<size_t>((mNext + k) % n)];
        if (slot.pending)
            collect(slot);
    }
}

} // namespace pacifica::gl
