/*
 * gc_intersect.h — ray/box and ray/triangle tests shared by the kernels, the host reference
 * traversal and (later) the Vulkan compute reference. Pure value functions in the dialect of
 * gc_platform.h: OpenCL C 1.2, C++20 and GLSL 4.50.
 *
 * Cross-device rule: for the same inputs every device must return the same bits. So the code
 * uses only +, -, * (correctly rounded everywhere, never contracted into FMA: gc_platform.h
 * turns contraction off in OpenCL, the host builds with -ffp-contract=off), comparisons,
 * fmin/fmax and two kinds of division: three reciprocals of the direction once per ray, and
 * one reciprocal of the determinant per triangle whose edge tests already passed (the few
 * triangles the ray's line really pierces). OpenCL 1.2 only promises 2.5 ulp for division
 * unless the program is built with -cl-fp32-correctly-rounded-divide-sqrt, so the host's
 * program builder must pass that option where the device supports it: without it, NVIDIA's
 * hits differ from the host's by a few ulp in t/u/v; with it, they are bit-identical to the
 * host's and PoCL's (docs/decisions/correct-division.md). No native_*, half_* or rsqrt is
 * used anywhere.
 *
 * Choice of triangle test: the watertight test of Woop, Benthin and Wald 2013 ("Watertight
 * Ray/Triangle Intersection", JCGT 2(1)), not Moller-Trumbore. It transforms the vertices
 * into a ray-aligned frame (translate to the origin, permute so the dominant direction axis
 * is z, shear z onto the ray) and evaluates the three 2D edge functions there. A shared edge
 * is evaluated from the same two sheared vertices by the same expression in both triangles,
 * and with contraction off a*b - c*d is exactly the negation of c*d - a*b, so the two
 * neighbours see exactly opposite signs: a ray can never slip between them (MT computes each
 * triangle's edges from different differences and leaks at shared edges and vertices). An
 * edge function of exactly 0 counts as inside for both neighbours, so the paper's double
 * precision re-evaluation (unavailable on many OpenCL devices and in core GLSL) is left out:
 * it sharpens which neighbour wins on an exact tie, it is not needed for watertightness.
 *
 * Triangles are two-sided; degenerate (zero-area) triangles never hit: their det is 0 or
 * rounding noise, which the test rejects (see the noise floor in gc_intersect_triangle).
 */
#ifndef GC_INTERSECT_H
#define GC_INTERSECT_H

#include "gc_accessors.h"
#include "gc_types.h"

/* GC_INFINITY: gc_accessors.h. */

/* What gc_intersect_aabb returns on a miss. Every hit returns a finite value (at least one
 * direction component is non-zero, so one slab gives a finite exit), so `t < GC_AABB_MISS`
 * is the hit test. */
#define GC_AABB_MISS GC_INFINITY

/* The box test must never cull a box holding a triangle that gc_intersect_triangle hits
 * (otherwise the BVH and a brute-force loop disagree), so it is conservative twice over:
 *
 * 1. Relative: after Ize 2013 ("Robust BVH Ray Traversal", JCGT 2(2)), entry and exit each
 *    carry up to gamma(3) relative rounding error (gamma(n) = n eps / (1 - n eps),
 *    eps = 2^-24), so the exit is scaled by 1 + 2 gamma(3) (= 1.00000036). We use 1 + 2^-20
 *    (about 8 ulp), which also covers a 2.5-ulp reciprocal on devices without correctly
 *    rounded division.
 * 2. Absolute: the triangle's t is a difference of vertex and origin coordinates, so its
 *    error is proportional to the vertices' distance from the origin, not to t: about
 *    eps * |v - o| / |d_dominant|. Near the origin (small t, large triangles, coplanar
 *    overlaps) that exceeds any relative slack, and a box pruned against a slightly-too-small
 *    best t would hide a triangle with a smaller computed t. So the entry is lowered by
 *    GC_BOX_ABS_EPS * (largest |corner - origin| coordinate) * min_i |1 / d_i| (the dominant
 *    axis has the smallest reciprocal), a bound on the t error of any triangle inside.
 *    2^-18 is 64 eps: room for the dozen roundings of the triangle test with a factor of 4.
 *    The traversal takes the largest coordinate over the *root* box (gc_ray_with_margin),
 *    which bounds |v - origin| for every triangle in the tree, so the margin is one per-ray
 *    constant instead of a dozen extra operations per box, which cost CPUs a large share of
 *    the traversal (docs/decisions/bvh8-traversal-variants.md). It is looser than a per-box
 *    margin by the ratio of the farthest scene corner's distance to the box's, still 4e-6 of
 *    that distance in t.
 * The price is a few extra box visits within that margin of the current best distance. */
#define GC_BOX_TFAR_SCALE 1.00000095367431640625f
#define GC_BOX_ABS_EPS 3.814697265625e-06f

/* Relative noise floor of the triangle test's determinant: 8 eps (see gc_intersect_triangle). */
#define GC_TRI_DET_EPS 4.76837158203125e-07f

GC_NAMESPACE_BEGIN

/* Per-ray constants of both tests, computed once by gc_ray_precompute. Private to a work
 * item: never stored in a buffer (float4 fields only, so it obeys the struct rules anyway). */
GC_STRUCT(GcRayPre) {
    float4 org;     /* xyz: origin;    w: t_min */
    float4 dir;     /* xyz: direction; w: t_max */
    float4 inv_dir; /* xyz: 1 / direction (+-inf for +-0 components); w: min |xyz| */
    float4 shear;   /* x: Sx, y: Sy, z: Sz of Woop et al.; w: the box test's absolute margin
                     * (0 from gc_ray_precompute; gc_ray_with_margin sets it) */
    uint kx;        /* permutation: kz is the axis of the largest |direction| component */
    uint ky;
    uint kz;
    uint pad;
} GC_STRUCT_END(GcRayPre)

/* v[k] for a run-time k: OpenCL C vectors have no run-time subscript. */
GC_FUNC float gc_float3_get(float3 v, uint k)
{
    return k == 0u ? v.x : (k == 1u ? v.y : v.z);
}

/* max(x, running) and min(x, running) that drop a NaN x and keep `running` (never NaN in
 * the callers). OpenCL's fmax/fmin give the same values but must also handle a NaN second
 * operand, which costs x86 two extra instructions per call; a compare-and-select is one
 * maxss/minss, and in GLSL it is defined for NaN where min/max are not. */
GC_FUNC float gc_max_keep(float x, float running)
{
    return x > running ? x : running;
}

GC_FUNC float gc_min_keep(float x, float running)
{
    return x < running ? x : running;
}

/* A ray is traced only if no component is NaN, its direction is not zero and
 * t_min <= t_max; anything else misses everything. (x == x is false only for NaN.) */
GC_FUNC bool gc_ray_is_valid(GcRay ray)
{
    float4 o = ray.org_tmin;
    float4 d = ray.dir_tmax;
    bool not_nan = o.x == o.x && o.y == o.y && o.z == o.z && d.x == d.x && d.y == d.y && d.z == d.z;
    bool nonzero = d.x != 0.0f || d.y != 0.0f || d.z != 0.0f;
    return not_nan && nonzero && o.w <= d.w;
}

/* The miss record: prim GC_INVALID, t = +inf, u = v = 0. */
GC_FUNC GcHit gc_no_hit(void)
{
    GcHit hit;
    hit.t = GC_INFINITY;
    hit.u = 0.0f;
    hit.v = 0.0f;
    hit.prim = GC_INVALID;
    return hit;
}

GC_FUNC GcRayPre gc_ray_precompute(GcRay ray)
{
    GcRayPre r;
    r.org = ray.org_tmin;
    r.dir = ray.dir_tmax;
    float3 d = GC_XYZ(ray.dir_tmax);
    /* 1/(+0) = +inf and 1/(-0) = -inf: the slab test below is written for these.
     * (Compilers divide the whole (d, t_max) register: see GC_RAY_UNBOUNDED.) */
    float3 inv = make_float3(1.0f / d.x, 1.0f / d.y, 1.0f / d.z);
    /* w: the dominant axis's |1/d|, the smallest, for the box test's absolute margin. */
    r.inv_dir = make_float4(inv.x, inv.y, inv.z, fmin(fabs(inv.x), fmin(fabs(inv.y), fabs(inv.z))));

    /* Largest |d| component becomes z; the other two follow cyclically. Woop et al. 2013
     * (section 3) also swap x and y when d.z is negative, to keep the sheared triangle's
     * winding; the test here accepts both windings, and the swap would only negate the edge
     * functions, det and tz together, so t, u and v are the same bits without it. Leaving it
     * out makes kx and ky functions of kz alone, which the wide leaves specialise on
     * (gc_traverse4.h). */
    float ax = fabs(d.x);
    float ay = fabs(d.y);
    float az = fabs(d.z);
    uint kz = (ax > ay) ? ((ax > az) ? 0u : 2u) : ((ay > az) ? 1u : 2u);
    uint kx = kz == 2u ? 0u : kz + 1u;
    uint ky = kx == 2u ? 0u : kx + 1u;
    r.kx = kx;
    r.ky = ky;
    r.kz = kz;
    r.pad = 0u;
    /* Sz is the reciprocal already computed for the slab test: one division per axis. */
    float sz = gc_float3_get(GC_XYZ(r.inv_dir), kz);
    r.shear = make_float4(gc_float3_get(d, kx) * sz, gc_float3_get(d, ky) * sz, sz, 0.0f);
    return r;
}

/*
 * Slab test (Kay and Kajiya 1986) against the closed box [lo, hi], clipped to [tmin, tmax].
 * Returns a lower bound on the entry distance of any triangle hit inside the box:
 * max(tmin, box entry) minus `margin`, the absolute margin described above (so it may be a
 * little below tmin), or GC_AABB_MISS. Hit: entry - margin <= exit * GC_BOX_TFAR_SCALE.
 *
 * Per axis the near plane is chosen by the sign of inv_dir (Williams et al. 2005, "An
 * efficient and robust ray-box intersection algorithm"), so the only NaN that can arise is
 * 0 * inf: a direction component of +-0 with the origin exactly on that slab's plane. The
 * ray then lies in the closed slab, which must not constrain t, and gc_max_keep/gc_min_keep
 * drop a NaN first operand, so folding the axis terms into the running max/min ignores it:
 * such rays hit, as they should. Off the plane, (plane - o) * +-inf gives +-inf with the
 * right sign, so a parallel ray outside the slab misses. tmin and tmax are not NaN
 * (gc_ray_is_valid), so the folded results are never NaN. Empty bounds (lo = +inf,
 * hi = -inf) give entry +inf and exit -inf: a miss (their margin is inf, and -inf + inf is
 * NaN, which compares false).
 */
GC_FUNC float gc_intersect_aabb_m(float3 org, float3 inv_dir, float margin, float tmin, float tmax, float3 lo,
                                  float3 hi)
{
    float nx = (inv_dir.x >= 0.0f ? lo.x : hi.x) - org.x;
    float fx = (inv_dir.x >= 0.0f ? hi.x : lo.x) - org.x;
    float ny = (inv_dir.y >= 0.0f ? lo.y : hi.y) - org.y;
    float fy = (inv_dir.y >= 0.0f ? hi.y : lo.y) - org.y;
    float nz = (inv_dir.z >= 0.0f ? lo.z : hi.z) - org.z;
    float fz = (inv_dir.z >= 0.0f ? hi.z : lo.z) - org.z;
    /* The running value is the *second* operand so a NaN axis term is the one dropped. */
    float tnear = gc_max_keep(nz * inv_dir.z, gc_max_keep(ny * inv_dir.y, gc_max_keep(nx * inv_dir.x, tmin)));
    float tfar = gc_min_keep(fz * inv_dir.z, gc_min_keep(fy * inv_dir.y, gc_min_keep(fx * inv_dir.x, tmax)));
    float entry = tnear - margin;
    return entry <= tfar * GC_BOX_TFAR_SCALE ? entry : GC_AABB_MISS;
}

/* The absolute margin for triangles inside [lo, hi]: GC_BOX_ABS_EPS times the largest
 * |corner - origin| coordinate times inv_min = min(|inv_dir.x|, |inv_dir.y|, |inv_dir.z|). */
GC_FUNC float gc_box_margin(float3 org, float inv_min, float3 lo, float3 hi)
{
    float3 m = fmax(fabs(lo - org), fabs(hi - org));
    return GC_BOX_ABS_EPS * (fmax(m.x, fmax(m.y, m.z)) * inv_min);
}

/* The slab test with the box's own margin (tests and one-off boxes). */
GC_FUNC float gc_intersect_aabb(float3 org, float3 inv_dir, float tmin, float tmax, float3 lo, float3 hi)
{
    float inv_min = fmin(fabs(inv_dir.x), fmin(fabs(inv_dir.y), fabs(inv_dir.z)));
    return gc_intersect_aabb_m(org, inv_dir, gc_box_margin(org, inv_min, lo, hi), tmin, tmax, lo, hi);
}

/* The ray with the margin of every box inside [root_lo, root_hi] (the BVH's root bounds). */
GC_FUNC GcRayPre gc_ray_with_margin(GcRayPre r, float3 root_lo, float3 root_hi)
{
    r.shear.w = gc_box_margin(GC_XYZ(r.org), r.inv_dir.w, root_lo, root_hi);
    return r;
}

/* The same margin from the scene's extent: `extent` >= every |coordinate| of the root box, so
 * |corner - origin| <= extent + max |origin coordinate| bounds what gc_box_margin takes the
 * maximum of (a little looser, still conservative). The wide layouts store the extent in the
 * root node, which saves each ray the reduction over the root's children. */
GC_FUNC GcRayPre gc_ray_with_extent_margin(GcRayPre r, float extent)
{
    float3 o = fabs(GC_XYZ(r.org));
    r.shear.w = GC_BOX_ABS_EPS * ((extent + fmax(o.x, fmax(o.y, o.z))) * r.inv_dir.w);
    return r;
}

/* The slab test with a precomputed ray (see gc_ray_with_margin), clipped to [ray t_min, tmax]. */
GC_FUNC float gc_intersect_aabb_pre(GcRayPre r, float tmax, float3 lo, float3 hi)
{
    return gc_intersect_aabb_m(GC_XYZ(r.org), GC_XYZ(r.inv_dir), r.shear.w, r.org.w, tmax, lo, hi);
}

/* True when a box whose gc_intersect_aabb result is `entry` may still hold a hit at
 * t <= tmax: the same widened comparison, for entries popped off a stack after tmax shrank. */
GC_FUNC bool gc_aabb_entry_within(float entry, float tmax)
{
    return entry < GC_AABB_MISS && entry <= tmax * GC_BOX_TFAR_SCALE;
}

/*
 * Watertight ray/triangle test (Woop, Benthin, Wald 2013). Accepts hits with
 * t in [ray t_min, tmax] (both ends inclusive, so callers can resolve ties themselves).
 * Returns t, and u, v = barycentric weights of v1 and v2 (the hit point is
 * (1-u-v) v0 + u v1 + v v2); prim is 0 on a hit and GC_INVALID on a miss (the caller stores
 * the scene triangle index). t is a pure function of the ray and the three vertices: the
 * tmax passed in only filters, so a triangle gets the same t whatever order it is tested in.
 */
GC_FUNC GcHit gc_intersect_triangle(GcRayPre r, float3 v0, float3 v1, float3 v2, float tmax)
{
    GcHit hit = gc_no_hit();

    float3 o = GC_XYZ(r.org);
    float3 a = v0 - o;
    float3 b = v1 - o;
    float3 c = v2 - o;
    float sx = r.shear.x;
    float sy = r.shear.y;
    float sz = r.shear.z;
    float az = gc_float3_get(a, r.kz);
    float bz = gc_float3_get(b, r.kz);
    float cz = gc_float3_get(c, r.kz);
    /* Shear into the ray's frame: the ray becomes the +z axis through (0, 0). */
    float ax = gc_float3_get(a, r.kx) - sx * az;
    float ay = gc_float3_get(a, r.ky) - sy * az;
    float bx = gc_float3_get(b, r.kx) - sx * bz;
    float by = gc_float3_get(b, r.ky) - sy * bz;
    float cx = gc_float3_get(c, r.kx) - sx * cz;
    float cy = gc_float3_get(c, r.ky) - sy * cz;

    /* Scaled barycentrics: 2D edge functions of edges (v1,v2), (v2,v0), (v0,v1). */
    float eu = cx * by - cy * bx;
    float ev = ax * cy - ay * cx;
    float ew = bx * ay - by * ax;
    /* Inside when all three share a sign (0 counts as either). Written positively so that a
     * NaN anywhere is a miss. */
    bool inside = (eu >= 0.0f && ev >= 0.0f && ew >= 0.0f) || (eu <= 0.0f && ev <= 0.0f && ew <= 0.0f);
    float det = eu + ev + ew;
    if (!inside) return hit;
    /* Noise floor. The sheared coordinates carry absolute errors of about eps * |v - o|, so
     * the edge functions carry about eps * s * (s + |v - o|), s the largest sheared
     * coordinate. A det below that is rounding noise: a degenerate or needle-thin triangle
     * whose "inside" is meaningless, and whose would-be hit can lie far from the triangle
     * (outside its box, where a BVH would never find it). Reject it, as det == 0 (and NaN)
     * always were. It drops only triangles whose projected area / size^2 is below about
     * 5e-7 * (1 + distance / projected size): slivers at the edge of float resolution. A
     * ray through such a sliver's interior may leak; shared edges stay watertight, since
     * the neighbour still counts a 0 edge function as inside. */
    float s2 = fmax(fmax(fmax(fabs(ax), fabs(ay)), fmax(fabs(bx), fabs(by))), fmax(fabs(cx), fabs(cy)));
    float3 m3 = fmax(fmax(fabs(a), fabs(b)), fabs(c));
    float s3 = fmax(m3.x, fmax(m3.y, m3.z));
    if (!(fabs(det) > GC_TRI_DET_EPS * (s2 * (s2 + s3)))) return hit;

    float tz = eu * (sz * az) + ev * (sz * bz) + ew * (sz * cz);
    float rcp = 1.0f / det;
    float t = tz * rcp;
    if (!(t >= r.org.w && t <= tmax)) return hit;
    hit.t = t;
    hit.u = ev * rcp;
    hit.v = ew * rcp;
    hit.prim = 0u;
    return hit;
}

GC_NAMESPACE_END

#endif /* GC_INTERSECT_H */
