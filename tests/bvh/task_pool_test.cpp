// TaskPool (host/bvh/task_pool.h), the fork-join pool of the BVH builder, flatten and the
// wide collapse: every task runs exactly once, nested fork-join finishes (a waiting thread
// runs queued tasks instead of blocking), for_each's caller runs no task but its own while
// it waits, failures reach the caller, worker indices stay within the pool, and a later
// pool borrows the parked threads of an earlier one.
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

// Binary fork-join to depth 14 (16383 tasks), the builder's pattern: the right half as a
// task, the left one here, then the join (fork_join). Each node also bins "its triangles" in
// four chunks first (for_each), as the builder's large nodes do. Counts the leaves.
long count_leaves(TaskPool& pool, int depth)
{
    if (depth == 0) return 1;
    std::atomic<int> chunks{0};
    pool.for_each(4, [&](std::size_t) { ++chunks; });
    if (chunks.load() != 4) return -(1L << 20); // makes the total wrong
    long left = 0;
    long right = 0;
    pool.fork_join([&] { left = count_leaves(pool, depth - 1); }, [&] { right = count_leaves(pool, depth - 1); });
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

// While it waits, for_each's caller runs its own chunks and nothing else: an unrelated task
// queued meanwhile (by another thread, in the builder: a subtree) would hold back whatever
// the chunks' end releases. Here the caller's own chunk queues it, so that it is the newest
// task when the caller starts to wait; on a pool of one thread nothing else runs it.
TEST(TaskPool, ForEachRunsOnlyItsOwnTasksWhileWaiting)
{
    TaskPool pool(1);
    TaskGroup unrelated;
    std::atomic<bool> unrelated_ran{false};
    std::atomic<int> chunks{0};
    pool.for_each(3, [&](std::size_t c) {
        if (c == 0) pool.spawn(unrelated, [&] { unrelated_ran = true; });
        ++chunks;
    });
    const bool ran_during_for_each = unrelated_ran.load();
    pool.wait(unrelated);
    std::printf("[ pool ] for_each ran %d of 3 chunks; the unrelated task ran %s\n", chunks.load(),
                ran_during_for_each ? "inside for_each" : "after it, in wait()");
    EXPECT_EQ(chunks.load(), 3);
    EXPECT_FALSE(ran_during_for_each);
    EXPECT_TRUE(unrelated_ran.load());
}

// wait() helps with any queued task: a thread whose group's last task is running elsewhere
// takes the unrelated one meanwhile (here the worker's task cannot finish until it has).
TEST(TaskPool, WaitRunsOtherTasksMeanwhile)
{
    TaskPool pool(2);
    std::atomic<bool> worker_started{false};
    std::atomic<bool> unrelated_ran{false};
    std::atomic<bool> worker_saw_it{false};
    TaskGroup mine;
    pool.spawn(mine, [&] {
        worker_started = true;
        const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (!unrelated_ran.load() && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
        worker_saw_it = unrelated_ran.load();
    });
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (!worker_started.load() && std::chrono::steady_clock::now() < give_up) std::this_thread::yield();
    ASSERT_TRUE(worker_started.load()) << "the worker never took the task";
    TaskGroup unrelated;
    pool.spawn(unrelated, [&] { unrelated_ran = true; });
    pool.wait(mine);
    pool.wait(unrelated);
    std::printf("[ pool ] the waiting caller ran the unrelated task: %s\n", worker_saw_it.load() ? "yes" : "no");
    EXPECT_TRUE(worker_saw_it.load());
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

// The builder and the collapse fork with for_each and fork_join because of this: when the
// caller's own share throws, the other tasks, which refer to the caller's frame, have
// finished before the exception leaves.
TEST(TaskPool, ForkJoinsWaitForTheirTasksBeforeRethrowing)
{
    TaskPool pool(2);
    std::atomic<bool> task_done{false};
    const auto slow_task = [&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
        task_done = true;
    };
    try {
        pool.for_each(2, [&](std::size_t i) {
            if (i == 0) throw std::runtime_error("the caller's share");
            slow_task();
        });
        FAIL() << "expected the caller's exception from for_each";
    } catch (const std::runtime_error&) {
        EXPECT_TRUE(task_done.load()) << "for_each let the exception out while its task still ran";
    }
    task_done = false;
    try {
        pool.fork_join([] { throw std::runtime_error("the caller's half"); }, slow_task);
        FAIL() << "expected the caller's exception from fork_join";
    } catch (const std::runtime_error&) {
        EXPECT_TRUE(task_done.load()) << "fork_join let the exception out while its task still ran";
    }
    EXPECT_THROW(pool.fork_join([] {}, [] { throw std::logic_error("the task's half"); }), std::logic_error);
}

}  // namespace
}  // namespace gc::test
