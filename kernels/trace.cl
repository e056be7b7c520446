/*
 * trace.cl — traversal as a service: closest or any hit for a buffer of rays. Used by the
 * device-vs-host traversal tests and by geocold-bench's ray-throughput figures; the
 * integrators call the same gc_trace_* functions inline.
 */
#include "gc_traverse.h"

__kernel void trace_closest(__global const GcTraversalNode* nodes,
                            __global const GcTraversalTriangle* tris,
                            __global const GcRay* rays,
                            __global GcHit* hits,
                            const uint count)
{
    const uint i = get_global_id(0);
    if (i >= count) return;
    hits[i] = gc_trace_closest(nodes, tris, rays[i]);
}

__kernel void trace_any(__global const GcTraversalNode* nodes,
                        __global const GcTraversalTriangle* tris,
                        __global const GcRay* rays,
                        __global uint* occluded,
                        const uint count)
{
    const uint i = get_global_id(0);
    if (i >= count) return;
    occluded[i] = gc_trace_any(nodes, tris, rays[i]) ? 1u : 0u;
}
