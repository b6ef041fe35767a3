// Unit tests of WorkerQueue (tools/src/WorkerQueue.h): replay's background image encoder. Jobs run in
// order on another thread, results and exceptions arrive through futures, the queue stays bounded, and the
// destructor finishes what was queued.
#include "WorkerQueue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <future>
#include <stdexcept>
#include <thread>
#include <vector>

using pacifica::tools::WorkerQueue;

TEST(WorkerQueue, RunsJobsInOrderOnAnotherThread) {
    WorkerQueue<int> q(2);
    std::vector<int> order;
    std::vector<std::future<int>> results;
    const std::thread::id caller = std::this_thread::get_id();
    std::atomic<bool> otherThread{true};
    for (int i = 0; i < 20; ++i)
        results.push_back(q.submit([&, i] {
            otherThread = otherThread && std::this_thread::get_id() != caller;
            order.push_back(i); // only the worker touches it
            return i * i;
        }));
    for (int i = 0; i < 20; ++i)
        EXPECT_EQ(results[static_cast<size_t>(i)].get(), i * i);
    EXPECT_TRUE(otherThread);
    ASSERT_EQ(order.size(), 20u);
    for (int i = 0; i < 20; ++i)
        EXPECT_EQ(order[static_cast<size_t>(i)], i);
}

TEST(WorkerQueue, SubmitBlocksWhileMaxPendingJobsWait) {
    WorkerQueue<int> q(1);
    std::promise<void> release;
    std::shared_future<void> gate = release.get_future().share();
    std::future<int> first = q.submit([gate] {
        gate.wait();
        return 1;
    }); // running, holds the worker
    // Wait until the worker has taken the first job off the queue.
    for (int i = 0; i < 1000 && q.pending() != 0; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ASSERT_EQ(q.pending(), 0u);
    std::future<int> second = q.submit([] { return 2; }); // queued: the queue is now full
    EXPECT_EQ(q.pending(), 1u);
    std::atomic<bool> thirdQueued{false};
    std::thread producer([&] {
        std::future<int> third = q.submit([] { return 3; });
        thirdQueued = true;
        EXPECT_EQ(third.get(), 3);
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    EXPECT_FALSE(thirdQueued) << "a full queue makes submit() wait";
    release.set_value();
    producer.join();
    EXPECT_TRUE(thirdQueued);
    EXPECT_EQ(first.get(), 1);
    EXPECT_EQ(second.get(), 2);
}

TEST(WorkerQueue, AJobsExceptionReachesItsFutureAndLaterJobsStillRun) {
    WorkerQueue<int> q(2);
    std::future<int> bad = q.submit([]() -> int { throw std::runtime_error("disk full: frame_00003.exr"); });
    std::future<int> good = q.submit([] { return 7; });
    try {
        bad.get();
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "disk full: frame_00003.exr");
    }
    EXPECT_EQ(good.get(), 7);
}

TEST(WorkerQueue, DestructorFinishesQueuedJobs) {
    std::atomic<int> done{0};
    {
        WorkerQueue<int> q(4);
        for (int i = 0; i < 4; ++i)
            (void)q.submit([&done] {
                std::this_thread::sleep_for(std::chrono::milliseconds(5));
                return ++done;
            });
    }
    EXPECT_EQ(done.load(), 4);
    EXPECT_THROW(WorkerQueue<int>(0), std::logic_error);
}
