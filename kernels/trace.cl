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
    float ox[8], oy[8], oz[8], dx[8], dy[8], dz[8], tmin[8], tmax[8];
    int on[8];
    for (uint k = 0u; k < 8u; ++k) {
        const GcRay r = rays[8u * i + k];
        ox[k] = r.org_tmin.x; oy[k] = r.org_tmin.y; oz[k] = r.org_tmin.z; tmin[k] = r.org_tmin.w;
        dx[k] = r.dir_tmax.x; dy[k] = r.dir_tmax.y; dz[k] = r.dir_tmax.z; tmax[k] = r.dir_tmax.w;
        on[k] = active[8u * i + k] != 0 ? -1 : 0;
    }
    GcRays8 packet;
    packet.ox = vload8(0, ox); packet.oy = vload8(0, oy); packet.oz = vload8(0, oz);
    packet.dx = vload8(0, dx); packet.dy = vload8(0, dy); packet.dz = vload8(0, dz);
    packet.tmin = vload8(0, tmin);
    packet.tmax = vload8(0, tmax);
    packet.active = vload8(0, on);
    const GcHits8 h = gc_trace_closest8(nodes, tris, packet);
    float t[8], u[8], v[8];
    uint prim[8];
    vstore8(h.t, 0, t); vstore8(h.u, 0, u); vstore8(h.v, 0, v); vstore8(h.prim, 0, prim);
    for (uint k = 0u; k < 8u; ++k) {
        GcHit hit;
        hit.t = t[k];
        hit.u = u[k];
        hit.v = v[k];
        hit.prim = prim[k];
        hits[8u * i + k] = hit;
    }
}
#endif
