/*
 * EXPERIMENT, not part of the renderer: kernels/megakernel.cl with eight paths per work-item
 * in float8 lanes, to measure what explicit SIMD across paths gives a whole path tracer on a
 * CPU. tools/bench/experiments/packet-megakernel.sh swaps it in for megakernel.cl (same
 * kernel name and arguments), checks the image bits and times both with kernel-ab.sh.
 *
 * The work-items whose slot is a multiple of GROUP each take GROUP consecutive pixels of the
 * pass (the others return at once); their eight lanes start a pixel's path as soon as the
 * lane's previous path ends. Everything gc_shade_vertex does for a Lambert surface runs for
 * eight paths at a time; its scope is untextured Lambert materials, triangle emitters, a
 * constant environment and no alpha (the Cornell box and the bench's dragon). Rays are traced
 * lane by lane with the renderer's traversal, or as packets of eight through the same BVH8:
 *
 *   PK_PACKET_SHADOW   1: shadow rays as one packet (pk_occluded8); 0: lane by lane
 *   PK_PACKET_CLOSEST  1: path rays as one packet (pk_closest8); 0: lane by lane
 *
 * Every lane performs the scalar code's operations in its order, and neither query's answer
 * depends on the order nodes are visited in, so the film is the scalar megakernel's, bit for
 * bit, in all four combinations. Figures and conclusion: README.md here.
 */
#include "gc_alpha.h"
#include "gc_traverse.h"
#include "gc_packet8.h"
#include "gc_path_vertex.h"
#include "gc_camera.h"
#include "gc_rng.h"

typedef float8 vf;
typedef int8 vi;
typedef uint8 vu;

#define SEL(m, a, b) select((b), (a), (m)) /* lane-wise m ? a : b */
#define LANES 8u

#ifndef PK_PACKET_SHADOW
#define PK_PACKET_SHADOW 1
#endif
#ifndef PK_PACKET_CLOSEST
#define PK_PACKET_CLOSEST 0
#endif
#ifndef PK_PIXEL_LANES
#define PK_PIXEL_LANES 0
#endif
#ifndef PK_PACKET_PRIMARY
#define PK_PACKET_PRIMARY 0
#endif

/* gc_pcg4d with each of its four words a vector of lanes. */
static void pk_pcg4d(vu* x, vu* y, vu* z, vu* w)
{
    vu a = *x * 1664525u + 1013904223u;
    vu b = *y * 1664525u + 1013904223u;
    vu c = *z * 1664525u + 1013904223u;
    vu d = *w * 1664525u + 1013904223u;
    a += b * d;
    b += c * a;
    c += a * b;
    d += b * c;
    a ^= a >> 16u;
    b ^= b >> 16u;
    c ^= c >> 16u;
    d ^= d >> 16u;
    a += b * d;
    b += c * a;
    c += a * b;
    d += b * c;
    *x = a;
    *y = b;
    *z = c;
    *w = d;
}

static vf pk_unit(vu bits) { return convert_float8(bits >> 8u) * (1.0f / 16777216.0f); }

static void pk_rand4(vu pixel, vu sample, vu block, uint seed, vf* r0, vf* r1, vf* r2, vf* r3)
{
    vu x = pixel;
    vu y = sample;
    vu z = block;
    vu w = (vu)(seed);
    pk_pcg4d(&x, &y, &z, &w);
    *r0 = pk_unit(x);
    *r1 = pk_unit(y);
    *r2 = pk_unit(z);
    *r3 = pk_unit(w);
}

/* A float3 of lanes. */
typedef struct {
    vf x, y, z;
} V3;

static V3 v3(vf x, vf y, vf z)
{
    V3 r;
    r.x = x;
    r.y = y;
    r.z = z;
    return r;
}
static V3 v3_add(V3 a, V3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static V3 v3_sub(V3 a, V3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static V3 v3_mul(V3 a, V3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static V3 v3_scale(V3 a, vf s) { return v3(a.x * s, a.y * s, a.z * s); }
static V3 v3_div(V3 a, vf s) { return v3(a.x / s, a.y / s, a.z / s); }
static V3 v3_neg(V3 a) { return v3(-a.x, -a.y, -a.z); }
static V3 v3_sel(vi m, V3 a, V3 b) { return v3(SEL(m, a.x, b.x), SEL(m, a.y, b.y), SEL(m, a.z, b.z)); }
static vf v3_dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static vf v3_length(V3 a) { return sqrt(v3_dot(a, a)); }
static vi v3_any_positive(V3 a) { return (a.x > 0.0f) | (a.y > 0.0f) | (a.z > 0.0f); }

/* A float3 per lane, staged through memory: lanes are written one at a time, then read as
 * three vectors (writing a vector's lane by index spilled the vector each time). */
typedef struct {
    float x[8], y[8], z[8];
} PkStage3;

static void pk_stage(PkStage3* s, uint k, float4 v)
{
    s->x[k] = v.x;
    s->y[k] = v.y;
    s->z[k] = v.z;
}

static V3 pk_staged(const PkStage3* s) { return v3(vload8(0, s->x), vload8(0, s->y), vload8(0, s->z)); }

static vf pk_offset_component(vf p, vf n)
{
    const vi of = convert_int8_rtz(256.0f * n);
    const vi step = SEL(p < 0.0f, -of, of);
    const vf far_ = as_float8(as_int8(p) + step);
    return SEL(fabs(p) < (1.0f / 32.0f), p + (1.0f / 65536.0f) * n, far_);
}

static V3 pk_offset_ray_origin(V3 p, V3 n)
{
    return v3(pk_offset_component(p.x, n.x), pk_offset_component(p.y, n.y), pk_offset_component(p.z, n.z));
}

static V3 pk_side_normal(V3 ng, V3 w) { return v3_sel(v3_dot(ng, w) >= 0.0f, ng, v3_neg(ng)); }

static vf pk_power_heuristic(vf pdf_a, vf pdf_b)
{
    const vf r = pdf_b / pdf_a;
    return SEL(pdf_a > 0.0f, 1.0f / (1.0f + r * r), (vf)(0.0f));
}

static vf pk_luminance(V3 c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

static vf pk_light_pdf_w(V3 emission, float emitter_power, vf dist, vf cos_light)
{
    const vf pdf_area = pk_luminance(emission) / emitter_power;
    return pdf_area * dist * dist / fabs(cos_light);
}

static vi pk_emits_toward(vi two_sided, vf cos_out) { return (cos_out > 0.0f) | (two_sided & (cos_out < 0.0f)); }

/* gc_cos_sin_quarter */
static void pk_cos_sin_quarter(vf x, vf* c, vf* s)
{
    const vf z = x * x;
    *s = x + x * z * (-0.166666552f + z * (0.00833216123f + z * -0.000195153087f));
    *c = 1.0f - 0.5f * z + z * z * (0.0416666456f + z * (-0.00138873165f + z * 2.44331768e-05f));
}

/* gc_sample_cosine_hemisphere */
static V3 pk_cosine_hemisphere(vf u0, vf u1)
{
    const vf a = 2.0f * u0 - 1.0f;
    const vf b = 2.0f * u1 - 1.0f;
    const vi a_major = fabs(a) > fabs(b);
    const vf ratio = SEL(a_major, b / a, a / b);
    vf c, s;
    pk_cos_sin_quarter((0.25f * GC_PI) * ratio, &c, &s);
    const vi origin = (a == 0.0f) & (b == 0.0f);
    const vf dx = SEL(origin, (vf)(0.0f), SEL(a_major, a * c, b * s));
    const vf dy = SEL(origin, (vf)(0.0f), SEL(a_major, a * s, b * c));
    const vf r = fmax(fabs(2.0f * u0 - 1.0f), fabs(2.0f * u1 - 1.0f));
    return v3(dx, dy, sqrt(fmax(0.0f, (1.0f - r) * (1.0f + r))));
}

/* Lambert gc_bsdf_eval / gc_bsdf_pdf: both need wo and wi above the surface after the
 * two-sided flip. */
static vi pk_lambert_upper(V3 wo, V3 wi)
{
    const vf side = SEL(wo.z < 0.0f, (vf)(-1.0f), (vf)(1.0f));
    return (wo.z * side > 0.0f) & (wi.z * side > 0.0f);
}

static vf pk_lambert_pdf(V3 wo, V3 wi)
{
    const vf side = SEL(wo.z < 0.0f, (vf)(-1.0f), (vf)(1.0f));
    return SEL(pk_lambert_upper(wo, wi), fmax(wi.z * side, 0.0f) * GC_INV_PI, (vf)(0.0f));
}

static V3 pk_lambert_eval(V3 albedo, V3 wo, V3 wi)
{
    const V3 zero = v3(0.0f, 0.0f, 0.0f);
    return v3_sel(pk_lambert_upper(wo, wi), v3_scale(albedo, (vf)(GC_INV_PI)), zero);
}

/* gc_frame_from_normal and the two conversions. */
typedef struct {
    V3 t, b, n;
} F3;

static F3 pk_frame(V3 n)
{
    const vf s = SEL(n.z >= 0.0f, (vf)(1.0f), (vf)(-1.0f));
    const vf a = -1.0f / (s + n.z);
    const vf c = n.x * n.y * a;
    F3 f;
    f.t = v3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    f.b = v3(c, s + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}

static V3 pk_to_local(F3 f, V3 v) { return v3(v3_dot(v, f.t), v3_dot(v, f.b), v3_dot(v, f.n)); }
static V3 pk_to_world(F3 f, V3 v) { return v3_add(v3_add(v3_scale(f.t, v.x), v3_scale(f.b, v.y)), v3_scale(f.n, v.z)); }

/* ------------------------------------------------------------------ packet traversal */

/* Eight rays from lanes of V3, t_min 0 (kernels/shared/gc_packet8.h's packets). */
static GcRays8 pk_packet(V3 o, V3 d, vf tmax, vi active)
{
    GcRays8 rays;
    rays.ox = o.x; rays.oy = o.y; rays.oz = o.z;
    rays.dx = d.x; rays.dy = d.y; rays.dz = d.z;
    rays.tmin = (vf)(0.0f);
    rays.tmax = tmax;
    rays.active = active;
    return rays;
}

/* gc_trace_any for eight rays at once over the BVH8, built from gc_packet8.h's pieces: a
 * child is entered when any ray still unoccluded hits its box, and every triangle of a leaf
 * is tested against all of them. An any-hit answer does not depend on the order nodes are
 * visited in. */
static vi pk_occluded8(GC_BVH_PARAMS, V3 o, V3 d, vf tmax, vi active)
{
    const GcRays8 rays = pk_packet(o, d, tmax, active);
    vi occluded = 0;
    active &= gc_packet_valid8(rays);
    const GcPacketPre8 r = gc_packet_precompute8(rays, as_float(GC_BVH_NODE(0u).pad0.x));
    uint stack[GC_BVH8_STACK_SIZE];
    uint sp = 0u;
    uint ref = 0u;
    for (;;) {
        if ((ref & GC_BVH4_LEAF) == 0u) {
            GcPacketNode8 n;
            gc_packet_load_node8(&GC_BVH_NODE(ref), &n);
            for (uint c = 0u; c < 8u; ++c) {
                vi hit;
                gc_packet_box_entry8(&r, &n, c, tmax, &hit);
                if (any(active & hit) && sp < GC_BVH8_STACK_SIZE) stack[sp++] = n.child[c];
            }
        } else {
            const uint first = ref & GC_BVH4_LEAF_FIRST_MASK;
            const uint end = first + ((ref >> GC_BVH4_LEAF_COUNT_SHIFT) & 15u) + 1u;
            for (uint b = first; b < end; ++b) {
                GcPacketBlock4 q;
                gc_packet_load_block4(&GC_BVH_TRI(b), &q);
                for (uint k = 0u; k < 4u; ++k) {
                    if (q.prim[k] == GC_INVALID) continue;
                    vf t, u, v;
                    const vi hit = gc_packet_triangle8(&r, &q, k, tmax, active, &t, &u, &v);
                    occluded |= hit;
                    active &= ~hit;
                }
            }
            if (!any(active)) return occluded;
        }
        if (sp == 0u) break;
        ref = stack[--sp];
    }
    return occluded;
}

/* gc_trace_closest for eight rays at once: gc_packet8.h's packet, which the renderer now
 * uses for camera rays. */
static void pk_closest8(GC_BVH_PARAMS, V3 o, V3 d, vi active, vf* out_t, vf* out_u, vf* out_v, vu* out_prim)
{
    const GcHits8 h = gc_trace_closest8(GC_BVH_ARGS, pk_packet(o, d, (vf)(GC_RAY_UNBOUNDED), active));
    *out_t = h.t;
    *out_u = h.u;
    *out_v = h.v;
    *out_prim = h.prim;
}

/* The eight paths of a work-item, lane by lane: what GcPathState and the path's ray carry,
 * and the pixel and sample each lane belongs to. */
typedef struct {
    V3 org, dir, beta, L;
    vf pdf_last;
    vi specular, alive;
    vu pixel, sample, depth;
} PkPaths;

/* Starts lane k's path: the camera ray of sample `sample` of pixel px (generate.cl). */
static void pk_start(PkPaths* ps, uint k, const GcRenderParams* params, uint px, uint sample)
{
    const float4 jitter = gc_rand4(px, sample, GC_RNG_BLOCK_CAMERA, params->seed);
    const GcRay ray = gc_camera_ray(params->camera, params->width, params->height, px % params->width,
                                    px / params->width, jitter.x, jitter.y);
    ps->org.x[k] = ray.org_tmin.x; ps->org.y[k] = ray.org_tmin.y; ps->org.z[k] = ray.org_tmin.z;
    ps->dir.x[k] = ray.dir_tmax.x; ps->dir.y[k] = ray.dir_tmax.y; ps->dir.z[k] = ray.dir_tmax.z;
    ps->pixel[k] = px;
    ps->sample[k] = sample;
    ps->depth[k] = 0u;
    ps->beta.x[k] = 1.0f; ps->beta.y[k] = 1.0f; ps->beta.z[k] = 1.0f;
    ps->L.x[k] = 0.0f; ps->L.y[k] = 0.0f; ps->L.z[k] = 0.0f;
    ps->pdf_last[k] = 0.0f;
    ps->specular[k] = -1;
    ps->alive[k] = -1;
}

static PkPaths pk_no_paths(void)
{
    PkPaths ps;
    ps.org = ps.dir = ps.beta = ps.L = v3(0.0f, 0.0f, 0.0f);
    ps.pdf_last = 0.0f;
    ps.specular = 0;
    ps.alive = 0;
    ps.pixel = 0u;
    ps.sample = 0u;
    ps.depth = 0u;
    return ps;
}

/* One segment of every alive lane's path: extend.cl, shade.cl and shadow.cl. Returns the lanes
 * whose path goes on (their ray is the next one); the others' L is final. packet_closest:
 * trace the path rays as one packet (pk_closest8) instead of lane by lane. */
static vi pk_segment(const GcRenderParams* params, GC_SCENE_PARAMS, PkPaths* ps, bool packet_closest)
{
    const float group_pmf = gc_light_group_pmf(*params);
    const V3 env = v3(params->env_radiance.x, params->env_radiance.y, params->env_radiance.z);
    ps->depth = SEL(ps->alive, ps->depth + 1u, ps->depth);
    const vu bounce = ps->depth - 1u;

    /* extend.cl, per lane */
    vf t, u, v;
    vu prim;
    if (packet_closest) {
        pk_closest8(GC_BVH_ARGS, ps->org, ps->dir, ps->alive, &t, &u, &v, &prim);
    } else {
        float h_t[LANES], h_u[LANES], h_v[LANES];
        uint h_prim[LANES];
        float r_ox[LANES], r_oy[LANES], r_oz[LANES], r_dx[LANES], r_dy[LANES], r_dz[LANES];
        vstore8(ps->org.x, 0, r_ox); vstore8(ps->org.y, 0, r_oy); vstore8(ps->org.z, 0, r_oz);
        vstore8(ps->dir.x, 0, r_dx); vstore8(ps->dir.y, 0, r_dy); vstore8(ps->dir.z, 0, r_dz);
        for (uint k = 0u; k < LANES; ++k) {
            h_t[k] = 0.0f; h_u[k] = 0.0f; h_v[k] = 0.0f; h_prim[k] = GC_INVALID;
            if (!ps->alive[k]) continue;
            const GcRay ray = gc_make_ray(make_float3(r_ox[k], r_oy[k], r_oz[k]),
                                          make_float3(r_dx[k], r_dy[k], r_dz[k]), 0.0f, GC_RAY_UNBOUNDED);
            const GcHit hit = gc_trace_closest(GC_BVH_ARGS, ray);
            h_t[k] = hit.t; h_u[k] = hit.u; h_v[k] = hit.v; h_prim[k] = hit.prim;
        }
        t = vload8(0, h_t); u = vload8(0, h_u); v = vload8(0, h_v);
        prim = vload8(0, h_prim);
    }
    const vi active = ps->alive & (prim != (vu)(GC_INVALID));
    ps->L = v3_sel(ps->alive & ~active, v3_add(ps->L, v3_mul(ps->beta, env)), ps->L); /* escaped */

    /* The surface and its material, gathered per lane through private arrays (one
     * vector load per field; writing lanes of a vector by index spills it each time). */
    PkStage3 s_n0, s_n1, s_n2, s_ng, s_albedo, s_emission;
    int s_two[LANES];
    for (uint k = 0u; k < LANES; ++k) {
        const GcTriangleAttribs a = GC_ATTRIB(active[k] ? prim[k] : 0u);
        const GcMaterial m = GC_MATERIAL(a.material);
        pk_stage(&s_n0, k, a.n0);
        pk_stage(&s_n1, k, a.n1);
        pk_stage(&s_n2, k, a.n2);
        pk_stage(&s_ng, k, a.ng);
        pk_stage(&s_albedo, k, m.albedo);
        pk_stage(&s_emission, k, m.emission);
        s_two[k] = (m.flags & GC_MATF_TWO_SIDED) != 0u ? -1 : 0;
    }
    const V3 n0 = pk_staged(&s_n0), n1 = pk_staged(&s_n1), n2 = pk_staged(&s_n2), ng = pk_staged(&s_ng);
    const V3 albedo = pk_staged(&s_albedo), emission = pk_staged(&s_emission);
    const vi two_sided = vload8(0, s_two);
    /* gc_surface_at */
    const vf b0 = 1.0f - u - v;
    const V3 p = v3_add(ps->org, v3_scale(ps->dir, t));
    const V3 n = v3_add(v3_add(v3_scale(n0, b0), v3_scale(n1, u)), v3_scale(n2, v));
    const vf len = v3_length(n);
    V3 ns = v3_sel(len > 0.0f, v3_scale(n, 1.0f / len), ng);
    ns = v3_sel(v3_dot(ns, ng) < 0.0f, v3_neg(ns), ns);
    const V3 wo_world = v3_neg(ps->dir);

    /* Emission seen by this ray. */
    const vf cos_out = v3_dot(ng, wo_world);
    const vi emits = active & v3_any_positive(emission) & pk_emits_toward(two_sided, cos_out);
    if (any(emits)) {
        vf w = 1.0f;
        if (params->num_emitters > 0u)
            w = SEL(ps->specular, w,
                    pk_power_heuristic(ps->pdf_last, group_pmf * pk_light_pdf_w(emission, params->emitter_power, t, cos_out)));
        ps->L = v3_sel(emits, v3_add(ps->L, v3_scale(v3_mul(ps->beta, emission), w)), ps->L);
    }
    const vi cont = active & (ps->depth < (vu)(params->max_depth));
    vi survive = 0;
    if (any(cont)) {
        const F3 frame = pk_frame(ns);
        const V3 wo = pk_to_local(frame, wo_world);

        /* Next-event estimation to one emitter (the emitter group is the only one in scope). */
        vi shadow = 0;
        V3 shadow_org, shadow_dir, contribution;
        vf shadow_len = 0.0f;
        if (group_pmf > 0.0f) {
            vf r0, r1, r2, r3;
            pk_rand4(ps->pixel, ps->sample, 1u + bounce * GC_RNG_BLOCKS_PER_BOUNCE + GC_RNG_BLOCK_LIGHT, params->seed,
                     &r0, &r1, &r2, &r3);
            const uint groups = gc_uint(1.0f / group_pmf + 0.5f);
            const vf ug = r0 * gc_float(groups);
            vu group = convert_uint8_rtz(ug);
            group = SEL(group >= groups, (vu)(groups - 1u), group);
            const vf ue = fmin(ug - convert_float8(group), 0.99999994f);
            PkStage3 s_v0, s_v1, s_v2, s_lng, s_le;
            int s_ltwo[LANES];
            for (uint k = 0u; k < LANES; ++k) {
                const GcEmitter e = GC_EMITTER(gc_pick_emitter(GC_EMITTERS_ARG, params->num_emitters, cont[k] ? ue[k] : 0.0f));
                const GcTriangleAttribs la = GC_ATTRIB(e.triangle);
                const GcMaterial lm = GC_MATERIAL(la.material);
                pk_stage(&s_v0, k, e.v0);
                pk_stage(&s_v1, k, e.v1);
                pk_stage(&s_v2, k, e.v2);
                pk_stage(&s_lng, k, la.ng);
                pk_stage(&s_le, k, lm.emission);
                s_ltwo[k] = (lm.flags & GC_MATF_TWO_SIDED) != 0u ? -1 : 0;
            }
            const V3 v0 = pk_staged(&s_v0), v1 = pk_staged(&s_v1), v2 = pk_staged(&s_v2);
            const V3 lng = pk_staged(&s_lng), le = pk_staged(&s_le);
            const vi l_two_sided = vload8(0, s_ltwo);
            /* gc_sample_uniform_triangle */
            const vi lower = r1 < r2;
            const vf bb0 = SEL(lower, 0.5f * r1, r1 - 0.5f * r2);
            const vf bb1 = SEL(lower, r2 - 0.5f * r1, 0.5f * r2);
            const vf bb2 = 1.0f - bb0 - bb1;
            const V3 p_light = v3_add(v3_add(v3_scale(v0, bb0), v3_scale(v1, bb1)), v3_scale(v2, bb2));
            const V3 to_light = v3_sub(p_light, p);
            const vf dist = v3_length(to_light);
            const V3 wi_world = v3_div(to_light, dist);
            const vf cos_light = v3_dot(lng, v3_neg(wi_world));
            const vi sampled = cont & (dist > 0.0f) & pk_emits_toward(l_two_sided, cos_light);
            const vf pdf_w = group_pmf * pk_light_pdf_w(le, params->emitter_power, dist, cos_light);
            const vi usable = sampled & (pdf_w > 0.0f);
            if (any(usable)) {
                const V3 target = pk_offset_ray_origin(p_light, pk_side_normal(lng, v3_neg(wi_world)));
                const V3 wi = pk_to_local(frame, wi_world);
                const V3 f = pk_lambert_eval(albedo, wo, wi);
                const vf w = pk_power_heuristic(pdf_w, pk_lambert_pdf(wo, wi));
                contribution = v3_mul(v3_scale(v3_mul(ps->beta, f), fabs(wi.z) * w / pdf_w), le);
                shadow = usable & v3_any_positive(contribution);
                shadow_org = pk_offset_ray_origin(p, pk_side_normal(ng, wi_world));
                const V3 d = v3_sub(target, shadow_org);
                shadow_len = v3_length(d);
                shadow_dir = v3_div(d, shadow_len);
            }
        }
#if PK_PACKET_SHADOW
        if (any(shadow)) shadow &= ~pk_occluded8(GC_BVH_ARGS, shadow_org, shadow_dir, shadow_len, shadow);
#else
        for (uint k = 0u; k < LANES; ++k) {
            if (!shadow[k]) continue;
            const GcRay ray = gc_make_ray(make_float3(shadow_org.x[k], shadow_org.y[k], shadow_org.z[k]),
                                          make_float3(shadow_dir.x[k], shadow_dir.y[k], shadow_dir.z[k]), 0.0f,
                                          shadow_len[k]);
            if (gc_trace_any(GC_BVH_ARGS, ray)) shadow[k] = 0;
        }
#endif

        /* Continue the path by sampling the BSDF (Lambert). */
        vf r0, r1, r2, r3;
        pk_rand4(ps->pixel, ps->sample, 1u + bounce * GC_RNG_BLOCKS_PER_BOUNCE + GC_RNG_BLOCK_BSDF, params->seed, &r0,
                 &r1, &r2, &r3);
        const vf side = SEL(wo.z < 0.0f, (vf)(-1.0f), (vf)(1.0f));
        const vi wo_up = wo.z * side > 0.0f;
        const V3 wi_up = pk_cosine_hemisphere(r1, r2);
        const V3 wi = v3(wi_up.x, wi_up.y, wi_up.z * side);
        const V3 f = pk_lambert_eval(albedo, wo, wi);
        const vf pdf = pk_lambert_pdf(wo, wi);
        const vi sampled = wo_up & (pdf > 0.0f);
        const V3 weight = v3_scale(f, fabs(wi.z) / pdf);
        /* The shadow ray's light joins the radiance after the vertex, as in megakernel.cl. */
        ps->L = v3_sel(shadow, v3_add(ps->L, contribution), ps->L);
        ps->beta = v3_sel(sampled, v3_mul(ps->beta, weight), v3(0.0f, 0.0f, 0.0f));
        survive = cont & sampled & v3_any_positive(ps->beta);
        const vi roulette = survive & (ps->depth >= (vu)(params->rr_depth));
        if (any(roulette)) {
            vf q0, q1, q2, q3;
            pk_rand4(ps->pixel, ps->sample, 1u + bounce * GC_RNG_BLOCKS_PER_BOUNCE + GC_RNG_BLOCK_ROULETTE, params->seed,
                     &q0, &q1, &q2, &q3);
            const vf keep = fmin(fmax(ps->beta.x, fmax(ps->beta.y, ps->beta.z)) * 1.0f, 0.95f);
            survive = survive & ~(roulette & (q0 >= keep));
            ps->beta = v3_sel(roulette, v3_div(ps->beta, keep), ps->beta);
        }
        const V3 wi_w = pk_to_world(frame, wi);
        ps->org = v3_sel(survive, pk_offset_ray_origin(p, pk_side_normal(ng, wi_w)), ps->org);
        ps->dir = v3_sel(survive, wi_w, ps->dir);
        ps->pdf_last = SEL(survive, pdf, ps->pdf_last);
        ps->specular = ps->specular & ~survive;
    }
    return survive;
}

#if PK_PIXEL_LANES
/* Mitsuba's layout: a work-item renders one pixel, its lanes eight consecutive samples of it
 * in lock step (no refill), so the camera rays of a packet leave through one pixel and their
 * first hits and first shadow rays start from one small patch. PK_PACKET_PRIMARY traces the
 * camera rays as one packet. Each pixel's samples reach the film in sample order. */
__kernel void path_megakernel(const GcRenderParams params,
                              GC_SCENE_PARAMS,
                              __global float4* film,
                              __global float4* film_squares)
{
    /* The host sizes the launch for the scalar megakernel's pixels_per_item neighbours per
     * work-item (gc_packet_lanes.h); this layout renders them one after the other. */
    const uint per_item = max(params.pixels_per_item, 1u);
    const uint first = get_global_id(0) * per_item;
    const uint last = min(first + per_item, params.pixel_count);
    for (uint slot = first; slot < last; ++slot) {
        const uint px = params.pixel_offset + slot;
        float4 sum = film[px];
        float4 squares = film_squares[px];
        for (uint s0 = 0u; s0 < params.samples_in_pass; s0 += LANES) {
            const uint lanes = min(LANES, params.samples_in_pass - s0);
            PkPaths ps = pk_no_paths();
            for (uint k = 0u; k < lanes; ++k) pk_start(&ps, k, &params, px, params.sample_index + s0 + k);
            V3 done = v3(0.0f, 0.0f, 0.0f);
            bool camera_rays = true;
            while (any(ps.alive)) {
                const vi was = ps.alive;
                const vi survive = pk_segment(&params, GC_SCENE_ARGS, &ps, camera_rays ? PK_PACKET_PRIMARY : PK_PACKET_CLOSEST);
                camera_rays = false;
                done = v3_sel(was & ~survive, ps.L, done);
                ps.alive = survive;
            }
            for (uint k = 0u; k < lanes; ++k) {
                const float3 value = gc_film_value(make_float3(done.x[k], done.y[k], done.z[k]));
                sum += (float4)(value, 1.0f);
                squares += (float4)(value * value, 0.0f);
            }
        }
        film[px] = sum;
        film_squares[px] = squares;
    }
}
#else
/* Pixels per active work-item: its lanes take them one after the other, a new path
 * starting in a lane as soon as the lane's path ends (one sample of every pixel per round, so
 * a pixel's samples still reach the film in sample order). */
#define GROUP 64u

__kernel void path_megakernel(const GcRenderParams params,
                              GC_SCENE_PARAMS,
                              __global float4* film,
                              __global float4* film_squares)
{
    /* The group of GROUP work-items, each sized by the host for pixels_per_item neighbours
     * (gc_packet_lanes.h), is rendered by its first work-item. */
    const uint per_item = max(params.pixels_per_item, 1u);
    if ((get_global_id(0) % GROUP) != 0u) return;
    const uint slot0 = get_global_id(0) * per_item;
    if (slot0 >= params.pixel_count) return;
    const uint group_end = min(slot0 + GROUP * per_item, params.pixel_count);
    for (uint s = 0u; s < params.samples_in_pass; ++s) {
        const uint sample = params.sample_index + s;
        uint next = slot0;
        PkPaths ps = pk_no_paths();
        for (;;) {
            /* Refill idle lanes with the group's next pixels (generate.cl). */
            for (uint k = 0u; k < LANES && next < group_end; ++k) {
                if (ps.alive[k]) continue;
                pk_start(&ps, k, &params, params.pixel_offset + next, sample);
                ++next;
            }
            if (!any(ps.alive)) break;
            const vi survive = pk_segment(&params, GC_SCENE_ARGS, &ps, PK_PACKET_CLOSEST);
            /* accumulate.cl for the lanes whose path ended */
            const vi ended = ps.alive & ~survive;
            for (uint k = 0u; k < LANES; ++k) {
                if (!ended[k]) continue;
                const float3 value = gc_film_value(make_float3(ps.L.x[k], ps.L.y[k], ps.L.z[k]));
                film[ps.pixel[k]] += (float4)(value, 1.0f);
                film_squares[ps.pixel[k]] += (float4)(value * value, 0.0f);
            }
            ps.alive = survive;
        }
    }
}
#endif
