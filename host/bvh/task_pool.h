// A small fork-join pool for the BVH builder, flatten and the wide collapse: a thread that
// waits for its children runs queued tasks meanwhile, so nested fork-join never idles a core
// or deadlocks. Its workers are the process's parked worker threads, lent to the pool for its
// lifetime and parked again by its destructor (threads are started only when no parked one is
// free), so a render's three pools and a bench's many builds start no thread after the first.
//
//     TaskPool pool(threads);           // threads - 1 workers; the caller is worker 0
//     TaskGroup group;
//     pool.spawn(group, [&] { ... });   // may run on any thread, or on the caller in wait()
//     ...                               // the caller's own share
//     pool.wait(group);                 // rethrows the first exception of the group's tasks
//
//     pool.for_each(chunks, [&](std::size_t c) { ... });   // the same for chunks 0..n-1
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
    void wait(TaskGroup& group);

    // Runs fn(0) .. fn(count - 1) and returns when all have run: fn(0) on the calling thread,
    // the rest as tasks of one group. Rethrows the first exception (the caller's own first).
    template <class Fn>
    void for_each(std::size_t count, const Fn& fn)
    {
        TaskGroup group;
        for (std::size_t i = 1; i < count; ++i) spawn(group, [&fn, i] { fn(i); });
        std::exception_ptr own;
        if (count > 0) {
            try {
                fn(std::size_t{0});
            } catch (...) {
                own = std::current_exception();
            }
        }
        wait(group); // before unwinding: the tasks refer to fn
        if (own) std::rethrow_exception(own);
    }

    struct Worker; // a parked thread of the process (task_pool.cpp)

private:
    struct Task {
        TaskGroup* group;
        std::function<void()> run;
    };
    static void worker_loop(Worker* worker);
    void worker_main(int index);
    void run_task(Task& task, std::unique_lock<std::mutex>& lock);
    void release_workers() noexcept;

    std::mutex m_mutex;
    // Two wake-up calls, so that a finished task does not wake every idle worker: with one
    // condition variable and notify_all per finished group, every idle thread woke (to find
    // nothing) for each of a mid-size build's hundreds of subtree tasks. H200 host, 16 cores,
    // against Embree's commit in the same runs: CPU start of the dragon 0.34-0.39x -> 0.45-0.48x,
    // the tree alone unchanged within noise (separate runs, not interleaved).
    std::condition_variable m_work;     // a task was queued, or the pool stops (idle workers)
    std::condition_variable m_progress; // a task was queued or a group finished (threads in wait())
    int m_waiting = 0;                  // threads blocked in wait(), guarded by m_mutex
    std::deque<Task> m_queue;
    bool m_stop = false;
    std::vector<Worker*> m_workers; // lent for the pool's lifetime
    // The creating thread's previous pool, if any, restored on destruction. A pool must be
    // destroyed on the thread that made it.
    const TaskPool* m_outer_pool;
    int m_outer_index;
};

}  // namespace gc
