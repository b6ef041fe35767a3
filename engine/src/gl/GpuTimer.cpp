// GpuTimer implementation: ring of GL_TIME_ELAPSED queries, or wall clock around glFinish on llvmpipe.
#include "engine/gl/GpuTimer.h"

#include <epoxy/gl.h>

#include <stdexcept>

namespace pacifica::gl {

GpuTimer::GpuTimer(const ContextInfo& info, int ringSize)
    : GpuTimer(info.software ? Clock::WallAroundFinish : Clock::TimerQuery, ringSize) {}

GpuTimer::GpuTimer(Clock clock, int ringSize) : mClock(clock) {
    if (ringSize < 1)
        throw std::logic_error("GpuTimer::GpuTimer(): ringSize must be >= 1, got " +
                               std::to_string(ringSize));
    if (mClock == Clock::TimerQuery) {
        for (int i = 0; i < ringSize; ++i)
            mQueries.push_back(Query::create(GL_TIME_ELAPSED));
        mPending.assign(static_cast<size_t>(ringSize), false);
    }
}

const char* GpuTimer::clockName() const {
    return mClock == Clock::TimerQuery ? "GL_TIME_ELAPSED timer query"
                                       : "wall clock (steady_clock) around glFinish";
}

void GpuTimer::begin() {
    if (mOpen)
        throw std::logic_error("GpuTimer::begin(): span already open");
    mOpen = true;
    if (mClock == Clock::WallAroundFinish) {
        glFinish();
        mStart = std::chrono::steady_clock::now();
        return;
    }
    const size_t slot = static_cast<size_t>(mNext);
    if (mPending[slot]) // the ring is full: this one result we must have before reusing the query
        collect(true);
    glBeginQuery(GL_TIME_ELAPSED, mQueries[slot].id());
}

void GpuTimer::end() {
    if (!mOpen)
        throw std::logic_error("GpuTimer::end(): no open span");
    mOpen = false;
    if (mClock == Clock::WallAroundFinish) {
        glFinish();
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart).count();
        mSamples.push_back(ms);
        mLatest = ms;
        return;
    }
    glEndQuery(GL_TIME_ELAPSED);
    mPending[static_cast<size_t>(mNext)] = true;
    mNext = (mNext + 1) % static_cast<int>(mQueries.size());
}

void GpuTimer::collect(bool wait) {
    // Oldest pending first: the ring slot right after the newest.
    const int n = static_cast<int>(mQueries.size());
    for (int k = 0; k < n; ++k) {
        const size_t slot = static_cast<size_t>((mNext + k) % n);
        if (!mPending[slot])
            continue;
        GLint available = 0;
        if (!wait)
            glGetQueryObjectiv(mQueries[slot].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (!wait && !available)
            return; // results arrive in order: later ones are not ready either
        GLuint64 ns = 0;
        glGetQueryObjectui64v(mQueries[slot].id(), GL_QUERY_RESULT, &ns);
        mPending[slot] = false;
        const double ms = static_cast<double>(ns) * 1e-6;
        mSamples.push_back(ms);
        mLatest = ms;
        if (wait)
            return;
    }
}

void GpuTimer::drain() {
    if (mClock != Clock::TimerQuery)
        return;
    for (size_t k = 0; k < mQueries.size(); ++k)
        collect(true); // each call takes the oldest pending result, waiting for it
}

std::optional<double> GpuTimer::poll() {
    if (mClock == Clock::TimerQuery)
        collect(false);
    auto v = mLatest;
    mLatest.reset();
    return v;
}

} // namespace pacifica::gl
