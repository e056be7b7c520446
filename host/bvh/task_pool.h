// A small fork-join pool for the BVH builder, flatten and the wide collapse: a thread that
// waits for its children runs queued tasks meanwhile (its own, or any: see for_each and
// fork_join), so nested fork-join never deadlocks. Its workers are the process's parked
// worker threads, lent to the pool for its lifetime and parked again by its destructor
// (threads are started only when no parked one is free), so a render's three pools and a
// bench's many builds start no thread after the first.
//
//     TaskPool pool(threads);           // threads - 1 workers; the caller is worker 0
//     TaskGroup group;
//     pool.spawn(group, [&] { ... });   // may run on any thread, or on the caller in wait()
//     ...                               // the caller's own share
//     pool.wait(group);                 // rethrows the first exception of the group's tasks
//
//     pool.for_each(chunks, [&](std::size_t c) { ... });   // chunks 0..n-1 of one job
//     pool.fork_join([&] { left(); }, [&] { right(); });   // two halves of a recursion
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <vector>

namespace gc {

struct TaskGroup {
    std::size_t pending = 0;  // guarded by the pool's mutex
    std::exception_ptr error; // the first failure, guarded likewise
};

class TaskPool {
public:
    explicit TaskPool(int threads);
    ~TaskPool();
    TaskPool(const TaskPool&) = delete;
    TaskPool& operator=(const TaskPool&) = delete;

    int threads() const { return static_cast<int>(m_workers.size()) + 1; }
    // 0 on the thread that made the pool, 1..threads()-1 on the workers; -1 elsewhere.
    int worker_index() const;

    void spawn(TaskGroup& group, std::function<void()> task);
    // Returns when the group's tasks have all run, running any queued task meanwhile (the
    // newest first), else sleeping. Rethrows the first exception of the group's tasks.
    void wait(TaskGroup& group);

    // Runs fn(0) .. fn(count - 1) and returns when all have run: fn(0) on the calling thread,
    // the rest as tasks of one group. Rethrows the first exception (the caller's own first).
    // While it waits, the caller runs only these tasks, else sleeps. They are the chunks of one
    // job, such as a node's binning, whose end releases more work (the node's partition, then
    // its children); an unrelated task picked up meanwhile, often a whole subtree, would hold
    // that work back while other threads run dry (docs/decisions/bvh-build-many-cores.md).
    template <class Fn>
    void for_each(std::size_t count, const Fn& fn)
    {
        TaskGroup group;
        for (std::size_t i = 1; i < count; ++i) spawn(group, [&fn, i] { fn(i); });
        run_then_join(
            group,
            [&] {
                if (count > 0) fn(std::size_t{0});
            },
            true);
    }

    // Runs left() on the calling thread and right() as a task, and returns when both have
    // run; exceptions as for_each. While it waits, the caller runs any queued task (wait):
    // the two are halves of a recursion (the builder's subtrees), whose join releases no
    // further work, and the caller would otherwise idle for as long as the other half takes.
    template <class Left, class Right>
    void fork_join(const Left& left, const Right& right)
    {
        TaskGroup group;
        spawn(group, [&right] { right(); });
        run_then_join(group, left, false);
    }

    struct Worker; // a parked thread of the process (task_pool.cpp)

private:
    // The caller's share, then the join. The group's tasks refer to the caller's frame, so
    // they must have finished before an exception from either leaves it.
    template <class Own>
    void run_then_join(TaskGroup& group, const Own& own, bool own_tasks_only)
    {
        std::exception_ptr error;
        try {
            own();
        } catch (...) {
            error = std::current_exception();
        }
        try {
            join(group, own_tasks_only);
        } catch (...) {
            if (!error) error = std::current_exception();
        }
        if (error) std::rethrow_exception(error);
    }

    struct Task {
        TaskGroup* group;
        std::function<void()> run;
    };
    static void worker_loop(Worker* worker);
    void worker_main(int index);
    void run_task(Task& task, std::unique_lock<std::mutex>& lock);
    std::deque<Task>::iterator next_task_for(const TaskGroup& group, bool own_tasks_only); // lock held
    // wait(), or with own_tasks_only the join of for_each: only the group's own queued tasks.
    void join(TaskGroup& group, bool own_tasks_only);
    void release_workers() noexcept;

    std::mutex m_mutex;
    // Two wake-up calls, so that a finished task does not wake every idle worker: with one
    // condition variable and notify_all per finished group, every idle thread would wake (to
    // find nothing) for each of a mid-size build's hundreds of subtree tasks
    // (docs/decisions/bvh-build-many-cores.md).
    std::condition_variable m_work;     // a task was queued, or the pool stops (idle workers)
    std::condition_variable m_progress; // a task was queued or a group finished (threads in wait())
    int m_waiting = 0;                  // threads blocked in wait(), guarded by m_mutex
    // Threads joining their own tasks only care that a group finished (those tasks were all
    // queued before they waited), so a queued task does not wake them in place of a thread in
    // wait().
    std::condition_variable m_group_done;
    int m_waiting_own = 0;              // threads blocked joining own tasks, guarded by m_mutex
    std::deque<Task> m_queue;
    bool m_stop = false;
    std::vector<Worker*> m_workers; // lent for the pool's lifetime
    // The creating thread's previous pool, if any, restored on destruction. A pool must be
    // destroyed on the thread that made it.
    const TaskPool* m_outer_pool;
    int m_outer_index;
};

}  // namespace gc
