/*
 * queue_probe.cl — exercises gc_queue.h's work-group reservation the way shade.cl uses it:
 * work-item i (of a range rounded up to whole groups) pushes i onto queue 0 when i % 3 == 0
 * and onto queue 1 when i % 5 == 0, for i < count only. Tests check that each queue then
 * holds exactly those items once each, whatever the group size and however the groups ran.
 */
#include "gc_queue.h"

__kernel void queue_probe(__global uint* queue0, __global uint* queue1, __global uint* counters, const uint count)
{
    __local uint group_counts[2];
    const uint i = get_global_id(0);
    const bool live = i < count;
    const bool push0 = live && i % 3u == 0u;
    const bool push1 = live && i % 5u == 0u;
    const GcQueueSlots at = gc_queue_reserve2(&counters[0], push0, &counters[1], push1, group_counts);
    if (push0) queue0[at.first] = i;
    if (push1) queue1[at.second] = i;
}
