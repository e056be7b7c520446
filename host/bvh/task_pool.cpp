#include "host/bvh/task_pool.h"

#include <iterator>
#include <memory>
#include <thread>

namespace gc {

// A thread of the process that pools borrow: parked on its own condition variable until a
// pool lends it a job (`pool`, `index`), then serving that pool until it stops, then parked
// again. `pool` goes back to null only once the worker is done with the pool, which is what
// the pool's destructor waits for.
struct TaskPool::Worker {
    std::mutex mutex;
    std::condition_variable changed; // `pool` or `quit` changed
    TaskPool* pool = nullptr;        // guarded by mutex
    int index = 0;
    bool quit = false;
    std::thread thread;
};

namespace {

// Which pool the current thread serves, and as which worker (see worker_index()).
thread_local const TaskPool* t_pool = nullptr;
thread_local int t_index = -1;

// The process's workers. Starting and joining a thread per core for each pool would cost
// every build, and a CPU render makes three pools (tree, layout, collapse), where Embree's TBB
// keeps its threads: parked workers are woken instead. They sleep at once when idle: spinning
// first, as TBB's do, gains nothing here (docs/decisions/bvh-build-many-cores.md).
class ParkedWorkers {
public:
    ~ParkedWorkers()
    {
        // At exit every pool is gone (pools are scoped), so every worker is parked; one that
        // is not (exit() from inside a task) is left to the process's end rather than waited on.
        std::lock_guard<std::mutex> lock(m_mutex);
        for (TaskPool::Worker* w : m_parked) {
            {
                std::lock_guard<std::mutex> worker_lock(w->mutex);
                w->quit = true;
            }
            w->changed.notify_all();
        }
        for (const std::unique_ptr<TaskPool::Worker>& w : m_all) {
            if (w->thread.joinable()) {
                if (is_parked(w.get())) w->thread.join();
                else w->thread.detach();
            }
        }
    }

    TaskPool::Worker* take(void (*loop)(TaskPool::Worker*))
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        if (!m_parked.empty()) {
            TaskPool::Worker* w = m_parked.back();
            m_parked.pop_back();
            return w;
        }
        m_all.push_back(std::make_unique<TaskPool::Worker>());
        TaskPool::Worker* w = m_all.back().get();
        w->thread = std::thread(loop, w);
        return w;
    }

    void park(TaskPool::Worker* w)
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_parked.push_back(w);
    }

private:
    bool is_parked(const TaskPool::Worker* w) const
    {
        for (const TaskPool::Worker* p : m_parked)
            if (p == w) return true;
        return false;
    }

    std::mutex m_mutex;
    std::vector<std::unique_ptr<TaskPool::Worker>> m_all;
    std::vector<TaskPool::Worker*> m_parked;
};

ParkedWorkers& parked_workers()
{
    static ParkedWorkers workers;
    return workers;
}

}  // namespace

void TaskPool::worker_loop(Worker* worker)
{
    std::unique_lock<std::mutex> lock(worker->mutex);
    for (;;) {
        worker->changed.wait(lock, [worker] { return worker->pool != nullptr || worker->quit; });
        if (worker->pool == nullptr) return;
        TaskPool* pool = worker->pool;
        const int index = worker->index;
        lock.unlock();
        pool->worker_main(index);
        t_pool = nullptr;
        t_index = -1;
        lock.lock();
        worker->pool = nullptr;
        worker->changed.notify_all();
    }
}

TaskPool::TaskPool(int threads) : m_outer_pool(t_pool), m_outer_index(t_index)
{
    t_pool = this;
    t_index = 0;
    try {
        for (int i = 1; i < threads; ++i) {
            Worker* w = parked_workers().take(&TaskPool::worker_loop);
            m_workers.push_back(w);
            {
                std::lock_guard<std::mutex> lock(w->mutex);
                w->pool = this;
                w->index = i;
            }
            w->changed.notify_all();
        }
    } catch (...) { // no thread could be started: give back those lent so far
        release_workers();
        t_pool = m_outer_pool;
        t_index = m_outer_index;
        throw;
    }
}

TaskPool::~TaskPool()
{
    release_workers();
    t_pool = m_outer_pool;
    t_index = m_outer_index;
}

// Stops the pool, waits until each lent worker has left worker_main, and parks them.
void TaskPool::release_workers() noexcept
{
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_work.notify_all();
    for (Worker* w : m_workers) {
        std::unique_lock<std::mutex> lock(w->mutex);
        w->changed.wait(lock, [w] { return w->pool == nullptr; });
    }
    for (Worker* w : m_workers) parked_workers().park(w);
    m_workers.clear();
}

int TaskPool::worker_index() const { return t_pool == this ? t_index : -1; }

void TaskPool::spawn(TaskGroup& group, std::function<void()> task)
{
    bool waiters = false;
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        ++group.pending;
        m_queue.push_back(Task{&group, std::move(task)});
        waiters = m_waiting > 0;
    }
    m_work.notify_one();
    if (waiters) m_progress.notify_one();
}

// Runs with the lock released; takes it again to account for the task.
void TaskPool::run_task(Task& task, std::unique_lock<std::mutex>& lock)
{
    lock.unlock();
    std::exception_ptr error;
    try {
        task.run();
    } catch (...) {
        error = std::current_exception();
    }
    task.run = nullptr; // release captures outside the lock
    lock.lock();
    if (error && !task.group->error) task.group->error = error;
    // Only waiting threads care that a group finished; idle workers sleep on.
    if (--task.group->pending == 0) {
        if (m_waiting > 0) m_progress.notify_all();
        if (m_waiting_own > 0) m_group_done.notify_all();
    }
}

void TaskPool::wait(TaskGroup& group) { join(group, false); }

// The queued task a thread joining `group` runs next, or m_queue.end(). Any task: the newest,
// the smallest and the most likely to be this thread's own child, still warm in its cache.
// Own tasks: the group's newest (the queue is short: tasks are taken as they come).
std::deque<TaskPool::Task>::iterator TaskPool::next_task_for(const TaskGroup& group, bool own_tasks_only)
{
    if (!own_tasks_only) return m_queue.empty() ? m_queue.end() : std::prev(m_queue.end());
    for (auto it = m_queue.end(); it != m_queue.begin();)
        if ((--it)->group == &group) return it;
    return m_queue.end();
}

void TaskPool::join(TaskGroup& group, bool own_tasks_only)
{
    std::unique_lock<std::mutex> lock(m_mutex);
    while (group.pending > 0) {
        const auto next = next_task_for(group, own_tasks_only);
        if (next != m_queue.end()) {
            Task task = std::move(*next);
            m_queue.erase(next);
            run_task(task, lock);
            continue;
        }
        int& sleepers = own_tasks_only ? m_waiting_own : m_waiting;
        ++sleepers;
        (own_tasks_only ? m_group_done : m_progress).wait(lock);
        --sleepers;
    }
    if (group.error) {
        std::exception_ptr error = group.error;
        group.error = nullptr;
        std::rethrow_exception(error);
    }
}

void TaskPool::worker_main(int index)
{
    t_pool = this;
    t_index = index;
    std::unique_lock<std::mutex> lock(m_mutex);
    for (;;) {
        if (!m_queue.empty()) {
            // Oldest first: idle workers take the largest pending subtrees.
            Task task = std::move(m_queue.front());
            m_queue.pop_front();
            run_task(task, lock);
        } else if (m_stop) {
            return;
        } else {
            m_work.wait(lock);
        }
    }
}

}  // namespace gc
