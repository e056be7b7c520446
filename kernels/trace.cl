/*
 * trace.cl — traversal as a service: closest or any hit for a buffer of rays. Used by the
 * device-vs-host traversal tests and by geocold-bench's ray-throughput figures; the
 * integrators call the same gc_trace_* functions inline. Every triangle is opaque here (no
 * alpha-MASK test), so the kernels take the BVH's two buffers only.
 */
#define GC_TRACE_OPAQUE 1
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

#include "gc_packet8.h"
#if defined(GC_HAVE_PACKET8)
/* Eight rays per work-item as one packet (gc_packet8.h): lane k of work-item i is ray
 * 8 i + k, traced where active[8 i + k] is non-zero; the other lanes get the miss record.
 * rays, active and hits hold 8 * packets entries. */
__kernel void trace_closest8(__global const GcTraversalNode* nodes,
                             __global const GcTraversalTriangle* tris,
                             __global const GcRay* rays,
                             __global const int* active,
                             __global GcHit* hits,
                             const uint packets)
{
    const uint i = get_global_id(0);
    if (i >= packets) return;
    GcRay ray[8];
    int on[8];
    GcHit hit[8];
    for (uint k = 0u; k < 8u; ++k) {
        ray[k] = rays[8u * i + k];
        on[k] = active[8u * i + k];
    }
    gc_packet_closest_hits8(nodes, tris, ray, on, hit);
    for (uint k = 0u; k < 8u; ++k) hits[8u * i + k] = hit[k];
}
#endif
