#include "worker_pool.h"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "terrasynth/guard.h"
#include "terrasynth/status.h"

namespace terrasynth::plugin {

WorkerPool::WorkerPool(int threads) {
    TERRASYNTH_REQUIRE(threads >= 1, "a worker pool needs at least one thread");
    for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { workerLoop(); });
}

WorkerPool::~WorkerPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        queue_.clear();
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
}

void WorkerPool::sortQueueLocked() {
    // Stable so equal priorities keep the caller's order (its best first becomes our back).
    std::reverse(queue_.begin(), queue_.end());
    std::stable_sort(queue_.begin(), queue_.end(),
                     [](const Task& a, const Task& b) { return a.priority > b.priority; });
}

void WorkerPool::replaceQueue(std::vector<Task> tasks) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        queue_ = std::move(tasks);
        sortQueueLocked();
    }
    wake_.notify_all();
    idle_.notify_all();
}

void WorkerPool::push(Task task) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        // Before every task of equal or better priority, so it runs after them.
        auto at = std::find_if(queue_.begin(), queue_.end(),
                               [&](const Task& t) { return t.priority <= task.priority; });
        queue_.insert(at, std::move(task));
    }
    wake_.notify_one();
}

size_t WorkerPool::pending() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return queue_.size() + running_;
}

void WorkerPool::waitIdle() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return queue_.empty() && running_ == 0; });
}

void WorkerPool::runOnEveryThread(const std::function<void()>& fn) {
    std::lock_guard<std::mutex> turn(every_thread_turn_);
    std::unique_lock<std::mutex> lock(mutex_);
    every_thread_ = &fn;
    every_thread_left_ = threads_.size();
    ++every_thread_round_;
    wake_.notify_all();
    idle_.wait(lock, [this] { return every_thread_left_ == 0; });
    every_thread_ = nullptr;
}

void WorkerPool::workerLoop() {
    // Below the frame loop's priority: on a machine with as many workers as cores, the update, cull
    // and draw threads must not wait for a tile build to yield the CPU (Linux: nice is per thread).
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kWorkerNice);
    std::unique_lock<std::mutex> lock(mutex_);
    uint64_t round_done = 0;  // not the member: a thread may first run after a round has begun
    for (;;) {
        wake_.wait(lock, [&] { return stopping_ || !queue_.empty() || round_done != every_thread_round_; });
        if (stopping_) return;
        if (round_done != every_thread_round_) {
            round_done = every_thread_round_;
            const std::function<void()>* fn = every_thread_;
            lock.unlock();
            invokeGuarded([&] { (*fn)(); },
                          [](const std::string& why) { std::fprintf(stderr, "terrasynth worker: %s\n", why.c_str()); });
            lock.lock();
            if (--every_thread_left_ == 0) idle_.notify_all();
            continue;
        }
        Task task = std::move(queue_.back());
        queue_.pop_back();
        ++running_;
        lock.unlock();
        // An exception must not end the worker (std::terminate); tasks report their own errors.
        invokeGuarded([&] { task.run(); },
                      [](const std::string& why) { std::fprintf(stderr, "terrasynth worker: %s\n", why.c_str()); });
        lock.lock();
        --running_;
        if (queue_.empty() && running_ == 0) idle_.notify_all();
    }
}

}  // namespace terrasynth::plugin
