/*
 * gc_traverse4.h — gc_trace_wide over the BVH4 layout (GcBvh4Node, GcTriangle4 in
 * gc_types.h). gc_traverse.h includes it instead of its BVH2 loop when the program is built
 * with -D GC_BVH_WIDE, which the host does for CPUs without 8-wide SIMD; CPUs with AVX get
 * the BVH8 of gc_traverse8.h, which reuses this file's leaf test and helpers
 * (host/render/device_bvh.h chooses).
 *
 * Why a second layout: on a CPU, PoCL runs each work-item's traversal loop as scalar code (the
 * loop diverges from ray to ray, so it cannot be vectorised across work-items), and a BVH2
 * spends its time on one box or one triangle at a time. Here one ray tests four boxes, then
 * four triangles, with float4 arithmetic that the compiler maps to SSE/AVX lanes — the
 * single-ray scheme of Embree (Wald et al. 2014, "Embree: a kernel framework for efficient
 * CPU ray tracing"). GPUs keep the BVH2: there a float4 is four scalar instructions, and a
 * warp already runs 32 rays side by side.
 *
 * Same results as the BVH2, bit for bit. Each lane of gc_box4_entry performs exactly the
 * operations of gc_intersect_aabb_m, and each lane of gc_intersect_triangle4 those of
 * gc_intersect_triangle (same order, no contraction, correctly rounded division), so every
 * candidate gets the same t, u, v. The closest hit is the (t, scene index) minimum with the
 * tie rule of gc_traverse.h, which does not depend on the tree, and boxes are pruned with
 * the same widened `entry <= t_best`: the traversal equals the brute force, as the BVH2's
 * does (tests/bvh/traverse_test.cpp and wide_bvh_test.cpp on the host,
 * tests/render/device_kernels_test.cpp and alpha_mask_test.cpp on every device).
 *
 * OpenCL C and C++ only (the GLSL reference keeps the BVH2). The four-lane helpers below are
 * spelled once per dialect: OpenCL vector comparisons give int4 masks (-1 true, 0 false) and
 * select() picks per lane; the host uses glm's bvec4.
 */
#ifndef GC_TRAVERSE4_H
#define GC_TRAVERSE4_H

#include "gc_intersect.h"

/* Deferred children: each inner node visited on the way down defers at most three, and the
 * BVH4 is no deeper than the BVH2 it is collapsed from (GC_BVH_MAX_DEPTH). */
#define GC_BVH4_STACK_SIZE (3u * GC_BVH_MAX_DEPTH)

#if defined(GC_OPENCL)
#define GcMask4 int4
#define gc_splat4(x) ((float4)(x))
#define gc_lt4(a, b) ((a) < (b))
#define gc_le4(a, b) ((a) <= (b))
#define gc_ge4(a, b) ((a) >= (b))
#define gc_gt4(a, b) ((a) > (b))
#define gc_ne4u(a, b) ((a) != (b))
#define gc_and4(a, b) ((a) & (b))
#define gc_or4(a, b) ((a) | (b))
#define gc_select4(m, a, b) select((b), (a), (m))
#define gc_lane(m, c) ((m).c != 0)
/* any() of a comparison mask. Clang's or-reduction of the sign-extended mask compiles to
 * kmovd + test on AVX-512, where PoCL's any() moved the mask back into a vector and
 * or-ed its lanes through two shuffles (ten instructions per block)
 * (docs/decisions/bvh8-traversal-variants.md). Other compilers keep any(). */
#if defined(__clang__) && defined(__has_builtin)
#if __has_builtin(__builtin_reduce_or)
#define GC_HAVE_REDUCE_OR 1
#endif
#endif
#if defined(GC_HAVE_REDUCE_OR)
#define gc_any4(m) (__builtin_reduce_or(m) != 0)
#else
#define gc_any4(m) any(m)
#endif
#else
GC_NAMESPACE_BEGIN
using GcMask4 = glm::bvec4;
inline float4 gc_splat4(float x) { return float4(x); }
inline GcMask4 gc_lt4(float4 a, float4 b) { return glm::lessThan(a, b); }
inline GcMask4 gc_le4(float4 a, float4 b) { return glm::lessThanEqual(a, b); }
inline GcMask4 gc_ge4(float4 a, float4 b) { return glm::greaterThanEqual(a, b); }
inline GcMask4 gc_gt4(float4 a, float4 b) { return glm::greaterThan(a, b); }
inline GcMask4 gc_ne4u(uint4 a, uint4 b) { return glm::notEqual(a, b); }
inline GcMask4 gc_and4(GcMask4 a, GcMask4 b) { return {a.x && b.x, a.y && b.y, a.z && b.z, a.w && b.w}; }
inline GcMask4 gc_or4(GcMask4 a, GcMask4 b) { return {a.x || b.x, a.y || b.y, a.z || b.z, a.w || b.w}; }
inline float4 gc_select4(GcMask4 m, float4 a, float4 b) { return glm::mix(b, a, m); }
GC_NAMESPACE_END
#define gc_lane(m, c) ((m).c)
#define gc_any4(m) glm::any(m)
#endif

GC_NAMESPACE_BEGIN

/* gc_max_keep / gc_min_keep per lane: a NaN x is dropped, `running` kept. */
GC_FUNC float4 gc_max_keep4(float4 x, float4 running)
{
    return gc_select4(gc_gt4(x, running), x, running);
}

GC_FUNC float4 gc_min_keep4(float4 x, float4 running)
{
    return gc_select4(gc_lt4(x, running), x, running);
}

/* max(|a|, |b|) for the triangle test's noise floor. A NaN operand never reaches an accepted
 * lane (every sheared coordinate enters an edge function, and a NaN edge function fails the
 * inside test), and for the rest this is exactly fmax, without the NaN handling that costs
 * x86 two extra instructions per fmax. */
GC_FUNC float4 gc_abs_max4(float4 a, float4 b)
{
    float4 fa = fabs(a);
    float4 fb = fabs(b);
    return gc_select4(gc_gt4(fa, fb), fa, fb);
}

GC_FUNC float4 gc_max4(float4 a, float4 b)
{
    return gc_select4(gc_gt4(a, b), a, b);
}

/* gc_intersect_aabb_pre against the node's four child boxes: per lane the entry bound, or
 * GC_AABB_MISS. Empty slots have empty bounds and always miss. */
GC_FUNC float4 gc_box4_entry(GcRayPre r, float tmax, GcBvh4Node n)
{
    bool px = r.inv_dir.x >= 0.0f;
    bool py = r.inv_dir.y >= 0.0f;
    bool pz = r.inv_dir.z >= 0.0f;
    float4 nx = (px ? n.lo_x : n.hi_x) - r.org.x;
    float4 fx = (px ? n.hi_x : n.lo_x) - r.org.x;
    float4 ny = (py ? n.lo_y : n.hi_y) - r.org.y;
    float4 fy = (py ? n.hi_y : n.lo_y) - r.org.y;
    float4 nz = (pz ? n.lo_z : n.hi_z) - r.org.z;
    float4 fz = (pz ? n.hi_z : n.lo_z) - r.org.z;
    float4 tnear = gc_max_keep4(nz * r.inv_dir.z,
                                gc_max_keep4(ny * r.inv_dir.y, gc_max_keep4(nx * r.inv_dir.x, gc_splat4(r.org.w))));
    float4 tfar = gc_min_keep4(fz * r.inv_dir.z,
                               gc_min_keep4(fy * r.inv_dir.y, gc_min_keep4(fx * r.inv_dir.x, gc_splat4(tmax))));
    float4 entry = tnear - r.shear.w;
    return gc_select4(gc_le4(entry, tfar * GC_BOX_TFAR_SCALE), entry, gc_splat4(GC_AABB_MISS));
}

/* Candidate hits of four triangles: hit.k says lane k is hit with t in [t_min, tmax]. */
GC_STRUCT(GcTriangleHits4) {
    float4 t;
    float4 u;
    float4 v;
    GcMask4 hit;
} GC_STRUCT_END(GcTriangleHits4)

/* One of three per-axis values, by a per-ray axis index (the same for all lanes). */
GC_FUNC float4 gc_axis4(uint k, float4 x, float4 y, float4 z)
{
    return k == 0u ? x : (k == 1u ? y : z);
}

/* gc_intersect_triangle on four triangles at once; the comments there explain each step.
 * kx, ky, kz are the ray's r.kx, r.ky, r.kz, passed as constants by GC_WIDE_TRIANGLE4 (one
 * inlined copy per kz), so that picking a coordinate is a register choice and not a select
 * per use (nine per block; docs/decisions/bvh8-traversal-variants.md). */
GC_FUNC GcTriangleHits4 gc_intersect_triangle4(GcRayPre r, GcTriangle4 q, float tmax, uint kx, uint ky, uint kz)
{
    /* Vertices relative to the origin, per world axis. */
    float4 a0 = q.v0x - r.org.x;
    float4 a1 = q.v0y - r.org.y;
    float4 a2 = q.v0z - r.org.z;
    float4 b0 = q.v1x - r.org.x;
    float4 b1 = q.v1y - r.org.y;
    float4 b2 = q.v1z - r.org.z;
    float4 c0 = q.v2x - r.org.x;
    float4 c1 = q.v2y - r.org.y;
    float4 c2 = q.v2z - r.org.z;
    float sx = r.shear.x;
    float sy = r.shear.y;
    float sz = r.shear.z;
    float4 az = gc_axis4(kz, a0, a1, a2);
    float4 bz = gc_axis4(kz, b0, b1, b2);
    float4 cz = gc_axis4(kz, c0, c1, c2);
    float4 ax = gc_axis4(kx, a0, a1, a2) - sx * az;
    float4 ay = gc_axis4(ky, a0, a1, a2) - sy * az;
    float4 bx = gc_axis4(kx, b0, b1, b2) - sx * bz;
    float4 by = gc_axis4(ky, b0, b1, b2) - sy * bz;
    float4 cx = gc_axis4(kx, c0, c1, c2) - sx * cz;
    float4 cy = gc_axis4(ky, c0, c1, c2) - sy * cz;

    float4 eu = cx * by - cy * bx;
    float4 ev = ax * cy - ay * cx;
    float4 ew = bx * ay - by * ax;
    float4 zero = gc_splat4(0.0f);
    GcMask4 inside = gc_or4(gc_and4(gc_and4(gc_ge4(eu, zero), gc_ge4(ev, zero)), gc_ge4(ew, zero)),
                            gc_and4(gc_and4(gc_le4(eu, zero), gc_le4(ev, zero)), gc_le4(ew, zero)));
    float4 det = eu + ev + ew;

    float4 tz = eu * (sz * az) + ev * (sz * bz) + ew * (sz * cz);
    float4 rcp = 1.0f / det;
    GcTriangleHits4 h;
    h.t = tz * rcp;
    h.u = ev * rcp;
    h.v = ew * rcp;
    GcMask4 in_range = gc_and4(gc_ge4(h.t, gc_splat4(r.org.w)), gc_le4(h.t, gc_splat4(tmax)));
    /* Unused lanes (prim GC_INVALID) have zero area and would fail the noise floor below;
     * the empty scene's dummy block is excluded here too, as the BVH2 loop excludes its
     * dummy. */
    GcMask4 real = gc_ne4u(q.prim, make_uint4(GC_INVALID, GC_INVALID, GC_INVALID, GC_INVALID));
    h.hit = gc_and4(inside, gc_and4(in_range, real));
    /* Noise floor (gc_intersect_triangle), computed only for blocks with a candidate left:
     * most blocks a ray opens have none (no lane inside, or only farther than t_best), and
     * the floor is a fifth of the test (docs/decisions/bvh8-traversal-variants.md). */
    if (gc_any4(h.hit)) {
        /* s3 is the largest |vertex - origin| coordinate: a maximum is exact, so taking it
         * over the world axes in any order gives gc_intersect_triangle's value. */
        float4 s2 = gc_max4(gc_max4(gc_abs_max4(ax, ay), gc_abs_max4(bx, by)), gc_abs_max4(cx, cy));
        float4 m0 = gc_max4(gc_abs_max4(a0, b0), fabs(c0));
        float4 m1 = gc_max4(gc_abs_max4(a1, b1), fabs(c1));
        float4 m2 = gc_max4(gc_abs_max4(a2, b2), fabs(c2));
        float4 s3 = gc_max4(m0, gc_max4(m1, m2));
        h.hit = gc_and4(h.hit, gc_gt4(fabs(det), GC_TRI_DET_EPS * (s2 * (s2 + s3))));
    }
    return h;
}

/* Orders two (entry, child) pairs by entry. */
#define GC_BVH4_SORT2(ea, ca, eb, cb)        \
    {                                        \
        bool swap_ = (eb) < (ea);            \
        float e_ = swap_ ? (eb) : (ea);      \
        uint c_ = swap_ ? (cb) : (ca);       \
        (eb) = swap_ ? (ea) : (eb);          \
        (cb) = swap_ ? (ca) : (cb);          \
        (ea) = e_;                           \
        (ca) = c_;                           \
    }

/* Defers a child that was hit (sorted entries: misses come last). */
#define GC_BVH4_PUSH(e, c)                                   \
    if ((e) < GC_AABB_MISS && sp < GC_BVH4_STACK_SIZE) {     \
        stack_ref[sp] = (c);                                 \
        stack_entry[sp] = (e);                               \
        ++sp;                                                \
    }

/* The alpha test of gc_traverse.h, for one lane's candidate. */
#if defined(GC_ALPHA_TEST)
#define GC_BVH4_SOLID(flags, prim, u, v) ((((flags) & GC_TRI_ALPHA_TESTED) == 0u) || GC_ALPHA_TEST(prim, u, v))
#else
#define GC_BVH4_SOLID(flags, prim, u, v) true
#endif

/* Lane `c` of a block: accept it when it beats (t_best, best.prim) lexicographically. Lanes
 * are taken in order, each against the best so far, so the result is the same minimum the
 * BVH2 loop finds. */
#define GC_BVH4_ACCEPT(c)                                                                          \
    if (gc_lane(h.hit, c)) {                                                                       \
        uint prim = q.prim.c;                                                                      \
        float t = h.t.c;                                                                           \
        if ((t < t_best || (t == t_best && prim < best.prim)) && GC_BVH4_SOLID(q.flags.c, prim, h.u.c, h.v.c)) { \
            best.t = t;                                                                            \
            best.u = h.u.c;                                                                        \
            best.v = h.v.c;                                                                        \
            best.prim = prim;                                                                      \
            t_best = t;                                                                            \
            if (any_hit) return best;                                                              \
        }                                                                                          \
    }

/* The two wide traversals' shared steps, as statement macros over their locals (r, best,
 * t_best, any_hit, stack_ref, stack_entry, sp, ref): they update several of them and end
 * the enclosing function (any hit) or loop (empty stack), which a function cannot. */

/* The four-triangle test with the ray's axes as constants: one inlined copy per kz. */
#define GC_WIDE_TRIANGLE4(q)                                                                 \
    (r.kz == 0u ? gc_intersect_triangle4(r, (q), t_best, 1u, 2u, 0u)                          \
                : (r.kz == 1u ? gc_intersect_triangle4(r, (q), t_best, 2u, 0u, 1u)            \
                              : gc_intersect_triangle4(r, (q), t_best, 0u, 1u, 2u)))

/* Tests every GcTriangle4 block of leaf reference `leaf_ref`, lane by lane in order. */
#define GC_WIDE_LEAF(leaf_ref)                                                                \
    {                                                                                          \
        uint first_ = (leaf_ref) & GC_BVH4_LEAF_FIRST_MASK;                                    \
        uint end_ = first_ + (((leaf_ref) >> GC_BVH4_LEAF_COUNT_SHIFT) & 15u) + 1u;            \
        for (uint b_ = first_; b_ < end_; ++b_) {                                              \
            GcTriangle4 q = GC_BVH_TRI(b_);                                                    \
            GcTriangleHits4 h = GC_WIDE_TRIANGLE4(q);                                          \
            if (!gc_any4(h.hit)) continue;                                                     \
            GC_BVH4_ACCEPT(x)                                                                  \
            GC_BVH4_ACCEPT(y)                                                                  \
            GC_BVH4_ACCEPT(z)                                                                  \
            GC_BVH4_ACCEPT(w)                                                                  \
        }                                                                                      \
    }

/* Pops the nearest deferred child that can still beat t_best into `ref`, or leaves the
 * enclosing traversal loop when none can. */
#define GC_WIDE_POP()                                                                          \
    {                                                                                          \
        bool found_ = false;                                                                   \
        while (sp > 0u && !found_) {                                                           \
            --sp;                                                                              \
            found_ = gc_aabb_entry_within(stack_entry[sp], t_best);                           \
        }                                                                                      \
        if (!found_) break;                                                                    \
        ref = stack_ref[sp];                                                                   \
    }

/* The wide traversals' entry point, gc_trace_wide: one body for both queries (any_hit
 * returns at the first accepted triangle), called by gc_traverse.h's gc_trace_closest/any.
 *
 * Not inlined in OpenCL: PoCL inlines every call by default, so a kernel that asks for both
 * a closest and an any hit (the path megakernel) would compile the traversal twice. One
 * out-of-line copy shortens PoCL's cold build and costs no samples per second
 * (docs/decisions/cold-start.md). CPUs only: these are the CPU layouts, and a call costs a
 * GPU far more.
 *
 * The ray comes as its two float4s, which travel in registers: a GcRay argument went through
 * memory as two 16-byte stores read back by one 32-byte load, which store forwarding cannot
 * serve (perf: the hottest instruction of the megakernel's own code). */
#if defined(GC_OPENCL)
#define GC_WIDE_TRACE_BEGIN                                                                            \
    static __attribute__((noinline)) GcHit gc_trace_wide(GC_BVH_PARAMS, float4 ray_org_tmin, float4 ray_dir_tmax, \
                                                         bool any_hit)
#else
#define GC_WIDE_TRACE_BEGIN GC_FUNC GcHit gc_trace_wide(GC_BVH_PARAMS, float4 ray_org_tmin, float4 ray_dir_tmax, bool any_hit)
#endif

/* The wide bodies' locals: the ray (a miss if invalid), its precomputation with the margin
 * from the scene extent whose bits the root stores in `extent_bits` (every box lies inside
 * the root's children, so one margin serves all), the best hit so far, the stack of
 * deferred children, and `ref`, the node being visited, starting at the root. */
#define GC_WIDE_TRACE_SETUP(stack_size, extent_bits)                                          \
    GcRay ray;                                                                                 \
    ray.org_tmin = ray_org_tmin;                                                               \
    ray.dir_tmax = ray_dir_tmax;                                                               \
    GcHit best = gc_no_hit();                                                                  \
    if (!gc_ray_is_valid(ray)) return best;                                                    \
    GcRayPre r = gc_ray_with_extent_margin(gc_ray_precompute(ray), gc_as_float(extent_bits));  \
    float t_best = gc_ray_tmax(ray);                                                           \
    uint stack_ref[stack_size];                                                                \
    float stack_entry[stack_size];                                                             \
    uint sp = 0u;                                                                              \
    uint ref = 0u;

#if !defined(GC_TRAVERSE4_HELPERS_ONLY)
GC_WIDE_TRACE_BEGIN
{
    GC_WIDE_TRACE_SETUP(GC_BVH4_STACK_SIZE, GC_BVH_NODE(0u).pad.x)
    for (;;) {
        if ((ref & GC_BVH4_LEAF) == 0u) {
            GcBvh4Node n = GC_BVH_NODE(ref);
            float4 e = gc_box4_entry(r, t_best, n);
            float e0 = e.x;
            float e1 = e.y;
            float e2 = e.z;
            float e3 = e.w;
            uint c0 = n.child.x;
            uint c1 = n.child.y;
            uint c2 = n.child.z;
            uint c3 = n.child.w;
            /* Five compare-exchanges sort four entries; misses (+inf) sink to the end. */
            GC_BVH4_SORT2(e0, c0, e1, c1);
            GC_BVH4_SORT2(e2, c2, e3, c3);
            GC_BVH4_SORT2(e0, c0, e2, c2);
            GC_BVH4_SORT2(e1, c1, e3, c3);
            GC_BVH4_SORT2(e1, c1, e2, c2);
            if (e0 < GC_AABB_MISS) {
                /* Nearest child next; the others wait, farthest deepest in the stack. */
                GC_BVH4_PUSH(e3, c3);
                GC_BVH4_PUSH(e2, c2);
                GC_BVH4_PUSH(e1, c1);
                ref = c0;
                continue;
            }
        } else {
            GC_WIDE_LEAF(ref)
        }
        GC_WIDE_POP()
    }
    return best;
}

#undef GC_BVH4_SORT2
#undef GC_BVH4_PUSH
#undef GC_BVH4_SOLID
#undef GC_BVH4_ACCEPT
#undef GC_WIDE_LEAF
#undef GC_WIDE_TRIANGLE4
#undef GC_WIDE_POP
#undef GC_WIDE_TRACE_SETUP
#undef GC_WIDE_TRACE_BEGIN
#endif /* !GC_TRAVERSE4_HELPERS_ONLY */

GC_NAMESPACE_END

#endif /* GC_TRAVERSE4_H */
