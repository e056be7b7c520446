/*
 * shade.cl — one path vertex per queued path: gc_shade_vertex (kernels/shared/
 * gc_path_vertex.h, shared with the Vulkan compute reference) does the shading; this kernel
 * only moves its result into the wavefront's queues.
 */
#include "gc_path_vertex.h"

__kernel void shade(const GcRenderParams params,
                    GC_SHADE_PARAMS,
                    __global GcRay* rays,
                    __global const GcHit* hits,
                    __global GcPathState* paths,
                    __global const uint* queue_in,
                    __global uint* queue_out,
                    __global GcShadowRay* shadow_rays,
                    __global uint* counters,
                    const uint counter_in,
                    const uint counter_out)
{
    const uint q = get_global_id(0);
    if (q >= counters[counter_in] || q >= gc_pass_paths(params)) return;
    const uint slot = queue_in[q];
    const GcVertexResult res = gc_shade_vertex(GC_SHADE_ARGS, params, paths[slot], rays[slot], hits[slot]);
    paths[slot] = res.path;
    if ((res.flags & GC_VERTEX_SHADOW) != 0u) {
        GcShadowRay sr = res.shadow;
        sr.slot = slot;
        shadow_rays[atomic_inc(&counters[GC_COUNTER_SHADOW])] = sr;
    }
    if ((res.flags & GC_VERTEX_CONTINUE) != 0u) {
        rays[slot] = res.next;
        queue_out[atomic_inc(&counters[counter_out])] = slot;
    }
}
