/*
 * gc_packet8.h — closest hits of eight rays in one traversal of the BVH8, for rays that
 * travel together: the camera rays of one pixel's consecutive samples, or of a few
 * neighbouring pixels (gc_packet_lanes.h), which the CPU path megakernel traces as one packet
 * (kernels/megakernel.cl). They leave one point through one pixel or a few, so they open
 * nearly the same nodes and triangles, and one traversal with the eight
 * rays in float8 lanes replaces eight: node loads, child ordering and stack work are paid
 * once, and a triangle is tested against all eight rays in one set of vector operations.
 * Rays that part ways after the first bounce are traced one by one (gc_traverse8.h): in
 * packets they lost (docs/decisions/simd-across-paths.md).
 *
 * Same hits as gc_trace_closest, bit for bit, ray by ray. Each lane performs the single-ray
 * code's operations: the precomputation of gc_ray_precompute and gc_ray_with_extent_margin,
 * the box entries of gc_box8_entry, the watertight test of gc_intersect_triangle4 with its
 * noise floor, the alpha test. The answer is the (t, scene index) minimum of gc_traverse.h's
 * tie rule, which no visiting order changes, and a box is skipped for a ray only by the
 * single-ray test's widened `entry <= t_best`. Children are visited nearest first by their
 * smallest entry over the rays that hit them; a popped child is dropped only when its entry
 * is past every ray's best. tests/render/device_kernels_test.cpp compares the hit records
 * with the single-ray traversal's on every device, and tests/validation/determinism_test.cpp
 * the megakernel's image bits with the wavefront's.
 *
 * The structs below live in registers and private memory only, never in a buffer, so they
 * are not host/device layouts (gc_types.h holds those).
 *
 * OpenCL C, programs built for the BVH8 only (-D GC_BVH_WIDE8: CPUs with 8-wide SIMD); the
 * host and GLSL keep single rays. GC_HAVE_PACKET8 says whether it is compiled.
 */
#ifndef GC_PACKET8_H
#define GC_PACKET8_H

#include "gc_packet_lanes.h"
#include "gc_traverse.h"

#if defined(GC_OPENCL) && defined(GC_BVH_WIDE8)
#define GC_HAVE_PACKET8 1

GC_NAMESPACE_BEGIN

/* Eight rays, lane k being ray k; `active` (-1 or 0 per lane) says which lanes hold one. */
typedef struct {
    float8 ox, oy, oz;
    float8 dx, dy, dz;
    float8 tmin, tmax;
    int8 active;
} GcRays8;

/* Eight hits, as GcHit per lane (a miss or an inactive lane: prim GC_INVALID, t +inf). */
typedef struct {
    float8 t, u, v;
    uint8 prim;
} GcHits8;

/* The per-ray constants of gc_ray_precompute and gc_ray_with_extent_margin, per lane. */
typedef struct {
    float8 ox, oy, oz;
    float8 ix, iy, iz;    /* 1 / direction */
    float8 sx, sy, sz;    /* Woop et al.'s shear */
    float8 margin, tmin;
    uint8 kx, ky, kz;     /* kz: the axis of the largest |direction| component */
    int8 pos_x, pos_y, pos_z; /* 1 / direction >= 0: the near plane is the box's low one */
    /* Where every lane has the same (kx, ky, kz), as the camera rays of one pixel or of
     * neighbouring pixels do, the triangle test picks the vertices' components once, in
     * scalar, instead of per lane: shared_axes, those axes, and the origins in that order. */
    bool shared_axes;
    uint axis_x, axis_y, axis_z;
    float8 okx, oky, okz;
    /* Likewise where every lane's direction has the same signs: the box test reads each
     * axis's near and far plane once instead of selecting per lane. */
    bool shared_signs;
    /* Where, besides, the active lanes share one origin and every 1/direction is finite (a
     * pinhole camera's rays): the bounds over those lanes that gc_packet_node_cull8 tests a
     * node's eight boxes against at once (gc_packet_cull_setup8). */
    bool node_cull;
    float cull_ox, cull_oy, cull_oz;
    float ix_lo, ix_hi, iy_lo, iy_hi, iz_lo, iz_hi;
    float tmin_lo, margin_hi;
} GcPacketPre8;

/* One of three per-axis values by a per-lane axis index. */
GC_FUNC float8 gc_axis8(uint8 k, float8 x, float8 y, float8 z)
{
    return select(select(z, y, k == (uint8)(1u)), x, k == (uint8)(0u));
}

GC_FUNC float8 gc_max_keep8(float8 x, float8 running) { return select(running, x, x > running); }
GC_FUNC float8 gc_min_keep8(float8 x, float8 running) { return select(running, x, x < running); }
GC_FUNC float8 gc_max8(float8 a, float8 b) { return select(b, a, a > b); }
GC_FUNC float8 gc_abs_max8(float8 a, float8 b) { return gc_max8(fabs(a), fabs(b)); }

GC_FUNC float gc_reduce_min8(float8 v)
{
    const float4 a = fmin(v.lo, v.hi);
    const float2 b = fmin(a.lo, a.hi);
    return fmin(b.x, b.y);
}

GC_FUNC float gc_reduce_max8(float8 v)
{
    const float4 a = fmax(v.lo, v.hi);
    const float2 b = fmax(a.lo, a.hi);
    return fmax(b.x, b.y);
}

GC_FUNC GcPacketPre8 gc_packet_precompute8(GcRays8 rays, float extent)
{
    GcPacketPre8 r;
    r.ox = rays.ox;
    r.oy = rays.oy;
    r.oz = rays.oz;
    r.ix = 1.0f / rays.dx;
    r.iy = 1.0f / rays.dy;
    r.iz = 1.0f / rays.dz;
    const float8 inv_min = fmin(fabs(r.ix), fmin(fabs(r.iy), fabs(r.iz)));
    const float8 ax = fabs(rays.dx);
    const float8 ay = fabs(rays.dy);
    const float8 az = fabs(rays.dz);
    const uint8 two = (uint8)(2u);
    r.kz = select(select(two, (uint8)(1u), ay > az), select(two, (uint8)(0u), ax > az), ax > ay);
    r.kx = select(r.kz + 1u, (uint8)(0u), r.kz == two);
    r.ky = select(r.kx + 1u, (uint8)(0u), r.kx == two);
    r.sz = gc_axis8(r.kz, r.ix, r.iy, r.iz);
    r.sx = gc_axis8(r.kx, rays.dx, rays.dy, rays.dz) * r.sz;
    r.sy = gc_axis8(r.ky, rays.dx, rays.dy, rays.dz) * r.sz;
    const float8 o_max = fmax(fabs(rays.ox), fmax(fabs(rays.oy), fabs(rays.oz)));
    r.margin = GC_BOX_ABS_EPS * ((extent + o_max) * inv_min);
    r.tmin = rays.tmin;
    r.pos_x = r.ix >= 0.0f;
    r.pos_y = r.iy >= 0.0f;
    r.pos_z = r.iz >= 0.0f;
    r.axis_x = r.kx.s0;
    r.axis_y = r.ky.s0;
    r.axis_z = r.kz.s0;
    r.shared_axes = all(r.kz == (uint8)(r.axis_z)) && all(r.kx == (uint8)(r.axis_x));
    r.okx = gc_axis8(r.kx, rays.ox, rays.oy, rays.oz);
    r.oky = gc_axis8(r.ky, rays.ox, rays.oy, rays.oz);
    r.okz = gc_axis8(r.kz, rays.ox, rays.oy, rays.oz);
    r.shared_signs = all(r.pos_x == (int8)(r.pos_x.s0)) && all(r.pos_y == (int8)(r.pos_y.s0)) &&
                     all(r.pos_z == (int8)(r.pos_z.s0));
    return r;
}

GC_FUNC float gc_lanes_min8(float8 v, int8 active) { return gc_reduce_min8(select((float8)(GC_INFINITY), v, active)); }
GC_FUNC float gc_lanes_max8(float8 v, int8 active) { return gc_reduce_max8(select((float8)(-GC_INFINITY), v, active)); }

/* The node cull's bounds over the active lanes, where they apply (GcPacketPre8.node_cull). */
GC_FUNC void gc_packet_cull_setup8(GcPacketPre8* r, int8 active)
{
    r->cull_ox = gc_lanes_min8(r->ox, active);
    r->cull_oy = gc_lanes_min8(r->oy, active);
    r->cull_oz = gc_lanes_min8(r->oz, active);
    const int8 same_origin = (r->ox == (float8)(r->cull_ox)) & (r->oy == (float8)(r->cull_oy)) &
                             (r->oz == (float8)(r->cull_oz));
    const float8 inf = (float8)(GC_INFINITY);
    const int8 finite = (fabs(r->ix) < inf) & (fabs(r->iy) < inf) & (fabs(r->iz) < inf);
    r->node_cull = r->shared_signs && all(same_origin | ~active) && all(finite | ~active);
    r->ix_lo = gc_lanes_min8(r->ix, active);
    r->ix_hi = gc_lanes_max8(r->ix, active);
    r->iy_lo = gc_lanes_min8(r->iy, active);
    r->iy_hi = gc_lanes_max8(r->iy, active);
    r->iz_lo = gc_lanes_min8(r->iz, active);
    r->iz_hi = gc_lanes_max8(r->iz, active);
    r->tmin_lo = gc_lanes_min8(r->tmin, active);
    r->margin_hi = gc_lanes_max8(r->margin, active);
}

/* gc_ray_is_valid per lane. */
GC_FUNC int8 gc_packet_valid8(GcRays8 rays)
{
    const int8 not_nan = (rays.ox == rays.ox) & (rays.oy == rays.oy) & (rays.oz == rays.oz) & (rays.dx == rays.dx) &
                         (rays.dy == rays.dy) & (rays.dz == rays.dz);
    const int8 nonzero = (rays.dx != 0.0f) | (rays.dy != 0.0f) | (rays.dz != 0.0f);
    return not_nan & nonzero & (rays.tmin <= rays.tmax);
}

/* A BVH8 node's planes and children, stored for scalar reads of one child at a time. */
typedef struct {
    float lo_x[8], hi_x[8], lo_y[8], hi_y[8], lo_z[8], hi_z[8];
    uint child[8];
} GcPacketNode8;

GC_FUNC void gc_packet_load_node8(GC_GLOBAL const GcBvh8Node* n, GcPacketNode8* out)
{
    vstore8((float8)(n->lo_x0, n->lo_x1), 0, out->lo_x);
    vstore8((float8)(n->hi_x0, n->hi_x1), 0, out->hi_x);
    vstore8((float8)(n->lo_y0, n->lo_y1), 0, out->lo_y);
    vstore8((float8)(n->hi_y0, n->hi_y1), 0, out->hi_y);
    vstore8((float8)(n->lo_z0, n->lo_z1), 0, out->lo_z);
    vstore8((float8)(n->hi_z0, n->hi_z1), 0, out->hi_z);
    vstore8((uint8)(n->child0, n->child1), 0, out->child);
}

/* For packets with shared signs: each axis's planes as the lanes meet them, near then far
 * (the near plane is the low one where the direction is not negative). */
typedef struct {
    float near_x[8], far_x[8], near_y[8], far_y[8], near_z[8], far_z[8];
    uint child[8];
} GcPacketNearFar8;

GC_FUNC void gc_packet_load_near_far8(GC_GLOBAL const GcBvh8Node* n, const GcPacketPre8* r, GcPacketNearFar8* out)
{
    const float8 lo_x = (float8)(n->lo_x0, n->lo_x1), hi_x = (float8)(n->hi_x0, n->hi_x1);
    const float8 lo_y = (float8)(n->lo_y0, n->lo_y1), hi_y = (float8)(n->hi_y0, n->hi_y1);
    const float8 lo_z = (float8)(n->lo_z0, n->lo_z1), hi_z = (float8)(n->hi_z0, n->hi_z1);
    vstore8(r->pos_x.s0 ? lo_x : hi_x, 0, out->near_x);
    vstore8(r->pos_x.s0 ? hi_x : lo_x, 0, out->far_x);
    vstore8(r->pos_y.s0 ? lo_y : hi_y, 0, out->near_y);
    vstore8(r->pos_y.s0 ? hi_y : lo_y, 0, out->far_y);
    vstore8(r->pos_z.s0 ? lo_z : hi_z, 0, out->near_z);
    vstore8(r->pos_z.s0 ? hi_z : lo_z, 0, out->far_z);
    vstore8((uint8)(n->child0, n->child1), 0, out->child);
}

/* A leaf block's four triangles, stored for scalar reads of one triangle at a time:
 * v[corner][axis][triangle]. */
typedef struct {
    float v[3][3][4];
    uint prim[4], flags[4];
} GcPacketBlock4;

GC_FUNC void gc_packet_load_block4(GC_GLOBAL const GcTriangle4* q, GcPacketBlock4* out)
{
    vstore4(q->v0x, 0, out->v[0][0]); vstore4(q->v0y, 0, out->v[0][1]); vstore4(q->v0z, 0, out->v[0][2]);
    vstore4(q->v1x, 0, out->v[1][0]); vstore4(q->v1y, 0, out->v[1][1]); vstore4(q->v1z, 0, out->v[1][2]);
    vstore4(q->v2x, 0, out->v[2][0]); vstore4(q->v2y, 0, out->v[2][1]); vstore4(q->v2z, 0, out->v[2][2]);
    vstore4(q->prim, 0, out->prim);
    vstore4(q->flags, 0, out->flags);
}

/* Child c's box against the eight rays: lane c of gc_box8_entry, per ray. *hit says which
 * rays enter it before their t_best. */
GC_FUNC float8 gc_packet_box_entry8(const GcPacketPre8* r, const GcPacketNode8* n, uint c, float8 t_best, int8* hit)
{
    const float8 nx = select((float8)(n->hi_x[c]), (float8)(n->lo_x[c]), r->pos_x) - r->ox;
    const float8 fx = select((float8)(n->lo_x[c]), (float8)(n->hi_x[c]), r->pos_x) - r->ox;
    const float8 ny = select((float8)(n->hi_y[c]), (float8)(n->lo_y[c]), r->pos_y) - r->oy;
    const float8 fy = select((float8)(n->lo_y[c]), (float8)(n->hi_y[c]), r->pos_y) - r->oy;
    const float8 nz = select((float8)(n->hi_z[c]), (float8)(n->lo_z[c]), r->pos_z) - r->oz;
    const float8 fz = select((float8)(n->lo_z[c]), (float8)(n->hi_z[c]), r->pos_z) - r->oz;
    const float8 tnear = gc_max_keep8(nz * r->iz, gc_max_keep8(ny * r->iy, gc_max_keep8(nx * r->ix, r->tmin)));
    const float8 tfar = gc_min_keep8(fz * r->iz, gc_min_keep8(fy * r->iy, gc_min_keep8(fx * r->ix, t_best)));
    const float8 entry = tnear - r->margin;
    *hit = entry <= tfar * GC_BOX_TFAR_SCALE;
    return entry;
}

/* gc_packet_box_entry8 for packets with shared signs: the same operations per lane, on the
 * planes gc_packet_load_near_far8 put in order. */
GC_FUNC float8 gc_packet_box_entry8_shared_signs(const GcPacketPre8* r, const GcPacketNearFar8* n, uint c,
                                                 float8 t_best, int8* hit)
{
    const float8 nx = (float8)(n->near_x[c]) - r->ox;
    const float8 fx = (float8)(n->far_x[c]) - r->ox;
    const float8 ny = (float8)(n->near_y[c]) - r->oy;
    const float8 fy = (float8)(n->far_y[c]) - r->oy;
    const float8 nz = (float8)(n->near_z[c]) - r->oz;
    const float8 fz = (float8)(n->far_z[c]) - r->oz;
    const float8 tnear = gc_max_keep8(nz * r->iz, gc_max_keep8(ny * r->iy, gc_max_keep8(nx * r->ix, r->tmin)));
    const float8 tfar = gc_min_keep8(fz * r->iz, gc_min_keep8(fy * r->iy, gc_min_keep8(fx * r->ix, t_best)));
    const float8 entry = tnear - r->margin;
    *hit = entry <= tfar * GC_BOX_TFAR_SCALE;
    return entry;
}

/* The children of a node that some active lane may enter (lane c for child c), for packets
 * with GcPacketPre8.node_cull: one test of the eight boxes, as a single ray's, on bounds that
 * hold for every lane, so that the per-lane test runs only for boxes that pass.
 *
 * Exact, not heuristic: a lane's slab distance is (plane - origin) * (1 / direction), one
 * rounding each. The difference is the same float in every lane (one origin), and a rounded
 * product is monotonic in each factor, so the smaller and larger of the products with the
 * lanes' least and greatest 1 / direction bound every lane's product. The entry (largest
 * near distance, at least t_min, less the margin) and the exit (smallest far distance, at
 * most t_best, times GC_BOX_TFAR_SCALE) are monotonic too. So a box whose lowest possible
 * entry exceeds its highest possible exit is one that gc_packet_box_entry8 misses in every
 * lane; any other box still goes to that test. No NaN can arise: the inverses are finite. */
GC_FUNC int8 gc_packet_node_cull8(const GcPacketPre8* r, const GcPacketNearFar8* n, float t_best_hi)
{
    const float8 nx = vload8(0, n->near_x) - r->cull_ox;
    const float8 fx = vload8(0, n->far_x) - r->cull_ox;
    const float8 ny = vload8(0, n->near_y) - r->cull_oy;
    const float8 fy = vload8(0, n->far_y) - r->cull_oy;
    const float8 nz = vload8(0, n->near_z) - r->cull_oz;
    const float8 fz = vload8(0, n->far_z) - r->cull_oz;
    float8 entry_lo = (float8)(r->tmin_lo);
    entry_lo = fmax(entry_lo, fmin(nx * r->ix_lo, nx * r->ix_hi));
    entry_lo = fmax(entry_lo, fmin(ny * r->iy_lo, ny * r->iy_hi));
    entry_lo = fmax(entry_lo, fmin(nz * r->iz_lo, nz * r->iz_hi));
    float8 exit_hi = (float8)(t_best_hi);
    exit_hi = fmin(exit_hi, fmax(fx * r->ix_lo, fx * r->ix_hi));
    exit_hi = fmin(exit_hi, fmax(fy * r->iy_lo, fy * r->iy_hi));
    exit_hi = fmin(exit_hi, fmax(fz * r->iz_lo, fz * r->iz_hi));
    return (entry_lo - r->margin_hi) <= exit_hi * GC_BOX_TFAR_SCALE;
}

/* Triangle (a, b, c) against the eight rays: lane k of gc_intersect_triangle4 for ray k, the
 * noise floor included. Returns the `active` rays that hit it with t in [t_min, t_best]. */
GC_FUNC int8 gc_packet_triangle8_sheared(const GcPacketPre8* r, float8 akx, float8 aky, float8 akz, float8 bkx,
                                         float8 bky, float8 bkz, float8 ckx, float8 cky, float8 ckz, float8 t_best,
                                         int8 active, float8* t, float8* u, float8* v)
{
    const float8 ax = akx - r->sx * akz;
    const float8 ay = aky - r->sy * akz;
    const float8 bx = bkx - r->sx * bkz;
    const float8 by = bky - r->sy * bkz;
    const float8 cx = ckx - r->sx * ckz;
    const float8 cy = cky - r->sy * ckz;
    const float8 eu = cx * by - cy * bx;
    const float8 ev = ax * cy - ay * cx;
    const float8 ew = bx * ay - by * ax;
    const float8 zero = (float8)(0.0f);
    const int8 inside = active & (((eu >= zero) & (ev >= zero) & (ew >= zero)) | ((eu <= zero) & (ev <= zero) & (ew <= zero)));
    if (!any(inside)) return inside;
    const float8 det = eu + ev + ew;
    const float8 tz = eu * (r->sz * akz) + ev * (r->sz * bkz) + ew * (r->sz * ckz);
    const float8 rcp = 1.0f / det;
    *t = tz * rcp;
    *u = ev * rcp;
    *v = ew * rcp;
    const int8 candidate = inside & (*t >= r->tmin) & (*t <= t_best);
    if (!any(candidate)) return candidate;
    /* The noise floor's largest |component|: a maximum, so the axes' order does not matter. */
    const float8 s2 = gc_max8(gc_max8(gc_abs_max8(ax, ay), gc_abs_max8(bx, by)), gc_abs_max8(cx, cy));
    const float8 s3 = gc_max8(gc_max8(gc_abs_max8(akx, bkx), fabs(ckx)),
                              gc_max8(gc_max8(gc_abs_max8(aky, bky), fabs(cky)), gc_max8(gc_abs_max8(akz, bkz), fabs(ckz))));
    return candidate & (fabs(det) > GC_TRI_DET_EPS * (s2 * (s2 + s3)));
}

/* Corner `corner` of triangle k of a block, relative to the origins, one axis per lane's
 * (kx, ky, kz) (gc_axis8) or, for packets with shared axes, read once in that order. */
#define GC_PACKET_CORNER8(r, q, corner, k, rel_x, rel_y, rel_z)                                                  \
    float8 rel_x, rel_y, rel_z;                                                                                  \
    if ((r).shared_axes) {                                                                                       \
        rel_x = (float8)((q).v[corner][(r).axis_x][k]) - (r).okx;                                                \
        rel_y = (float8)((q).v[corner][(r).axis_y][k]) - (r).oky;                                                \
        rel_z = (float8)((q).v[corner][(r).axis_z][k]) - (r).okz;                                                \
    } else {                                                                                                     \
        const float8 d0 = (float8)((q).v[corner][0][k]) - (r).ox;                                                \
        const float8 d1 = (float8)((q).v[corner][1][k]) - (r).oy;                                                \
        const float8 d2 = (float8)((q).v[corner][2][k]) - (r).oz;                                                \
        rel_x = gc_axis8((r).kx, d0, d1, d2);                                                                    \
        rel_y = gc_axis8((r).ky, d0, d1, d2);                                                                    \
        rel_z = gc_axis8((r).kz, d0, d1, d2);                                                                    \
    }

/* Triangle k of block q against the eight rays. */
GC_FUNC int8 gc_packet_triangle8(const GcPacketPre8* r, const GcPacketBlock4* q, uint k, float8 t_best, int8 active,
                                 float8* t, float8* u, float8* v)
{
    GC_PACKET_CORNER8(*r, *q, 0, k, akx, aky, akz)
    GC_PACKET_CORNER8(*r, *q, 1, k, bkx, bky, bkz)
    GC_PACKET_CORNER8(*r, *q, 2, k, ckx, cky, ckz)
    return gc_packet_triangle8_sheared(r, akx, aky, akz, bkx, bky, bkz, ckx, cky, ckz, t_best, active, t, u, v);
}

/* Lanes of `take` whose candidate the alpha test cuts away are dropped (gc_alpha.h). */
#if defined(GC_ALPHA_TEST)
GC_FUNC int8 gc_packet_solid8(GC_ALPHA_PARAMS, int8 take, uint prim, float8 u, float8 v)
{
    int lanes[8];
    float us[8];
    float vs[8];
    vstore8(take, 0, lanes);
    vstore8(u, 0, us);
    vstore8(v, 0, vs);
    for (uint k = 0u; k < 8u; ++k)
        if (lanes[k] != 0 && !GC_ALPHA_TEST(prim, us[k], vs[k])) lanes[k] = 0;
    return vload8(0, lanes);
}
#endif

/* gc_trace_closest for eight rays. */
GC_FUNC GcHits8 gc_trace_closest8(GC_BVH_PARAMS, GcRays8 rays)
{
    GcHits8 best;
    best.t = (float8)(GC_INFINITY);
    best.u = (float8)(0.0f);
    best.v = (float8)(0.0f);
    best.prim = (uint8)(GC_INVALID);
    const int8 active = rays.active & gc_packet_valid8(rays);
    if (!any(active)) return best;
    GcPacketPre8 r = gc_packet_precompute8(rays, gc_as_float(GC_BVH_NODE(0u).pad0.x));
    gc_packet_cull_setup8(&r, active);
    float8 t_best = rays.tmax;
    uint stack_ref[GC_BVH8_STACK_SIZE];
    float stack_entry[GC_BVH8_STACK_SIZE];
    uint sp = 0u;
    uint ref = 0u;
    for (;;) {
        if ((ref & GC_BVH4_LEAF) == 0u) {
            GcPacketNode8 n;
            GcPacketNearFar8 nf;
            if (r.shared_signs) gc_packet_load_near_far8(&GC_BVH_NODE(ref), &r, &nf);
            else gc_packet_load_node8(&GC_BVH_NODE(ref), &n);
            const uint* child = r.shared_signs ? nf.child : n.child;
            int maybe[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
            if (r.node_cull) vstore8(gc_packet_node_cull8(&r, &nf, gc_lanes_max8(t_best, active)), 0, maybe);
            /* Pushed farthest first (insertion by entry), so the nearest is popped next. */
            const uint base = sp;
            for (uint c = 0u; c < 8u; ++c) {
                if (maybe[c] == 0) continue;
                int8 hit;
                const float8 entry = r.shared_signs ? gc_packet_box_entry8_shared_signs(&r, &nf, c, t_best, &hit)
                                                    : gc_packet_box_entry8(&r, &n, c, t_best, &hit);
                hit &= active;
                if (!any(hit) || sp >= GC_BVH8_STACK_SIZE) continue;
                const float e = gc_reduce_min8(select((float8)(GC_AABB_MISS), entry, hit));
                uint j = sp++;
                while (j > base && stack_entry[j - 1u] < e) {
                    stack_entry[j] = stack_entry[j - 1u];
                    stack_ref[j] = stack_ref[j - 1u];
                    --j;
                }
                stack_entry[j] = e;
                stack_ref[j] = child[c];
            }
        } else {
            const uint first = ref & GC_BVH4_LEAF_FIRST_MASK;
            const uint end = first + ((ref >> GC_BVH4_LEAF_COUNT_SHIFT) & 15u) + 1u;
            for (uint b = first; b < end; ++b) {
                GcPacketBlock4 q;
                gc_packet_load_block4(&GC_BVH_TRI(b), &q);
                for (uint k = 0u; k < 4u; ++k) {
                    if (q.prim[k] == GC_INVALID) continue;
                    float8 t, u, v;
                    const int8 hit = gc_packet_triangle8(&r, &q, k, t_best, active, &t, &u, &v);
                    if (!any(hit)) continue;
                    const uint8 prim = (uint8)(q.prim[k]);
                    int8 take = hit & ((t < t_best) | ((t == t_best) & (prim < best.prim)));
#if defined(GC_ALPHA_TEST)
                    if ((q.flags[k] & GC_TRI_ALPHA_TESTED) != 0u) take = gc_packet_solid8(GC_ALPHA_ARGS, take, q.prim[k], u, v);
#endif
                    t_best = select(t_best, t, take);
                    best.u = select(best.u, u, take);
                    best.v = select(best.v, v, take);
                    best.prim = select(best.prim, prim, take);
                }
            }
        }
        /* The nearest deferred child that some ray's best may not yet rule out. */
        const float reach = gc_reduce_max8(select((float8)(-GC_AABB_MISS), t_best, active));
        bool found = false;
        while (sp > 0u && !found) {
            --sp;
            found = gc_aabb_entry_within(stack_entry[sp], reach);
        }
        if (!found) break;
        ref = stack_ref[sp];
    }
    best.t = select((float8)(GC_INFINITY), t_best, best.prim != (uint8)(GC_INVALID));
    return best;
}

/* gc_trace_closest8 on private arrays of eight: hit[k] is what gc_trace_closest gives ray[k]
 * where active[k] is non-zero, the miss record elsewhere. */
GC_FUNC void gc_packet_closest_hits8(GC_BVH_PARAMS, const GcRay* ray, const int* active, GcHit* hit)
{
    float ox[8], oy[8], oz[8], dx[8], dy[8], dz[8], tmin[8], tmax[8];
    int on[8];
    for (uint k = 0u; k < 8u; ++k) {
        ox[k] = ray[k].org_tmin.x; oy[k] = ray[k].org_tmin.y; oz[k] = ray[k].org_tmin.z; tmin[k] = ray[k].org_tmin.w;
        dx[k] = ray[k].dir_tmax.x; dy[k] = ray[k].dir_tmax.y; dz[k] = ray[k].dir_tmax.z; tmax[k] = ray[k].dir_tmax.w;
        on[k] = active[k] != 0 ? -1 : 0;
    }
    GcRays8 rays;
    rays.ox = vload8(0, ox); rays.oy = vload8(0, oy); rays.oz = vload8(0, oz);
    rays.dx = vload8(0, dx); rays.dy = vload8(0, dy); rays.dz = vload8(0, dz);
    rays.tmin = vload8(0, tmin);
    rays.tmax = vload8(0, tmax);
    rays.active = vload8(0, on);
    const GcHits8 h = gc_trace_closest8(GC_BVH_ARGS, rays);
    float t[8], u[8], v[8];
    uint prim[8];
    vstore8(h.t, 0, t); vstore8(h.u, 0, u); vstore8(h.v, 0, v); vstore8(h.prim, 0, prim);
    for (uint k = 0u; k < 8u; ++k) {
        hit[k].t = t[k];
        hit[k].u = u[k];
        hit[k].v = v[k];
        hit[k].prim = prim[k];
    }
}

GC_NAMESPACE_END

#endif /* GC_OPENCL && GC_BVH_WIDE8 */

#endif /* GC_PACKET8_H */
