// worker_pool.h: the std::thread pool that builds tiles off the draw thread.
//
// Work is re-planned every frame: the tile manager hands over the complete list of tiles it still
// wants, best first, and the pool replaces its queue with it. Tasks nobody wants any more are
// dropped before they start (a flight never waits for tiles it has left behind); started tasks
// always finish. Workers run at a lower CPU priority than the threads that create the pool.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace terrasynth::plugin {

class WorkerPool {
public:
    // Niceness added to worker threads so the frame loop keeps its CPU share.
    static constexpr int kWorkerNice = 10;
    struct Task {
        double priority = 0.0;  // lower runs first
        std::function<void()> run;
    };

    // threads >= 1. The threads start at once and sleep until there is work.
    explicit WorkerPool(int threads);
    // Drops queued tasks, waits for running ones and joins.
    ~WorkerPool();
    WorkerPool(const WorkerPool&) = delete;
    WorkerPool& operator=(const WorkerPool&) = delete;

    // Replaces every queued (not started) task with `tasks`. Thread-safe.
    void replaceQueue(std::vector<Task> tasks);
    // Adds one task to the queue. Thread-safe.
    void push(Task task);
    // Queued plus running tasks.
    size_t pending() const;
    // Blocks until nothing is queued or running.
    void waitIdle();
    // Runs `fn` once on each worker thread, beside the queue (workers busy with a task run it after
    // that task), and returns when every worker has. For what belongs to a thread, made before the
    // frame loop needs it: each worker's synthesizer, so that no OpenCL context or kernel build
    // happens while a frame is drawn or the graphics context closes. `fn` must not throw or call
    // back into the pool. One caller at a time (calls from several threads take turns).
    void runOnEveryThread(const std::function<void()>& fn);
    int threadCount() const { return static_cast<int>(threads_.size()); }

private:
    void workerLoop();
    void sortQueueLocked();

    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::condition_variable idle_;
    std::vector<Task> queue_;  // sorted so that the best task is at the back
    size_t running_ = 0;
    bool stopping_ = false;
    std::mutex every_thread_turn_;                      // one runOnEveryThread at a time
    const std::function<void()>* every_thread_ = nullptr;  // what runOnEveryThread runs
    uint64_t every_thread_round_ = 0;                   // its calls so far
    size_t every_thread_left_ = 0;                      // workers yet to run this round's
    std::vector<std::thread> threads_;
};

}  // namespace terrasynth::plugin
