#include "host/bvh/task_pool.h"

namespace gc {
namespace {

// Which pool the current thread serves, and as which worker (see worker_index()).
thread_local const TaskPool* t_pool = nullptr;
thread_local int t_index = -1;

}  // namespace

TaskPool::TaskPool(int threads) : m_outer_pool(t_pool), m_outer_index(t_index)
{
    t_pool = this;
    t_index = 0;
    for (int i = 1; i < threads; ++i) m_workers.emplace_back([this, i] { worker_main(i); });
}

TaskPool::~TaskPool()
{
    {
        std::lock_guard<std::mutex> lock(m_mutex);
        m_stop = true;
    }
    m_work.notify_all();
    for (std::thread& t : m_workers) t.join();
    t_pool = m_outer_pool;
    t_index = m_outer_index;
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
    // Only threads in wait() care that a group finished; idle workers sleep on.
    if (--task.group->pending == 0 && m_waiting > 0) m_progress.notify_all();
}

void TaskPool::wait(TaskGroup& group)
{
    std::unique_lock<std::mutex> lock(m_mutex);
    while (group.pending > 0) {
        if (!m_queue.empty()) {
            // Newest first: the most recently spawned task is the smallest and the most
            // likely to be this thread's own child, still warm in its cache.
            Task task = std::move(m_queue.back());
            m_queue.pop_back();
            run_task(task, lock);
        } else {
            ++m_waiting;
            m_progress.wait(lock);
            --m_waiting;
        }
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
