/* extend.cl — closest hit for every queued ray, alpha-MASK cut-outs skipped (gc_alpha.h); in
 * an instanced scene through the two-level BVH, with the instance beside the hit
 * (gc_scene_trace.h). */
#include "gc_scene_trace.h"

__kernel void extend(const GcRenderParams params,
                     GC_INSTANCES_FIRST_PARAMS GC_BVH_PARAMS,
                     __global const GcRay* rays,
                     __global GcSceneHit* hits,
                     __global const uint* ray_queue,
                     __global const uint* counters,
                     const uint queue_counter)
{
    const uint count = min(counters[queue_counter], gc_pass_paths(params));
    /* Grid-stride: a GPU launch may hold fewer work-items than the queue
     * (wavefront_launches.h); where the host launches one per entry this runs once. */
    for (uint q = get_global_id(0); q < count; q += get_global_size(0)) {
        const uint slot = ray_queue[q];
        hits[slot] = gc_scene_closest(rays[slot]);
    }
}
