/*
 * gc_traverse8.h — gc_trace_wide over the BVH8 layout (GcBvh8Node + GcTriangle4 leaves),
 * compiled when the program is built with -D GC_BVH_WIDE -D GC_BVH_WIDE8. The leaves and the
 * triangle test are gc_traverse4.h's; the node test covers eight boxes with one float8
 * expression in OpenCL (one AVX instruction per step), and two gc_box4_entry calls on the
 * host, which perform the same operations per lane and so give the same bits.
 *
 * Child order: every child's (entry, reference) is written to the stack and the stack
 * pointer advances only past those hit (no branch per child); the few pushed (typically
 * 1-3) are then insertion-sorted so that the nearest is on top, and it is popped at once.
 * Same results as every other layout (the tie rule of gc_traverse.h); the stack holds at
 * most seven deferred children per level, and the BVH8 is no deeper than its BVH2.
 */
#ifndef GC_TRAVERSE8_H
#define GC_TRAVERSE8_H

#define GC_TRAVERSE4_HELPERS_ONLY
#include "gc_traverse4.h"
#undef GC_TRAVERSE4_HELPERS_ONLY

/* Each inner node on the way down defers at most seven children; eight slots of slack let
 * the branch-free push write before it checks. */
#define GC_BVH8_STACK_SIZE (7u * GC_BVH_MAX_DEPTH + 8u)

GC_NAMESPACE_BEGIN

#if defined(GC_OPENCL)

/* gc_box4_entry for eight boxes: per lane the same operations. Each axis's near and far
 * planes are loaded straight from the node at per-ray float offsets (near_x is 0, lo_x, when
 * the direction's x is not negative, else 8, hi_x; far is the other: near ^ 8), as Embree's
 * nearX/farX offsets do, instead of loading both planes and selecting one per lane: six
 * blends fewer per node (docs/decisions/bvh8-traversal-variants.md). */
GC_FUNC float8 gc_box8_entry(GcRayPre r, float tmax, GC_GLOBAL const float* node, uint near_x, uint near_y,
                             uint near_z)
{
    float8 nx = vload8(0, node + near_x) - r.org.x;
    float8 fx = vload8(0, node + (near_x ^ 8u)) - r.org.x;
    float8 ny = vload8(0, node + near_y) - r.org.y;
    float8 fy = vload8(0, node + (near_y ^ 8u)) - r.org.y;
    float8 nz = vload8(0, node + near_z) - r.org.z;
    float8 fz = vload8(0, node + (near_z ^ 8u)) - r.org.z;
    float8 tnear = (float8)(r.org.w);
    float8 t;
    t = nx * r.inv_dir.x;
    tnear = select(tnear, t, t > tnear);
    t = ny * r.inv_dir.y;
    tnear = select(tnear, t, t > tnear);
    t = nz * r.inv_dir.z;
    tnear = select(tnear, t, t > tnear);
    float8 tfar = (float8)(tmax);
    t = fx * r.inv_dir.x;
    tfar = select(tfar, t, t < tfar);
    t = fy * r.inv_dir.y;
    tfar = select(tfar, t, t < tfar);
    t = fz * r.inv_dir.z;
    tfar = select(tfar, t, t < tfar);
    float8 entry = tnear - r.shear.w;
    return select((float8)(GC_AABB_MISS), entry, entry <= tfar * GC_BOX_TFAR_SCALE);
}
#define GC_LANE8(v, k) (v).s##k
#else
/* Host: the entries of both halves, lanes 0-3 and 4-7. */
struct GcEntries8 {
    float4 a;
    float4 b;
};

inline GcBvh4Node gc_bvh8_half(const GcBvh8Node& n, bool upper)
{
    GcBvh4Node h;
    h.lo_x = upper ? n.lo_x1 : n.lo_x0;
    h.hi_x = upper ? n.hi_x1 : n.hi_x0;
    h.lo_y = upper ? n.lo_y1 : n.lo_y0;
    h.hi_y = upper ? n.hi_y1 : n.hi_y0;
    h.lo_z = upper ? n.lo_z1 : n.lo_z0;
    h.hi_z = upper ? n.hi_z1 : n.hi_z0;
    h.child = upper ? n.child1 : n.child0;
    h.pad = uint4(0u);
    return h;
}

inline GcEntries8 gc_box8_entry(GcRayPre r, float tmax, const GcBvh8Node& n)
{
    return {gc_box4_entry(r, tmax, gc_bvh8_half(n, false)), gc_box4_entry(r, tmax, gc_bvh8_half(n, true))};
}
#define GC_LANE8(v, k) ((k) < 4 ? (v).a[(k) & 3] : (v).b[(k) & 3])
#endif

/* Writes child k's (entry, ref) at the top of the stack and keeps it only if it was hit. */
#define GC_BVH8_PUSH(k, c)                   \
    {                                        \
        float e_ = GC_LANE8(e, k);           \
        stack_ref[sp] = (c);                 \
        stack_entry[sp] = e_;                \
        sp += e_ < GC_AABB_MISS ? 1u : 0u;   \
    }

GC_WIDE_TRACE_BEGIN
{
    GC_WIDE_TRACE_SETUP(GC_BVH8_STACK_SIZE, GC_BVH_NODE(0u).pad0.x)
#if defined(GC_OPENCL)
    /* gc_box8_entry's plane offsets in GcBvh8Node (gc_types.h): lo_x 0, hi_x 8, lo_y 16... */
    const uint near_x = r.inv_dir.x >= 0.0f ? 0u : 8u;
    const uint near_y = r.inv_dir.y >= 0.0f ? 16u : 24u;
    const uint near_z = r.inv_dir.z >= 0.0f ? 32u : 40u;
#endif
    for (;;) {
        if ((ref & GC_BVH4_LEAF) == 0u) {
            GcBvh8Node n = GC_BVH_NODE(ref);
#if defined(GC_OPENCL)
            float8 e = gc_box8_entry(r, t_best, (GC_GLOBAL const float*)&GC_BVH_NODE(ref), near_x, near_y, near_z);
#else
            GcEntries8 e = gc_box8_entry(r, t_best, n);
#endif
            uint base = sp;
            if (sp + 8u <= GC_BVH8_STACK_SIZE) {
                GC_BVH8_PUSH(0, n.child0.x)
                GC_BVH8_PUSH(1, n.child0.y)
                GC_BVH8_PUSH(2, n.child0.z)
                GC_BVH8_PUSH(3, n.child0.w)
                GC_BVH8_PUSH(4, n.child1.x)
                GC_BVH8_PUSH(5, n.child1.y)
                GC_BVH8_PUSH(6, n.child1.z)
                GC_BVH8_PUSH(7, n.child1.w)
            }
            if (!any_hit && sp > base + 1u) {
                /* Insertion sort of the pushed children, farthest deepest, nearest on top (an
                 * any-hit query stops at the first hit wherever it is: no order to keep). */
                for (uint i = base + 1u; i < sp; ++i) {
                    float ke = stack_entry[i];
                    uint kr = stack_ref[i];
                    uint j = i;
                    while (j > base && stack_entry[j - 1u] < ke) {
                        stack_entry[j] = stack_entry[j - 1u];
                        stack_ref[j] = stack_ref[j - 1u];
                        --j;
                    }
                    stack_entry[j] = ke;
                    stack_ref[j] = kr;
                }
            }
            if (sp > base) {
                --sp;
                ref = stack_ref[sp];
                continue;
            }
        } else {
            GC_WIDE_LEAF(ref)
        }
        GC_WIDE_POP()
    }
    return best;
}

#undef GC_BVH8_PUSH
#undef GC_WIDE_TRACE_SETUP
#undef GC_WIDE_TRACE_BEGIN
#undef GC_WIDE_LEAF
#undef GC_WIDE_TRIANGLE4
#undef GC_WIDE_POP
#undef GC_BVH4_SORT2
#undef GC_BVH4_PUSH
#undef GC_BVH4_SOLID
#undef GC_BVH4_ACCEPT

GC_NAMESPACE_END

#endif /* GC_TRAVERSE8_H */
