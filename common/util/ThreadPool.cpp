#include "util/ThreadPool.h"

#include <atomic>
#include <memory>

namespace igi {

ThreadPool::ThreadPool(unsigned threads) {
    for (unsigned i = 0; i < std::max(1u, threads); ++i) workers_.emplace_back([this] { run(); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (auto& w : workers_) w.join();
}

unsigned ThreadPool::defaultThreads() {
    return std::max(1u, std::thread::hardware_concurrency());
}

void ThreadPool::submit(std::function<void()> task) {
    {
        std::lock_guard lock(mutex_);
        tasks_.push_back(std::move(task));
    }
    wake_.notify_one();
}

void ThreadPool::clearPending() {
    std::lock_guard lock(mutex_);
    tasks_.clear();
    if (running_ == 0) idle_.notify_all();
}

void ThreadPool::waitIdle() {
    std::unique_lock lock(mutex_);
    idle_.wait(lock, [this] { return tasks_.empty() && running_ == 0; });
}

void ThreadPool::run() {
    for (;;) {
        std::function<void()> task;
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || !tasks_.empty(); });
            if (tasks_.empty()) return;  // stopping, and the queue is drained
            task = std::move(tasks_.front());
            tasks_.pop_front();
            ++running_;
        }
        task();
        std::lock_guard lock(mutex_);
        if (--running_ == 0 && tasks_.empty()) idle_.notify_all();
    }
}

void ThreadPool::parallelFor(std::size_t count, const std::function<void(std::size_t)>& f) {
    if (count == 0) return;
    // Shared state outlives this call: a helper task may only start after the caller returned,
    // and then it finds no index left and does nothing.
    struct State {
        std::atomic<std::size_t> next{0};
        std::atomic<std::size_t> done{0};
        std::mutex mutex;
        std::condition_variable finished;
        const std::function<void(std::size_t)>* f;
        std::size_t count;
    };
    auto state = std::make_shared<State>();
    state->f = &f;
    state->count = count;
    auto work = [state] {
        for (std::size_t i; (i = state->next.fetch_add(1)) < state->count;) {
            (*state->f)(i);
            if (state->done.fetch_add(1) + 1 == state->count) {
                std::lock_guard lock(state->mutex);
                state->finished.notify_all();
            }
        }
    };
    const std::size_t helpers = std::min<std::size_t>(workers_.size(), count - 1);
    for (std::size_t i = 0; i < helpers; ++i) submit(work);
    work();
    std::unique_lock lock(state->mutex);
    state->finished.wait(lock, [&] { return state->done.load() == count; });
}

}  // namespace igi
