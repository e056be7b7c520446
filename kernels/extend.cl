/* extend.cl — closest hit for every queued ray, alpha-MASK cut-outs skipped (gc_alpha.h). */
#include "gc_alpha.h"
#include "gc_traverse.h"

__kernel void extend(const GcRenderParams params,
                     GC_BVH_PARAMS,
                     __global const GcRay* rays,
                     __global GcHit* hits,
                     __global const uint* ray_queue,
                     __global const uint* counters,
                     const uint queue_counter)
{
    const uint q = get_global_id(0);
    if (q >= counters[queue_counter] || q >= gc_pass_paths(params)) return;
    const uint slot = ray_queue[q];
    hits[slot] = gc_trace_closest(GC_BVH_ARGS, rays[slot]);
}
