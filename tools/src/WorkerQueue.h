// WorkerQueue: one background thread running jobs in submission order, with at most `maxPending` jobs
// queued (submit() blocks beyond that, so memory stays bounded). Replay hands it each frame's image encoding
// (EXR + PNG) and renders the next frame meanwhile (docs/PERFORMANCE.md). A job's result or exception
// arrives through its std::future; the destructor runs what is queued and joins. Header-only.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>

namespace pacifica::tools {

template <typename Result>
class WorkerQueue {
public:
    explicit WorkerQueue(size_t maxPending = 2) : mMaxPending(maxPending) {
        if (maxPending < 1)
            throw std::logic_error("WorkerQueue: maxPending must be >= 1");
        mThread = std::thread([this] { run(); });
    }
    ~WorkerQueue() {
        {
            std::lock_guard<std::mutex> lock(mMutex);
            mStopping = true;
        }
        mWake.notify_all();
        mThread.join();
    }
    WorkerQueue(const WorkerQueue&) = delete;
    WorkerQueue& operator=(const WorkerQueue&) = delete;

    /// Queues `job`; blocks while maxPending jobs wait to start.
    std::future<Result> submit(std::function<Result()> job) {
        std::packaged_task<Result()> task(std::move(job));
        std::future<Result> result = task.get_future();
        std::unique_lock<std::mutex> lock(mMutex);
        mRoom.wait(lock, [this] { return mQueue.size() < mMaxPending; });
        mQueue.push_back(std::move(task));
        lock.unlock();
        mWake.notify_one();
        return result;
    }

    /// Jobs queued and not yet started.
    size_t pending() const {
        std::lock_guard<std::mutex> lock(mMutex);
        return mQueue.size();
    }

private:
    void run() {
        for (;;) {
            std::packaged_task<Result()> task;
            {
                std::unique_lock<std::mutex> lock(mMutex);
                mWake.wait(lock, [this] { return mStopping || !mQueue.empty(); });
                if (mQueue.empty())
                    return; // stopping and drained
                task = std::move(mQueue.front());
                mQueue.pop_front();
            }
            mRoom.notify_one();
            task(); // a throwing job stores its exception in its future
        }
    }

    size_t mMaxPending;
    mutable std::mutex mMutex;
    std::condition_variable mWake, mRoom;
    std::deque<std::packaged_task<Result()>> mQueue;
    bool mStopping = false;
    std::thread mThread;
};

} // namespace pacifica::tools
