/*
 * gc_traverse.h — stack-based BVH2 traversal, closest hit and any hit, over the flat layout
 * of gc_types.h: GcBvhNode[] (inner node: children nodes[first], nodes[first + 1]; leaf:
 * tris[first .. first + count); count == 0 marks an inner node) and GcTriangle[] in leaf
 * order (v0.w holds the scene triangle index). The same body runs in the OpenCL kernels, in
 * the host reference (host/bvh/traverse_host.cpp) and in GLSL (kernels/vk). Programs built
 * for CPUs get the BVH4 body of gc_traverse4.h (-D GC_BVH_WIDE) or the BVH8 body of
 * gc_traverse8.h (-D GC_BVH_WIDE -D GC_BVH_WIDE8) instead, with the same results; the
 * buffer types then change (GcTraversalNode and GcTraversalTriangle in gc_types.h name
 * whichever layout is compiled).
 *
 * Buffers come in as GC_BVH_PARAMS / GC_BVH_ARGS and are read through GC_BVH_NODE(i) and
 * GC_BVH_TRI(i), so the body does not care whether they are pointers or shader-storage
 * globals; gc_scene_buffers.h generates all four from the one list of scene buffers (GLSL:
 * a dummy parameter and the SSBOs of kernels/vk/scene_bindings.glsl).
 *
 * Conventions the host builder (host/bvh) guarantees and this code relies on:
 *   - node 0 is the root; the tree is at most GC_BVH_MAX_DEPTH levels deep, so the ordered
 *     traversal never holds more than GC_BVH_STACK_SIZE deferred nodes (a full stack drops
 *     the node instead of writing out of bounds — it cannot happen with a conforming BVH);
 *   - the empty scene is one leaf with empty bounds lo = +inf, hi = -inf, first = 0,
 *     count = 1, over one dummy triangle with all three vertices at the origin and scene
 *     index GC_INVALID. The box test misses such bounds for every valid ray, and even if it
 *     did not, the dummy has zero area (det == 0) and is never hit: both buffers stay
 *     non-empty (OpenCL has no zero-sized buffers) and every read stays in bounds.
 *
 * Tie rule: when two triangles are hit at exactly the same t, the closest hit is the one
 * with the smaller scene triangle index. Each triangle's t is a pure function of the ray and
 * its vertices, and the choice is the minimum of (t, index) in lexicographic order, so the
 * result does not depend on the traversal order or on the BVH's shape: it equals a brute-
 * force loop over all triangles (trace_brute_force on the host checks exactly this). Boxes
 * are pruned with `entry <= t_best` (widened, see gc_intersect.h), never `<`, so a box that
 * may hold an equal-t triangle with a smaller index is still opened.
 *
 * Misses: prim == GC_INVALID, t == +inf, u == v == 0. Invalid rays (NaN, zero direction,
 * t_min > t_max) miss.
 *
 * Alpha test (glTF alphaMode MASK): a triangle whose GcTriangle flags carry
 * GC_TRI_ALPHA_TESTED is a candidate only where GC_ALPHA_TEST(scene_tri, u, v) is true
 * (solid); a candidate that fails is ignored by closest and any hit alike, as if the ray had
 * missed it. The traversal takes the alpha test's buffers after the BVH's (the scene-buffer
 * group trace). A program (or host translation unit) that defines GC_TRACE_OPAQUE before
 * its includes — trace.cl, the probes, the host's plain reference — gets the traversal of
 * opaque triangles instead: the BVH buffers only, and no test compiled at all. It is a mode
 * of the whole program, like GC_BVH_WIDE, so no header's include order decides it.
 * Whether a triangle is solid at (u, v) is a pure function of the triangle, so the tie rule
 * and the brute-force equality above still hold (the brute force applies the same test).
 */
#ifndef GC_TRAVERSE_H
#define GC_TRAVERSE_H

#include "gc_scene_buffers.h"
#if !defined(GC_TRACE_OPAQUE)
#include "gc_alpha.h"
#define GC_ALPHA_TEST(scene_tri, u, v) gc_alpha_solid(GC_ALPHA_ARGS, scene_tri, u, v)
#endif
#include "gc_intersect.h"

/* Private stack: 64 node indices plus their entry distances (512 bytes). */
#define GC_BVH_STACK_SIZE 64u
/* Deepest tree the builder may emit (root at depth 0); ordered traversal defers at most one
 * node per level below the root, so depth <= stack size is enough. */
#define GC_BVH_MAX_DEPTH 64u

#if defined(GC_BVH_WIDE8)
/* CPUs with 8-wide SIMD: the BVH8 layout's gc_trace_wide. */
#include "gc_traverse8.h"
#elif defined(GC_BVH_WIDE)
/* CPUs: the BVH4 layout's gc_trace_wide. */
#include "gc_traverse4.h"
#else

GC_NAMESPACE_BEGIN

/* One body for both queries: any_hit returns at the first accepted triangle. */
GC_FUNC GcHit gc_trace_impl(GC_BVH_PARAMS, GcRay ray, bool any_hit)
{
    GcHit best = gc_no_hit();
    if (!gc_ray_is_valid(ray)) return best;

    GcRayPre r = gc_ray_precompute(ray);
    /* Hits are accepted up to t_best, inclusive; (t_best, best.prim) is the running minimum. */
    float t_best = gc_ray_tmax(ray);

    uint stack_node[GC_BVH_STACK_SIZE];
    float stack_entry[GC_BVH_STACK_SIZE];
    uint sp = 0u;

    GcBvhNode node = GC_BVH_NODE(0u);
    /* Every box below the root holds only triangles inside the root: one margin serves all. */
    r = gc_ray_with_margin(r, GC_XYZ(node.lo), GC_XYZ(node.hi));
    if (!(gc_intersect_aabb_pre(r, t_best, GC_XYZ(node.lo), GC_XYZ(node.hi)) < GC_AABB_MISS)) return best;

    for (;;) {
        if (gc_node_is_leaf(node)) {
            uint first = gc_node_first(node);
            uint end = first + gc_node_count(node);
            for (uint i = first; i < end; ++i) {
                GcTriangle tri = GC_BVH_TRI(i);
                GcHit h = gc_intersect_triangle(r, GC_XYZ(tri.v0), GC_XYZ(tri.v1), GC_XYZ(tri.v2), t_best);
                if (h.prim == GC_INVALID) continue;
                uint prim = gc_triangle_prim(tri);
                if (prim == GC_INVALID) continue; /* the empty scene's dummy */
#if defined(GC_ALPHA_TEST)
                if ((gc_triangle_flags(tri) & GC_TRI_ALPHA_TESTED) != 0u && !(GC_ALPHA_TEST(prim, h.u, h.v))) continue;
#endif
                if (h.t < t_best || prim < best.prim) {
                    /* h.t <= t_best here, so this is lexicographic (t, prim) order. */
                    best = h;
                    best.prim = prim;
                    t_best = h.t;
                    if (any_hit) return best;
                }
            }
        } else {
            uint first = gc_node_first(node);
            GcBvhNode c0 = GC_BVH_NODE(first);
            GcBvhNode c1 = GC_BVH_NODE(first + 1u);
            float e0 = gc_intersect_aabb_pre(r, t_best, GC_XYZ(c0.lo), GC_XYZ(c0.hi));
            float e1 = gc_intersect_aabb_pre(r, t_best, GC_XYZ(c1.lo), GC_XYZ(c1.hi));
            bool hit0 = e0 < GC_AABB_MISS;
            bool hit1 = e1 < GC_AABB_MISS;
            if (hit0 && hit1) {
                /* Near child first; the far one waits with its entry distance. */
                bool swap = e1 < e0;
                node = swap ? c1 : c0;
                if (sp < GC_BVH_STACK_SIZE) {
                    stack_node[sp] = swap ? first : first + 1u;
                    stack_entry[sp] = swap ? e0 : e1;
                    ++sp;
                }
                continue;
            }
            if (hit0 || hit1) {
                node = hit0 ? c0 : c1;
                continue;
            }
        }
        /* Pop the nearest deferred node that can still beat t_best. */
        bool found = false;
        while (sp > 0u && !found) {
            --sp;
            found = gc_aabb_entry_within(stack_entry[sp], t_best);
        }
        if (!found) break;
        node = GC_BVH_NODE(stack_node[sp]);
    }
    return best;
}

GC_NAMESPACE_END
#endif /* GC_BVH_WIDE */

GC_NAMESPACE_BEGIN

/* The layout's body: the wide ones take the ray as two float4s (see gc_traverse4.h). */
#if defined(GC_BVH_WIDE)
#define GC_TRACE_BODY(ray, any_hit) gc_trace_wide(GC_BVH_ARGS, (ray).org_tmin, (ray).dir_tmax, any_hit)
#else
#define GC_TRACE_BODY(ray, any_hit) gc_trace_impl(GC_BVH_ARGS, ray, any_hit)
#endif

/* Closest hit in [t_min, t_max]; ties in t go to the smaller scene triangle index. */
GC_FUNC GcHit gc_trace_closest(GC_BVH_PARAMS, GcRay ray)
{
    return GC_TRACE_BODY(ray, false);
}

/* True when any triangle is hit in [t_min, t_max] (shadow rays). */
GC_FUNC bool gc_trace_any(GC_BVH_PARAMS, GcRay ray)
{
    return GC_TRACE_BODY(ray, true).prim != GC_INVALID;
}

GC_NAMESPACE_END

#endif /* GC_TRAVERSE_H */
