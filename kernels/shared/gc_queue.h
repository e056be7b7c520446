/*
 * gc_queue.h — pushing onto the wavefront's global queues with one global atomic per
 * work-group and queue instead of one per work-item (OpenCL C only).
 *
 * Why: on PoCL a push straight to the global counter is a `lock xadd` on the one cache line
 * that all cores hammer, a large share of the CPU shade kernel's time
 * (docs/decisions/pocl-hot-spots.md). Here the work-items of a group count their pushes in
 * local memory (a cache line only the core running the group touches), one work-item
 * reserves the group's range with a single global atomic_add, and each work-item writes at
 * base + its rank in the group. On NVIDIA it makes no difference: its compiler already
 * merges same-address atomics per warp.
 *
 * The ranks within a group follow local atomics, so queue order is not fixed; the image does
 * not depend on it (see wavefront.cl).
 *
 * Every work-item of the group must call gc_queue_reserve2 (it has barriers): kernels keep
 * their idle work-items alive with push = false instead of returning early. The local
 * counters must be declared at kernel scope (OpenCL C) and passed in; call it once per
 * kernel, or put a barrier between calls (a second call's reset of the counters could
 * overtake the first call's last reads; shade.cl's loop does this).
 */
#ifndef GC_QUEUE_H
#define GC_QUEUE_H

/* Where this work-item writes in each queue. */
typedef struct {
    uint first;  /* index in queue 0 to write, valid when push0 */
    uint second; /* index in queue 1 to write, valid when push1 */
} GcQueueSlots;

/* The group's share of two queues. counts[q] first counts the group's pushes onto queue q,
 * then holds the base index that the global atomic returned. */
static inline GcQueueSlots gc_queue_reserve2(__global uint* counter0, bool push0,
                                             __global uint* counter1, bool push1,
                                             __local uint* counts /* [2] */)
{
    const bool leader = get_local_id(0) == 0;
    if (leader) {
        counts[0] = 0u;
        counts[1] = 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    GcQueueSlots rank;
    rank.first = push0 ? atomic_inc(&counts[0]) : 0u;
    rank.second = push1 ? atomic_inc(&counts[1]) : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (leader) {
        /* A group with nothing to push skips the global atomic altogether. */
        counts[0] = counts[0] != 0u ? atomic_add(counter0, counts[0]) : 0u;
        counts[1] = counts[1] != 0u ? atomic_add(counter1, counts[1]) : 0u;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    rank.first += counts[0];
    rank.second += counts[1];
    return rank;
}

#endif
