/*
 * EXPERIMENT, not part of the renderer: kernels/megakernel.cl with eight paths per work-item
 * in float8 lanes, to measure what explicit SIMD across paths gives a whole path tracer on a
 * CPU. tools/bench/experiments/packet-megakernel.sh swaps it in for megakernel.cl (same
 * kernel name and arguments), checks the image bits and times both with kernel-ab.sh.
 *
 * The work-items whose slot is a multiple of GROUP each take GROUP consecutive pixels of the
 * pass (the others return at once); their eight lanes start a pixel's path as soon as the
 * lane's previous path ends. Rays are traced lane by lane with the renderer's gc_trace_closest
 * and gc_trace_any; everything else of gc_shade_vertex is done for eight paths at a time:
 * the Lambert case only (untextured Lambert materials, triangle emitters, a constant
 * environment, no alpha: the Cornell box and the bench's dragon). Each lane performs the
 * scalar code's operations in its order, so the film is the scalar megakernel's, bit for bit.
 *
 * Result (README there): 1.06-1.14x the scalar megakernel's samples/s on the Cornell box and
 * 0.97-1.02x on the dragon, against 3-8x for the shading math alone (packet_probe.cl): the
 * per-lane gathers, ray set-up and traversal, which stay scalar, dominate.
 */
#include "gc_alpha.h"
#include "gc_traverse.h"
#include "gc_path_vertex.h"
#include "gc_camera.h"
#include "gc_rng.h"

typedef float8 vf;
typedef int8 vi;
typedef uint8 vu;

#define SEL(m, a, b) select((b), (a), (m)) /* lane-wise m ? a : b */
#define LANES 8u

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

static void pk_rand4(vu pixel, uint sample, vu block, uint seed, vf* r0, vf* r1, vf* r2, vf* r3)
{
    vu x = pixel;
    vu y = (vu)(sample);
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

/* Pixels per active work-item: its lanes take them one after the other, a new path
 * starting in a lane as soon as the lane's path ends (one sample of every pixel per round, so
 * a pixel's samples still reach the film in sample order). */
#define GROUP 64u

__kernel void path_megakernel(const GcRenderParams params,
                              GC_SCENE_PARAMS,
                              __global float4* film,
                              __global float4* film_squares)
{
    const uint slot0 = get_global_id(0);
    if ((slot0 % GROUP) != 0u || slot0 >= params.pixel_count) return;
    const uint group_end = min(slot0 + GROUP, params.pixel_count);
    const float group_pmf = gc_light_group_pmf(params);
    const V3 env = v3(params.env_radiance.x, params.env_radiance.y, params.env_radiance.z);

    for (uint s = 0u; s < params.samples_in_pass; ++s) {
        const uint sample = params.sample_index + s;
        uint next = slot0;
        vu pixel = 0u;
        vu depth = 0u;
        V3 org, dir;
        V3 beta = v3(0.0f, 0.0f, 0.0f);
        V3 L = v3(0.0f, 0.0f, 0.0f);
        vf pdf_last = 0.0f;
        vi specular = 0;
        vi alive = 0;
        for (;;) {
            /* Refill idle lanes with the group's next pixels (generate.cl). */
            for (uint k = 0u; k < LANES && next < group_end; ++k) {
                if (alive[k]) continue;
                const uint px = params.pixel_offset + next;
                ++next;
                const float4 jitter = gc_rand4(px, sample, GC_RNG_BLOCK_CAMERA, params.seed);
                const GcRay ray = gc_camera_ray(params.camera, params.width, params.height, px % params.width,
                                                px / params.width, jitter.x, jitter.y);
                org.x[k] = ray.org_tmin.x; org.y[k] = ray.org_tmin.y; org.z[k] = ray.org_tmin.z;
                dir.x[k] = ray.dir_tmax.x; dir.y[k] = ray.dir_tmax.y; dir.z[k] = ray.dir_tmax.z;
                pixel[k] = px;
                depth[k] = 0u;
                beta.x[k] = 1.0f; beta.y[k] = 1.0f; beta.z[k] = 1.0f;
                L.x[k] = 0.0f; L.y[k] = 0.0f; L.z[k] = 0.0f;
                pdf_last[k] = 0.0f;
                specular[k] = -1;
                alive[k] = -1;
            }
            if (!any(alive)) break;
            depth = SEL(alive, depth + 1u, depth);
            const vu bounce = depth - 1u;

            /* extend.cl, per lane */
            float h_t[LANES], h_u[LANES], h_v[LANES];
            uint h_prim[LANES];
            float r_ox[LANES], r_oy[LANES], r_oz[LANES], r_dx[LANES], r_dy[LANES], r_dz[LANES];
            vstore8(org.x, 0, r_ox); vstore8(org.y, 0, r_oy); vstore8(org.z, 0, r_oz);
            vstore8(dir.x, 0, r_dx); vstore8(dir.y, 0, r_dy); vstore8(dir.z, 0, r_dz);
            for (uint k = 0u; k < LANES; ++k) {
                h_t[k] = 0.0f; h_u[k] = 0.0f; h_v[k] = 0.0f; h_prim[k] = GC_INVALID;
                if (!alive[k]) continue;
                const GcRay ray = gc_make_ray(make_float3(r_ox[k], r_oy[k], r_oz[k]),
                                              make_float3(r_dx[k], r_dy[k], r_dz[k]), 0.0f, GC_RAY_UNBOUNDED);
                const GcHit hit = gc_trace_closest(GC_BVH_ARGS, ray);
                h_t[k] = hit.t; h_u[k] = hit.u; h_v[k] = hit.v; h_prim[k] = hit.prim;
            }
            const vf t = vload8(0, h_t), u = vload8(0, h_u), v = vload8(0, h_v);
            const vu prim = vload8(0, h_prim);
            const vi active = alive & (prim != (vu)(GC_INVALID));
            L = v3_sel(alive & ~active, v3_add(L, v3_mul(beta, env)), L); /* escaped */

            /* The surface and its material, gathered per lane through private arrays (one
             * vector load per field; writing lanes of a vector by index spills it each time). */
            float a_n0x[LANES], a_n0y[LANES], a_n0z[LANES], a_n1x[LANES], a_n1y[LANES], a_n1z[LANES];
            float a_n2x[LANES], a_n2y[LANES], a_n2z[LANES], a_ngx[LANES], a_ngy[LANES], a_ngz[LANES];
            float a_ar[LANES], a_ag[LANES], a_ab[LANES], a_er[LANES], a_eg[LANES], a_eb[LANES];
            int a_two[LANES];
            for (uint k = 0u; k < LANES; ++k) {
                const GcTriangleAttribs a = GC_ATTRIB(active[k] ? prim[k] : 0u);
                const GcMaterial m = GC_MATERIAL(a.material);
                a_n0x[k] = a.n0.x; a_n0y[k] = a.n0.y; a_n0z[k] = a.n0.z;
                a_n1x[k] = a.n1.x; a_n1y[k] = a.n1.y; a_n1z[k] = a.n1.z;
                a_n2x[k] = a.n2.x; a_n2y[k] = a.n2.y; a_n2z[k] = a.n2.z;
                a_ngx[k] = a.ng.x; a_ngy[k] = a.ng.y; a_ngz[k] = a.ng.z;
                a_ar[k] = m.albedo.x; a_ag[k] = m.albedo.y; a_ab[k] = m.albedo.z;
                a_er[k] = m.emission.x; a_eg[k] = m.emission.y; a_eb[k] = m.emission.z;
                a_two[k] = (m.flags & GC_MATF_TWO_SIDED) != 0u ? -1 : 0;
            }
            const V3 n0 = v3(vload8(0, a_n0x), vload8(0, a_n0y), vload8(0, a_n0z));
            const V3 n1 = v3(vload8(0, a_n1x), vload8(0, a_n1y), vload8(0, a_n1z));
            const V3 n2 = v3(vload8(0, a_n2x), vload8(0, a_n2y), vload8(0, a_n2z));
            const V3 ng = v3(vload8(0, a_ngx), vload8(0, a_ngy), vload8(0, a_ngz));
            const V3 albedo = v3(vload8(0, a_ar), vload8(0, a_ag), vload8(0, a_ab));
            const V3 emission = v3(vload8(0, a_er), vload8(0, a_eg), vload8(0, a_eb));
            const vi two_sided = vload8(0, a_two);
            /* gc_surface_at */
            const vf b0 = 1.0f - u - v;
            const V3 p = v3_add(org, v3_scale(dir, t));
            const V3 n = v3_add(v3_add(v3_scale(n0, b0), v3_scale(n1, u)), v3_scale(n2, v));
            const vf len = v3_length(n);
            V3 ns = v3_sel(len > 0.0f, v3_scale(n, 1.0f / len), ng);
            ns = v3_sel(v3_dot(ns, ng) < 0.0f, v3_neg(ns), ns);
            const V3 wo_world = v3_neg(dir);

            /* Emission seen by this ray. */
            const vf cos_out = v3_dot(ng, wo_world);
            const vi emits = active & v3_any_positive(emission) & pk_emits_toward(two_sided, cos_out);
            if (any(emits)) {
                vf w = 1.0f;
                if (params.num_emitters > 0u)
                    w = SEL(specular, w,
                            pk_power_heuristic(pdf_last, group_pmf * pk_light_pdf_w(emission, params.emitter_power, t, cos_out)));
                L = v3_sel(emits, v3_add(L, v3_scale(v3_mul(beta, emission), w)), L);
            }
            const vi cont = active & (depth < (vu)(params.max_depth));
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
                    pk_rand4(pixel, sample, 1u + bounce * GC_RNG_BLOCKS_PER_BOUNCE + GC_RNG_BLOCK_LIGHT, params.seed,
                             &r0, &r1, &r2, &r3);
                    const uint groups = gc_uint(1.0f / group_pmf + 0.5f);
                    const vf ug = r0 * gc_float(groups);
                    vu group = convert_uint8_rtz(ug);
                    group = SEL(group >= groups, (vu)(groups - 1u), group);
                    const vf ue = fmin(ug - convert_float8(group), 0.99999994f);
                    float e_v0x[LANES], e_v0y[LANES], e_v0z[LANES], e_v1x[LANES], e_v1y[LANES], e_v1z[LANES];
                    float e_v2x[LANES], e_v2y[LANES], e_v2z[LANES], e_ngx[LANES], e_ngy[LANES], e_ngz[LANES];
                    float e_r[LANES], e_g[LANES], e_b[LANES];
                    int e_two[LANES];
                    for (uint k = 0u; k < LANES; ++k) {
                        const GcEmitter e = GC_EMITTER(gc_pick_emitter(GC_EMITTERS_ARG, params.num_emitters, cont[k] ? ue[k] : 0.0f));
                        const GcTriangleAttribs la = GC_ATTRIB(e.triangle);
                        const GcMaterial lm = GC_MATERIAL(la.material);
                        e_v0x[k] = e.v0.x; e_v0y[k] = e.v0.y; e_v0z[k] = e.v0.z;
                        e_v1x[k] = e.v1.x; e_v1y[k] = e.v1.y; e_v1z[k] = e.v1.z;
                        e_v2x[k] = e.v2.x; e_v2y[k] = e.v2.y; e_v2z[k] = e.v2.z;
                        e_ngx[k] = la.ng.x; e_ngy[k] = la.ng.y; e_ngz[k] = la.ng.z;
                        e_r[k] = lm.emission.x; e_g[k] = lm.emission.y; e_b[k] = lm.emission.z;
                        e_two[k] = (lm.flags & GC_MATF_TWO_SIDED) != 0u ? -1 : 0;
                    }
                    const V3 v0 = v3(vload8(0, e_v0x), vload8(0, e_v0y), vload8(0, e_v0z));
                    const V3 v1 = v3(vload8(0, e_v1x), vload8(0, e_v1y), vload8(0, e_v1z));
                    const V3 v2 = v3(vload8(0, e_v2x), vload8(0, e_v2y), vload8(0, e_v2z));
                    const V3 lng = v3(vload8(0, e_ngx), vload8(0, e_ngy), vload8(0, e_ngz));
                    const V3 le = v3(vload8(0, e_r), vload8(0, e_g), vload8(0, e_b));
                    const vi l_two_sided = vload8(0, e_two);
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
                    const vf pdf_w = group_pmf * pk_light_pdf_w(le, params.emitter_power, dist, cos_light);
                    const vi usable = sampled & (pdf_w > 0.0f);
                    if (any(usable)) {
                        const V3 target = pk_offset_ray_origin(p_light, pk_side_normal(lng, v3_neg(wi_world)));
                        const V3 wi = pk_to_local(frame, wi_world);
                        const V3 f = pk_lambert_eval(albedo, wo, wi);
                        const vf w = pk_power_heuristic(pdf_w, pk_lambert_pdf(wo, wi));
                        contribution = v3_mul(v3_scale(v3_mul(beta, f), fabs(wi.z) * w / pdf_w), le);
                        shadow = usable & v3_any_positive(contribution);
                        shadow_org = pk_offset_ray_origin(p, pk_side_normal(ng, wi_world));
                        const V3 d = v3_sub(target, shadow_org);
                        shadow_len = v3_length(d);
                        shadow_dir = v3_div(d, shadow_len);
                    }
                }
                for (uint k = 0u; k < LANES; ++k) {
                    if (!shadow[k]) continue;
                    const GcRay ray = gc_make_ray(make_float3(shadow_org.x[k], shadow_org.y[k], shadow_org.z[k]),
                                                  make_float3(shadow_dir.x[k], shadow_dir.y[k], shadow_dir.z[k]), 0.0f,
                                                  shadow_len[k]);
                    if (gc_trace_any(GC_BVH_ARGS, ray)) shadow[k] = 0;
                }

                /* Continue the path by sampling the BSDF (Lambert). */
                vf r0, r1, r2, r3;
                pk_rand4(pixel, sample, 1u + bounce * GC_RNG_BLOCKS_PER_BOUNCE + GC_RNG_BLOCK_BSDF, params.seed, &r0,
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
                L = v3_sel(shadow, v3_add(L, contribution), L);
                beta = v3_sel(sampled, v3_mul(beta, weight), v3(0.0f, 0.0f, 0.0f));
                survive = cont & sampled & v3_any_positive(beta);
                const vi roulette = survive & (depth >= (vu)(params.rr_depth));
                if (any(roulette)) {
                    vf q0, q1, q2, q3;
                    pk_rand4(pixel, sample, 1u + bounce * GC_RNG_BLOCKS_PER_BOUNCE + GC_RNG_BLOCK_ROULETTE, params.seed,
                             &q0, &q1, &q2, &q3);
                    const vf keep = fmin(fmax(beta.x, fmax(beta.y, beta.z)) * 1.0f, 0.95f);
                    survive = survive & ~(roulette & (q0 >= keep));
                    beta = v3_sel(roulette, v3_div(beta, keep), beta);
                }
                const V3 wi_w = pk_to_world(frame, wi);
                org = v3_sel(survive, pk_offset_ray_origin(p, pk_side_normal(ng, wi_w)), org);
                dir = v3_sel(survive, wi_w, dir);
                pdf_last = SEL(survive, pdf, pdf_last);
                specular = specular & ~survive;
            }
            /* accumulate.cl for the lanes whose path ended */
            const vi ended = alive & ~survive;
            for (uint k = 0u; k < LANES; ++k) {
                if (!ended[k]) continue;
                const float3 value = gc_film_value(make_float3(L.x[k], L.y[k], L.z[k]));
                film[pixel[k]] += (float4)(value, 1.0f);
                film_squares[pixel[k]] += (float4)(value * value, 0.0f);
            }
            alive = survive;
        }
    }
}
