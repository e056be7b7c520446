// TaskPool (host/bvh/task_pool.h), the fork-join pool of the BVH builder, flatten and the
// wide collapse: every task runs exactly once, nested fork-join finishes (a waiting thread
// runs queued tasks instead of blocking), failures reach the caller, worker indices stay
// within the pool, and a later pool borrows the parked threads of an earlier one.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "host/bvh/task_pool.h"

namespace gc::test {
namespace {

TEST(TaskPool, ForEachRunsEveryIndexOnceOnValidWorkers)
{
    TaskPool pool(8);
    std::vector<std::atomic<int>> runs(5000);
    std::atomic<int> bad_index{0};
    pool.for_each(runs.size(), [&](std::size_t i) {
        ++runs[i];
        const int w = pool.worker_index();
        if (w < 0 || w >= pool.threads()) ++bad_index;
    });
    int wrong = 0;
    for (const std::atomic<int>& r : runs) wrong += r.load() == 1 ? 0 : 1;
    std::printf("[ pool ] %zu tasks on %d threads: %d ran other than once, %d on a bad worker index\n",
                runs.size(), pool.threads(), wrong, bad_index.load());
    EXPECT_EQ(wrong, 0);
    EXPECT_EQ(bad_index.load(), 0);
}

// Binary fork-join to depth 14 (16383 tasks), the builder's pattern: spawn the right half,
// do the left, wait. Counts the leaves.
long count_leaves(TaskPool& pool, int depth)
{
    if (depth == 0) return 1;
    long right = 0;
    TaskGroup group;
    pool.spawn(group, [&pool, &right, depth] { right = count_leaves(pool, depth - 1); });
    const long left = count_leaves(pool, depth - 1);
    pool.wait(group);
    return left + right;
}

TEST(TaskPool, NestedForkJoinCompletes)
{
    for (int threads : {1, 2, 16}) {
        TaskPool pool(threads);
        const long leaves = count_leaves(pool, 14);
        std::printf("[ pool ] %d threads: %ld leaves (expected %d)\n", threads, leaves, 1 << 14);
        EXPECT_EQ(leaves, 1L << 14);
    }
}

// Which threads serve one pool's workers: a serial number per thread (a thread_local, so a
// thread started anew gets a new one even where the OS reuses thread ids). Every one of the
// pool's threads() tasks waits until all have started, so each thread takes exactly one.
int thread_serial()
{
    static std::atomic<int> next_serial{0};
    thread_local const int serial = ++next_serial; // initialised on each thread's first call
    return serial;
}

std::vector<int> worker_serials(TaskPool& pool)
{
    std::atomic<int> started{0};
    std::vector<int> serials(static_cast<std::size_t>(pool.threads()), 0);
    pool.for_each(serials.size(), [&](std::size_t) {
        ++started;
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (started.load() < pool.threads() && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
        serials[static_cast<std::size_t>(pool.worker_index())] = thread_serial();
    });
    EXPECT_EQ(started.load(), pool.threads());
    return {serials.begin() + 1, serials.end()}; // the workers, without the caller
}

TEST(TaskPool, LaterPoolsReuseTheWorkersOfEarlierOnes)
{
    std::vector<int> first;
    {
        TaskPool pool(6);
        first = worker_serials(pool);
    }
    std::vector<int> second;
    {
        TaskPool pool(4);
        second = worker_serials(pool);
    }
    std::sort(first.begin(), first.end());
    int fresh = 0;
    for (int s : second) fresh += std::binary_search(first.begin(), first.end(), s) ? 0 : 1;
    std::printf("[ pool ] a pool of 6 then one of 4: %d of the second's %zu workers are new threads\n", fresh,
                second.size());
    EXPECT_EQ(first.size(), 5u);
    EXPECT_EQ(second.size(), 3u);
    EXPECT_EQ(fresh, 0);
}

TEST(TaskPool, FailuresReachTheCaller)
{
    TaskPool pool(4);
    EXPECT_THROW(pool.for_each(64, [](std::size_t i) {
        if (i == 37) throw std::runtime_error("task 37");
    }),
                 std::runtime_error);
    TaskGroup group;
    pool.spawn(group, [] { throw std::logic_error("spawned"); });
    EXPECT_THROW(pool.wait(group), std::logic_error);
    // The pool still works afterwards.
    std::atomic<int> ran{0};
    pool.for_each(100, [&](std::size_t) { ++ran; });
    EXPECT_EQ(ran.load(), 100);
}

// The builder and the collapse fork with for_each(2, ...) because of this: when the caller's
// own share throws, the other tasks, which refer to the caller's frame, have finished before
// the exception leaves for_each.
TEST(TaskPool, ForEachWaitsForItsTasksBeforeRethrowing)
{
    TaskPool pool(2);
    std::atomic<bool> task_done{false};
    try {
        pool.for_each(2, [&](std::size_t i) {
            if (i == 0) throw std::runtime_error("the caller's share");
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
            task_done = true;
        });
        FAIL() << "expected the caller's exception";
    } catch (const std::runtime_error&) {
        EXPECT_TRUE(task_done.load()) << "for_each let the exception out while its task still ran";
    }
}

}  // namespace
}  // namespace gc::test
