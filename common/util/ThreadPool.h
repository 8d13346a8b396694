#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace igi {

/// A fixed set of worker threads fed from one queue. Clients render tile chunks on it, the
/// master decodes and filters on it.
class ThreadPool {
  public:
    explicit ThreadPool(unsigned threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    void submit(std::function<void()> task);

    /// Drops the tasks that have not started (work that is no longer wanted, at shutdown).
    void clearPending();

    /// Waits until no task is queued or running.
    void waitIdle();

    /// Runs f(i) for every i in [0, count) on the workers and the calling thread; returns when
    /// all are done. The caller works too, so this never waits on a busy queue.
    void parallelFor(std::size_t count, const std::function<void(std::size_t)>& f);

    unsigned size() const { return static_cast<unsigned>(workers_.size()); }

    /// Number of threads to use when the user said 0: every hardware thread.
    static unsigned defaultThreads();

  private:
    void run();

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> tasks_;
    std::size_t running_ = 0;
    std::condition_variable idle_;
    bool stopping_ = false;
    std::vector<std::thread> workers_;
};

}  // namespace igi
