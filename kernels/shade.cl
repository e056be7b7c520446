/*
 * shade.cl — one path vertex per queued path: gc_shade_vertex (kernels/shared/
 * gc_path_vertex.h, shared with the Vulkan compute reference; gc_shade_scene_vertex, which
 * is it for a flat scene, also shades an instanced one's hits) does the shading; this kernel
 * only moves its result into the wavefront's queues, one global atomic per work-group and
 * queue (gc_queue.h). Work-items past the queue's end stay for the group's barriers.
 * A launch may hold fewer work-items than the queue: each group then takes further steps
 * of the whole launch's width (wavefront_launches.h).
 */
#include "gc_path_vertex.h"
#include "gc_queue.h"
#include "gc_scene_trace.h"

__kernel void shade(const GcRenderParams params,
                    GC_INSTANCES_FIRST_PARAMS GC_SHADE_PARAMS,
                    __global GcRay* rays,
                    __global const GcSceneHit* hits,
                    __global GcPathState* paths,
                    __global const uint* queue_in,
                    __global uint* queue_out,
                    __global GcShadowRay* shadow_rays,
                    __global uint* counters,
                    const uint counter_in,
                    const uint counter_out)
{
    __local uint group_counts[2];
    GC_INSTANCES_FIRST_UNUSED();
    const uint count = min(counters[counter_in], gc_pass_paths(params));
    /* Grid-stride, as in extend.cl, in steps the whole group takes together (base is the same
     * for all its work-items), because gc_queue_reserve2 has barriers. */
    for (uint base = get_group_id(0) * get_local_size(0); base < count; base += get_global_size(0)) {
        const uint q = base + get_local_id(0);
        const bool queued = q < count;
        uint slot = 0u;
        uint flags = 0u;
        GcShadowRay shadow;
        if (queued) {
            slot = queue_in[q];
            const GcSceneHit hit = hits[slot];
            const GcVertexResult res = gc_shade_scene_vertex(params, paths[slot], rays[slot], hit);
            paths[slot] = res.path;
            flags = res.flags;
            shadow = res.shadow;
            shadow.slot = slot;
            /* The extend stage has read this slot's ray already; nobody else touches it. */
            if ((flags & GC_VERTEX_CONTINUE) != 0u) rays[slot] = res.next;
        }
        const bool shadow_push = (flags & GC_VERTEX_SHADOW) != 0u;
        const bool continue_push = (flags & GC_VERTEX_CONTINUE) != 0u;
        const GcQueueSlots at = gc_queue_reserve2(&counters[GC_COUNTER_SHADOW], shadow_push,
                                                  &counters[counter_out], continue_push, group_counts);
        if (shadow_push) shadow_rays[at.first] = shadow;
        if (continue_push) queue_out[at.second] = slot;
        /* The next step's reset of group_counts must wait for every work-item's read above. */
        barrier(CLK_LOCAL_MEM_FENCE);
    }
}
