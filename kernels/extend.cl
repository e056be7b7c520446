/* extend.cl — closest hit for every queued ray, alpha-MASK cut-outs skipped (gc_alpha.h). */
#include "gc_alpha.h"
#include "gc_traverse.h"

__kernel void extend(const GcRenderParams params,
                     __global const GcTraversalNode* nodes,
                     __global const GcTraversalTriangle* tris,
                     __global const GcTriangleAttribs* attribs,
                     __global const GcMaterial* materials,
                     __global const GcTexture* textures,
                     __global const uint* texels,
                     __global const GcRay* rays,
                     __global GcHit* hits,
                     __global const uint* ray_queue,
                     __global const uint* counters,
                     const uint queue_counter)
{
    const uint q = get_global_id(0);
    if (q >= counters[queue_counter] || q >= gc_pass_paths(params)) return;
    const uint slot = ray_queue[q];
    hits[slot] = gc_trace_closest(nodes, tris, GC_ALPHA_ARGS, rays[slot]);
}
