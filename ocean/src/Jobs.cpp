// Jobs: the ocean's small thread pool (Jobs.h).
#include "ocean/Jobs.h"

#include <algorithm>

namespace pacifica::ocean {

ThreadPool::ThreadPool(unsigned threads) {
    const unsigned n = threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
    try {
        for (unsigned i = 1; i < n; ++i)
            mWorkers.emplace_back([this] { work(); });
    } catch (...) { // a thread could not start: stop the ones that did, then report it
        stop();
        throw;
    }
}

void ThreadPool::stop() {
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mStopping = true;
    }
    mStart.notify_all();
    for (std::thread& t : mWorkers)
        t.join();
    mWorkers.clear();
}

ThreadPool::~ThreadPool() {
    stop();
}

void ThreadPool::take() {
    // Called with mMutex held; runs each job unlocked.
    std::unique_lock<std::mutex> lock(mMutex, std::adopt_lock);
    while (mNext < mCount) {
        const size_t i = mNext++;
        const JobSystem::Job job = mJob;
        void* context = mContext;
        lock.unlock();
        job(context, i);
        lock.lock();
        if (++mFinished == mCount)
            mDone.notify_all();
    }
    lock.release(); // the caller still holds mMutex
}

void ThreadPool::work() {
    unsigned long long seen = 0;
    std::unique_lock<std::mutex> lock(mMutex);
    for (;;) {
        mStart.wait(lock, [&] { return mStopping || mBatch != seen; });
        if (mStopping)
            return;
        seen = mBatch;
        ++mBusy;
        lock.release();
        take();
        lock = std::unique_lock<std::mutex>(mMutex, std::adopt_lock);
        if (--mBusy == 0)
            mDone.notify_all();
    }
}

void ThreadPool::run(size_t count, JobSystem::Job job, void* context) {
    if (count == 0)
        return;
    if (mWorkers.empty() || count == 1) {
        for (size_t i = 0; i < count; ++i)
            job(context, i);
        return;
    }
    std::unique_lock<std::mutex> lock(mMutex);
    mJob = job;
    mContext = context;
    mCount = count;
    mNext = 0;
    mFinished = 0;
    ++mBatch;
    mStart.notify_all();
    lock.release();
    take();
    lock = std::unique_lock<std::mutex>(mMutex, std::adopt_lock);
    // Every job has finished and no worker still holds this batch's job (the next run() may reset it).
    mDone.wait(lock, [&] { return mFinished == mCount && mBusy == 0; });
    mCount = 0;
    mNext = 0;
}

} // namespace pacifica::ocean
