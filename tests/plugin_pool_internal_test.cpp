// The tile worker pool: best priority first, re-planning drops tasks that have not started, and
// started tasks always finish.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "worker_pool.h"
#include "wait_until.h"

namespace terrasynth::plugin {
namespace {

TEST(PluginPool, RunsBestPriorityFirstAndDropsReplacedTasks) {
    WorkerPool pool(1);
    std::mutex m;
    std::vector<int> order;
    std::atomic<bool> started{false}, release{false};
    // Occupy the only worker so that everything else queues.
    pool.push({0.0, [&] {
                   started = true;
                   while (!release) std::this_thread::yield();
               }});
    while (!started) std::this_thread::yield();
    auto record = [&](int id) { return [&, id] { std::lock_guard<std::mutex> l(m); order.push_back(id); }; };
    for (int id : {5, 1, 4}) pool.push({double(id), record(id)});
    // Re-plan: 5 and 4 are no longer wanted, 1 is still wanted and 2, 3 are new.
    pool.replaceQueue({{3.0, record(3)}, {1.0, record(1)}, {2.0, record(2)}});
    EXPECT_EQ(pool.pending(), 4u);
    release = true;
    pool.waitIdle();
    EXPECT_EQ(order, (std::vector<int>{1, 2, 3}));
    EXPECT_EQ(pool.pending(), 0u);
}

TEST(PluginPool, UsesAllThreadsAndFinishesStartedWork) {
    std::atomic<int> running{0}, peak{0}, done{0};
    std::atomic<bool> started{false};
    {
        WorkerPool pool(2);
        EXPECT_EQ(pool.threadCount(), 2);
        // Each task stays until two run at once (or a deadline of minutes, shared by all, passes):
        // with both threads in use that happens whatever the machine's load; with one it never does.
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
        for (int i = 0; i < 8; ++i)
            pool.push({double(i), [&] {
                           const int now = ++running;
                           int p = peak;
                           while (now > p && !peak.compare_exchange_weak(p, now)) {}
                           test::waitUntil([&] { return peak >= 2; }, deadline - std::chrono::steady_clock::now());
                           --running;
                           ++done;
                       }});
        pool.waitIdle();
        EXPECT_EQ(done, 8);
        pool.push({0.0, [&] {
                       started = true;
                       std::this_thread::sleep_for(std::chrono::milliseconds(30));  // still running at the destructor
                       ++done;
                   }});
        ASSERT_TRUE(test::waitUntil([&] { return started.load(); }));
    }  // the destructor waits for the started task
    EXPECT_EQ(peak, 2);
    EXPECT_EQ(done, 9);
}

// runOnEveryThread runs once on each worker (the preload, and each worker's synthesizer made before
// the first frame), also on a worker that is busy with a task when it is called, and again per call.
TEST(PluginPool, RunsOnEveryThreadOnceAlsoBesideABusyWorker) {
    WorkerPool pool(3);
    std::atomic<bool> busy{false}, release{false};
    pool.push({0.0, [&] {
                   busy = true;
                   test::waitUntil([&] { return release.load(); });
               }});
    ASSERT_TRUE(test::waitUntil([&] { return busy.load(); }));
    std::mutex m;
    std::vector<std::thread::id> ran;
    std::thread caller([&] {
        pool.runOnEveryThread([&] {
            std::lock_guard<std::mutex> lock(m);
            ran.push_back(std::this_thread::get_id());
        });
    });
    // The two idle workers run it; the call returns only once the busy one has too.
    EXPECT_TRUE(test::waitUntil([&] { std::lock_guard<std::mutex> lock(m); return ran.size() == 2; }));
    release = true;
    caller.join();
    ASSERT_EQ(ran.size(), 3u);
    std::sort(ran.begin(), ran.end());
    EXPECT_EQ(std::unique(ran.begin(), ran.end()), ran.end()) << "a worker ran it twice";
    EXPECT_EQ(std::count(ran.begin(), ran.end(), std::this_thread::get_id()), 0) << "the caller ran it";
    std::atomic<int> second{0};
    pool.runOnEveryThread([&] { ++second; });
    EXPECT_EQ(second, 3);
    pool.waitIdle();
}

}  // namespace
}  // namespace terrasynth::plugin
