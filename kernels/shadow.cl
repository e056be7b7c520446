/* shadow.cl — visibility of every queued next-event-estimation ray; unoccluded ones add
 * their contribution to their path. At most one shadow ray per path is in flight, so the
 * read-modify-write of the path's radiance is race-free. Alpha-MASK cut-outs let the ray
 * through (gc_alpha.h). */
#include "gc_scene_trace.h"

__kernel void shadow(const GcRenderParams params,
                     GC_INSTANCES_FIRST_PARAMS GC_BVH_PARAMS,
                     __global const GcShadowRay* shadow_rays,
                     __global GcPathState* paths,
                     __global const uint* counters)
{
    const uint count = min(counters[GC_COUNTER_SHADOW], gc_pass_paths(params));
    /* Grid-stride, as in extend.cl. */
    for (uint q = get_global_id(0); q < count; q += get_global_size(0)) {
        const GcShadowRay s = shadow_rays[q];
        if (!gc_scene_occluded(s.ray)) paths[s.slot].radiance += s.contribution;
    }
}
