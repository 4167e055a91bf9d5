// core/workers.h: the one helper every module's thread pool is built on.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/workers.h"
#include "wait_until.h"

namespace terrasynth {
namespace {

TEST(CoreWorkers, EveryWorkerRunsOnceAndWorkerZeroOnTheCallingThread) {
    std::vector<std::thread::id> ran_on(4);
    std::vector<int> runs(4, 0);
    runOnWorkers(4, [&](int worker) {
        ran_on[worker] = std::this_thread::get_id();
        ++runs[worker];  // each worker writes only its own slot
    });
    EXPECT_EQ(runs, std::vector<int>(4, 1));
    EXPECT_EQ(ran_on[0], std::this_thread::get_id());
    for (int worker = 1; worker < 4; ++worker) EXPECT_NE(ran_on[worker], std::this_thread::get_id()) << worker;
}

TEST(CoreWorkers, FewerThanOneWorkerRunsOneOnTheCallingThread) {
    int runs = 0;
    std::thread::id ran_on;
    runOnWorkers(0, [&](int worker) {
        EXPECT_EQ(worker, 0);
        ran_on = std::this_thread::get_id();
        ++runs;
    });
    EXPECT_EQ(runs, 1);
    EXPECT_EQ(ran_on, std::this_thread::get_id());
}

TEST(CoreWorkers, AWorkersExceptionReachesTheCallerOnceAllHaveFinished) {
    // Before core/workers.h, the drainage breach's workers had no guard: an exception there (a
    // carve list out of memory) ended the process with std::terminate.
    // The others finish only after worker 2 has thrown (a condition, not a pause), so the caller
    // must have waited for them.
    std::atomic<int> finished{0};
    std::atomic<bool> thrown{false};
    try {
        runOnWorkers(3, [&](int worker) {
            if (worker == 2) {
                thrown = true;
                throw std::runtime_error("worker 2 failed");
            }
            EXPECT_TRUE(test::waitUntil([&] { return thrown.load(); }));
            ++finished;
        });
        FAIL() << "the worker's exception was not rethrown";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "worker 2 failed");
    }
    EXPECT_EQ(finished.load(), 2);
}

TEST(CoreWorkers, ThreadCountMatchesTheMachine) {
    EXPECT_GE(hardwareThreads(), 1);
    EXPECT_EQ(hardwareThreads(), static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}

}  // namespace
}  // namespace terrasynth
