/* shadow.cl — visibility of every queued next-event-estimation ray; unoccluded ones add
 * their contribution to their path. At most one shadow ray per path is in flight, so the
 * read-modify-write of the path's radiance is race-free. Alpha-MASK cut-outs let the ray
 * through (gc_alpha.h). */
#include "gc_alpha.h"
#include "gc_traverse.h"

__kernel void shadow(const GcRenderParams params,
                     GC_BVH_PARAMS,
                     __global const GcShadowRay* shadow_rays,
                     __global GcPathState* paths,
                     __global const uint* counters)
{
    const uint q = get_global_id(0);
    if (q >= counters[GC_COUNTER_SHADOW] || q >= gc_pass_paths(params)) return;
    const GcShadowRay s = shadow_rays[q];
    if (!gc_trace_any(GC_BVH_ARGS, s.ray)) paths[s.slot].radiance += s.contribution;
}
