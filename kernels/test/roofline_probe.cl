/*
 * roofline_probe.cl — what one unit of BVH2 traversal compiles to on a GPU, for the
 * instruction half of geocold-bench's GPU roofline (tools/bench/issue_roofline.h). Never
 * launched: the bench only builds it and reads the driver's PTX.
 *
 * Each unit comes as two kernels, one doing it once and one doing it twice on other data.
 * Both load the same inputs and store the same number of results, so the difference of their
 * instruction counts is the unit's cost alone, without the kernel's prologue and I/O. The
 * units call what gc_trace_impl's loop calls (gc_traverse.h), with its glue:
 *   setup     per ray: validity, the precomputed ray, the root's margin and box test;
 *   inner     per inner node: its two children's box tests, the near one taken, the far
 *             one pushed with its entry;
 *   triangle  per triangle: the watertight test and the (t, prim) acceptance.
 * Every unit returns what the loop would go on to use, so the compiler keeps all of it.
 * Built with the BVH2 layout's options only (no GC_BVH_WIDE), opaque triangles only.
 */
#define GC_TRACE_OPAQUE 1
#include "gc_traverse.h"

/* The traversal of ray `rays[k]` up to its first node: the ray precomputed with the root's
 * margin, and the root's entry (GC_AABB_MISS for an invalid ray). */
float16 gc_probe_setup(__global const GcBvhNode* nodes, __global const GcRay* rays, uint k)
{
    const GcRay ray = rays[k];
    if (!gc_ray_is_valid(ray)) return (float16)(GC_AABB_MISS);
    GcRayPre r = gc_ray_precompute(ray);
    const GcBvhNode root = nodes[0];
    r = gc_ray_with_margin(r, GC_XYZ(root.lo), GC_XYZ(root.hi));
    const float entry = gc_intersect_aabb_pre(r, gc_ray_tmax(ray), GC_XYZ(root.lo), GC_XYZ(root.hi));
    float16 out;
    out.s0123 = r.org;
    out.s4567 = r.dir;
    out.s89ab = r.inv_dir;
    out.scdef = r.shear;
    /* kz takes inv_dir.w's slot and the root's entry the margin's: those two feed the entry,
     * so their work stays in, and kx, ky follow from kz (gc_ray_precompute). */
    out.sb = as_float(r.kz);
    out.sf = entry;
    return out;
}

/* One inner node, children nodes[first] and nodes[first + 1]: x = the next node's first
 * (or GC_INVALID), y = the pushed child, z = its entry, w = 1 when something was pushed. */
float4 gc_probe_inner(__global const GcBvhNode* nodes, const GcRayPre r, float t_best, uint first)
{
    const GcBvhNode c0 = nodes[first];
    const GcBvhNode c1 = nodes[first + 1u];
    const float e0 = gc_intersect_aabb_pre(r, t_best, GC_XYZ(c0.lo), GC_XYZ(c0.hi));
    const float e1 = gc_intersect_aabb_pre(r, t_best, GC_XYZ(c1.lo), GC_XYZ(c1.hi));
    const bool hit0 = e0 < GC_AABB_MISS;
    const bool hit1 = e1 < GC_AABB_MISS;
    if (hit0 && hit1) {
        const bool swap = e1 < e0;
        const GcBvhNode taken = swap ? c1 : c0;
        return (float4)(as_float(gc_node_first(taken)), as_float(swap ? first : first + 1u), swap ? e0 : e1, 1.0f);
    }
    if (hit0 || hit1) return (float4)(as_float(gc_node_first(hit0 ? c0 : c1)), 0.0f, 0.0f, 0.0f);
    return (float4)(as_float(GC_INVALID), 0.0f, 0.0f, 0.0f);
}

/* One triangle against the best hit so far (t_best, prim): the new best as (t, u, v, prim). */
float4 gc_probe_triangle(__global const GcTriangle* tris, const GcRayPre r, float t_best, uint best_prim, uint i)
{
    const GcTriangle tri = tris[i];
    const GcHit h = gc_intersect_triangle(r, GC_XYZ(tri.v0), GC_XYZ(tri.v1), GC_XYZ(tri.v2), t_best);
    const uint prim = gc_triangle_prim(tri);
    if (h.prim == GC_INVALID || prim == GC_INVALID) return (float4)(t_best, 0.0f, 0.0f, as_float(best_prim));
    if (h.t < t_best || prim < best_prim) return (float4)(h.t, h.u, h.v, as_float(prim));
    return (float4)(t_best, 0.0f, 0.0f, as_float(best_prim));
}

/* The precomputed ray the inner and triangle units start from, as the loop holds it (the
 * kernels below pass its t_max as the best t so far). */
GcRayPre gc_probe_ray(__global const float4* pre, uint k)
{
    GcRayPre r;
    r.org = pre[4u * k];
    r.dir = pre[4u * k + 1u];
    r.inv_dir = pre[4u * k + 2u];
    r.shear = pre[4u * k + 3u];
    r.kz = as_uint(r.inv_dir.w) & 3u; /* inv_dir.w is the set-up's only: no unit below reads it */
    r.kx = r.kz == 2u ? 0u : r.kz + 1u;
    r.ky = r.kx == 2u ? 0u : r.kx + 1u;
    r.pad = 0u;
    return r;
}

__kernel void probe_setup_x1(__global const GcBvhNode* nodes, __global const GcRay* rays, __global float16* out)
{
    const uint i = get_global_id(0);
    out[2u * i] = gc_probe_setup(nodes, rays, 2u * i);
    out[2u * i + 1u] = (float16)(0.0f);
}

__kernel void probe_setup_x2(__global const GcBvhNode* nodes, __global const GcRay* rays, __global float16* out)
{
    const uint i = get_global_id(0);
    out[2u * i] = gc_probe_setup(nodes, rays, 2u * i);
    out[2u * i + 1u] = gc_probe_setup(nodes, rays, 2u * i + 1u);
}

__kernel void probe_inner_x1(__global const GcBvhNode* nodes, __global const float4* pre, __global const uint* next,
                             __global float4* out)
{
    const uint i = get_global_id(0);
    const GcRayPre r = gc_probe_ray(pre, i);
    out[2u * i] = gc_probe_inner(nodes, r, r.dir.w, next[2u * i]);
    out[2u * i + 1u] = (float4)(0.0f);
}

__kernel void probe_inner_x2(__global const GcBvhNode* nodes, __global const float4* pre, __global const uint* next,
                             __global float4* out)
{
    const uint i = get_global_id(0);
    const GcRayPre r = gc_probe_ray(pre, i);
    out[2u * i] = gc_probe_inner(nodes, r, r.dir.w, next[2u * i]);
    out[2u * i + 1u] = gc_probe_inner(nodes, r, r.dir.w, next[2u * i + 1u]);
}

__kernel void probe_triangle_x1(__global const GcTriangle* tris, __global const float4* pre,
                                __global const uint* next, __global float4* out)
{
    const uint i = get_global_id(0);
    const GcRayPre r = gc_probe_ray(pre, i);
    out[2u * i] = gc_probe_triangle(tris, r, r.dir.w, GC_INVALID, next[2u * i]);
    out[2u * i + 1u] = (float4)(0.0f);
}

__kernel void probe_triangle_x2(__global const GcTriangle* tris, __global const float4* pre,
                                __global const uint* next, __global float4* out)
{
    const uint i = get_global_id(0);
    const GcRayPre r = gc_probe_ray(pre, i);
    out[2u * i] = gc_probe_triangle(tris, r, r.dir.w, GC_INVALID, next[2u * i]);
    out[2u * i + 1u] = gc_probe_triangle(tris, r, r.dir.w, GC_INVALID, next[2u * i + 1u]);
}
