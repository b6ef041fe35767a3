// Jobs: how the ocean's CPU work (sea queries, the FFT sea's tiles) is spread over threads -- the host's own
// job system through one function pointer (JobSystem), or the small pool here (ThreadPool). Neither
// allocates per call, so a query in a game's frame loop does not touch the heap.
//
//   ThreadPool pool(0);                       // one thread per hardware thread (the caller counts as one)
//   JobSystem jobs = pool.jobs();             // or {myScheduler, &myParallelFor} from the host
//   jobs.run(count, &work, &context);         // work(&context, i) for every i < count; returns when done
#pragma once

#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <thread>
#include <vector>

namespace pacifica::ocean {

/// A host's parallel-for: parallelFor(user, count, job, context) must call job(context, i) exactly once for
/// every i < count, on any threads, and return when all have returned. A job never throws (the ocean's jobs
/// catch what they raise). With parallelFor null, run() calls the jobs in order on the calling thread.
struct JobSystem {
    using Job = void (*)(void* context, size_t index);
    void* user = nullptr;
    void (*parallelFor)(void* user, size_t count, Job job, void* context) = nullptr;

    void run(size_t count, Job job, void* context) const {
        if (parallelFor && count > 1) {
            parallelFor(user, count, job, context);
            return;
        }
        for (size_t i = 0; i < count; ++i)
            job(context, i);
    }
};

/// `threads` - 1 worker threads that, with the calling thread, take the jobs of run() by an atomic counter.
/// threads = 0: one per hardware thread; 1: no workers (the calling thread runs everything). run() may be
/// called from one thread at a time; it allocates nothing.
class ThreadPool {
public:
    explicit ThreadPool(unsigned threads = 0);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    /// Threads that run jobs, the caller's included (>= 1).
    unsigned size() const { return static_cast<unsigned>(mWorkers.size()) + 1; }
    void run(size_t count, JobSystem::Job job, void* context);
    /// This pool as a JobSystem (valid while the pool lives).
    JobSystem jobs() {
        return {this, [](void* user, size_t count, JobSystem::Job job, void* context) {
                    static_cast<ThreadPool*>(user)->run(count, job, context);
                }};
    }

private:
    void work();
    void stop(); // stops and joins the workers
    void take(); // runs jobs of the current batch until none is left

    std::vector<std::thread> mWorkers;
    std::mutex mMutex;
    std::condition_variable mStart, mDone;
    unsigned long long mBatch = 0; // incremented by every run(): wakes the workers
    bool mStopping = false;
    JobSystem::Job mJob = nullptr;
    void* mContext = nullptr;
    size_t mCount = 0, mNext = 0, mFinished = 0;
    unsigned mBusy = 0; // workers inside the current batch
};

} // namespace pacifica::ocean
