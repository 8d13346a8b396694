#include "util/ThreadPool.h"

#include <atomic>
#include <vector>

#include <gtest/gtest.h>

namespace igi {
namespace {

TEST(ThreadPool, ParallelForRunsEveryIndexOnce) {
    ThreadPool pool(3);
    std::vector<std::atomic<int>> hits(1000);
    pool.parallelFor(hits.size(), [&](std::size_t i) { hits[i]++; });
    for (auto& h : hits) EXPECT_EQ(h.load(), 1);
}

TEST(ThreadPool, ParallelForCompletesWhileTheQueueIsBusy) {
    ThreadPool pool(1);
    std::atomic<bool> release{false};
    pool.submit([&] {
        while (!release) std::this_thread::yield();
    });
    std::atomic<int> sum{0};
    pool.parallelFor(100, [&](std::size_t i) { sum += int(i); });  // the caller does the work
    EXPECT_EQ(sum.load(), 4950);
    release = true;
}

TEST(ThreadPool, SubmittedTasksRunBeforeDestruction) {
    std::atomic<int> ran{0};
    {
        ThreadPool pool(2);
        for (int i = 0; i < 50; ++i) pool.submit([&] { ran++; });
    }
    EXPECT_EQ(ran.load(), 50);
}

}  // namespace
}  // namespace igi

namespace igi {
namespace {

TEST(ThreadPool, WaitIdleReturnsOnceEverythingQueuedHasRun) {
    ThreadPool pool(2);
    std::atomic<int> ran{0};
    for (int i = 0; i < 20; ++i)
        pool.submit([&] {
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
            ran++;
        });
    pool.waitIdle();
    EXPECT_EQ(ran.load(), 20);
    pool.waitIdle();  // idle already: returns at once
}

}  // namespace
}  // namespace igi
