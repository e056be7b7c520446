/*
 * whitted.cl — the `whitted` integrator: Whitted 1980, "An Improved Illumination Model for
 * Shaded Display" (CACM 23(6)), in radiometric units (the pure pieces are in gc_whitted.h).
 *
 * One work-item per pixel of the batch; it owns film[pixel] and adds (radiance, 1), so the
 * sum needs no atomics and the image is the same bits run to run.
 *
 * Model, per camera sample (pixel jitter from gc_rand4(pixel, sample, GC_RNG_BLOCK_CAMERA),
 * a box filter, so more spp anti-alias):
 *   - a ray that leaves the scene adds weight * env (--env);
 *   - a hit adds weight * Le when it sees the front face of an emitter (gc_emits_toward);
 *   - if the ray was segment `depth` and depth < max_depth (shade.cl's convention: camera
 *     ray = segment 1, so --max-depth 1 shows only emitters and the environment), it adds
 *     weight * local, with
 *       local = ambient + sum over point lights + one area-light sample,
 *       ambient = env * kd: the --env radiance doubles as Whitted's ambient light I_a;
 *       point light: f |cos| I / d^2, one shadow ray each;
 *       area emitters: ONE point per camera sample and depth for the whole emitter set,
 *         emitter picked by power (gc_pick_emitter), uniform on its triangle, random numbers
 *         from gc_rng_block(depth - 1, GC_RNG_BLOCK_LIGHT), weighted f |cos| Le |cos_l| /
 *         (d^2 pdf_area): unbiased, so soft shadows converge as spp grows;
 *       f = kd/pi + ks (n+2)/(2 pi) cos^n (the normalised modified Phong of gc_bsdf.h;
 *         Lambert has ks = 0, a mirror shades only its kd here, a dielectric nothing);
 *     and it spawns segment depth + 1: a mirror's reflection weighted by Ks, a dielectric's
 *     Fresnel reflection and Snell refraction (both pushed; total internal reflection
 *     sends all into the reflection).
 *   Opaque materials are two-sided (gc_bsdf.h flips to the viewer's side); light from
 *   behind the geometric surface does not reach it.
 *
 * No recursion (OpenCL C has none): the ray tree is walked depth-first with an explicit
 * private stack of (ray, weight, depth). Depth-first holds at most one pending sibling per
 * level, so the stack never holds more than max_depth entries and GC_WHITTED_STACK = 16
 * covers --max-depth <= 16 exactly. Beyond that, a push onto a full stack keeps the
 * heavier of the new entry and the lightest stacked one (by max weight component) and drops
 * the other: deep glass paths lose their dimmest branches instead of overflowing.
 *
 * Sibling rays of one dielectric (same depth) share their area-light random numbers: each
 * estimate stays unbiased, only correlated.
 */
#include "gc_camera.h"
#include "gc_path.h"
#include "gc_rng.h"
#include "gc_shading.h"
#include "gc_texture.h"
#include "gc_alpha.h" /* before gc_traverse.h: alpha-MASK cut-outs, as the path kernels */
#include "gc_traverse.h"
#include "gc_whitted.h"

#define GC_WHITTED_STACK 16u

static float3 gc_whitted_albedo(GC_TEXELS_PARAM, __global const GcTexture* textures, GcMaterial m, float2 uv)
{
    float3 albedo = m.albedo.xyz;
    if (m.albedo_texture != GC_INVALID)
        albedo *= gc_texture_sample(GC_TEXELS_ARG, textures[m.albedo_texture], uv.x, uv.y).xyz;
    return albedo;
}

/* The geometric normal on the side that direction w leaves into. */
static float3 gc_whitted_side(float3 ng, float3 w) { return gc_dot(ng, w) >= 0.0f ? ng : -ng; }

static bool gc_whitted_nonzero(float3 v) { return v.x > 0.0f || v.y > 0.0f || v.z > 0.0f; }

static float gc_whitted_priority(float3 w) { return fmax(w.x, fmax(w.y, w.z)); }

/* True when nothing blocks the segment from `origin` to `target` (both already offset off
 * their surfaces). */
static bool gc_whitted_unoccluded(GC_BVH_PARAMS, float3 origin, float3 target)
{
    const float3 d = target - origin;
    const float len = gc_length(d);
    if (!(len > 0.0f)) return true;
    return !gc_trace_any(GC_BVH_ARGS, gc_make_ray(origin, d / len, 0.0f, len));
}

/* Pushes (ray, weight, depth); on a full stack replaces the lightest entry if the new one is
 * heavier, else drops the new one (see the file comment). */
static void gc_whitted_push(GcRay* stack_ray, float3* stack_weight, uint* stack_depth, uint* sp, GcRay ray,
                            float3 weight, uint depth)
{
    if (!gc_whitted_nonzero(weight)) return;
    uint slot = *sp;
    if (slot >= GC_WHITTED_STACK) {
        uint lightest = 0u;
        for (uint k = 1u; k < GC_WHITTED_STACK; ++k)
            if (gc_whitted_priority(stack_weight[k]) < gc_whitted_priority(stack_weight[lightest])) lightest = k;
        if (!(gc_whitted_priority(weight) > gc_whitted_priority(stack_weight[lightest]))) return;
        slot = lightest;
    } else {
        *sp = slot + 1u;
    }
    stack_ray[slot] = ray;
    stack_weight[slot] = weight;
    stack_depth[slot] = depth;
}

/* One pixel's sample, out of line on CPUs (GC_ITEM_BODY, gc_platform.h): PoCL compiled three
 * 10 KB copies of it inlined. */
GC_ITEM_BODY gc_whitted_item(const uint i,
                             const GcRenderParams params,
                             GC_BVH_PARAMS,
                             GC_EMITTERS_PARAM,
                             __global const GcPointLight* point_lights,
                             __global float4* film)
{
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    const uint px = pixel % params.width;
    const uint py = pixel / params.width;
    const float3 env = params.env_radiance.xyz;

    GcRay stack_ray[GC_WHITTED_STACK];
    float3 stack_weight[GC_WHITTED_STACK];
    uint stack_depth[GC_WHITTED_STACK];
    uint sp = 0u;

    const float4 jitter = gc_rand4(pixel, params.sample_index, GC_RNG_BLOCK_CAMERA, params.seed);
    gc_whitted_push(stack_ray, stack_weight, stack_depth, &sp,
                    gc_camera_ray(params.camera, params.width, params.height, px, py, jitter.x, jitter.y),
                    (float3)(1.0f), 1u);

    float3 L = (float3)(0.0f);
    while (sp > 0u) {
        --sp;
        const GcRay ray = stack_ray[sp];
        const float3 weight = stack_weight[sp];
        const uint depth = stack_depth[sp];

        const GcHit hit = gc_trace_closest(GC_BVH_ARGS, ray);
        if (hit.prim == GC_INVALID) {
            L += weight * env;
            continue;
        }
        const GcSurface s = gc_surface_at(attribs[hit.prim], ray, hit);
        const GcMaterial m = materials[s.material];
        const float3 wo = -gc_normalize(ray.dir_tmax.xyz);

        if (gc_whitted_nonzero(m.emission.xyz) && gc_emits_toward(m, gc_dot(s.ng, wo))) L += weight * m.emission.xyz;
        if (depth >= params.max_depth) continue;

        /* Local shading: ambient + shadowed direct light. */
        if (m.type != GC_MAT_DIELECTRIC) {
            const float3 albedo = gc_whitted_albedo(texels, textures, m, s.uv);
            float3 direct = gc_whitted_ambient(m, albedo, env);

            for (uint k = 0u; k < params.num_point_lights; ++k) {
                const GcPointLight light = point_lights[k];
                const float3 to_light = light.position.xyz - s.p;
                const float dist2 = gc_dot(to_light, to_light);
                if (!(dist2 > 0.0f)) continue;
                const float3 wi = to_light / sqrt(dist2);
                const float3 brdf_cos = gc_whitted_brdf_cos(m, albedo, s.ns, s.ng, wo, wi);
                const float3 c = gc_whitted_point_light(brdf_cos, light.intensity.xyz, dist2);
                if (gc_whitted_nonzero(c) &&
                    gc_whitted_unoccluded(GC_BVH_ARGS, gc_offset_ray_origin(s.p, gc_whitted_side(s.ng, wi), s.spawn_scale),
                                          light.position.xyz))
                    direct += c;
            }

            if (params.num_emitters > 0u) {
                const float4 r = gc_rand4(pixel, params.sample_index, gc_rng_block(depth - 1u, GC_RNG_BLOCK_LIGHT),
                                          params.seed);
                const GcEmitter e = emitters[gc_pick_emitter(emitters, params.num_emitters, r.x)];
                const float3 b = gc_sample_uniform_triangle(r.y, r.z);
                const float3 p_light = b.x * e.v0.xyz + b.y * e.v1.xyz + b.z * e.v2.xyz;
                const GcTriangleAttribs la = attribs[e.triangle];
                const GcMaterial lm = materials[la.material];
                const float3 to_light = p_light - s.p;
                const float dist2 = gc_dot(to_light, to_light);
                if (dist2 > 0.0f && e.area > 0.0f) {
                    const float3 wi = to_light / sqrt(dist2);
                    const float cos_light = gc_dot(la.ng.xyz, -wi);
                    if (gc_emits_toward(lm, cos_light)) {
                        const float3 brdf_cos = gc_whitted_brdf_cos(m, albedo, s.ns, s.ng, wo, wi);
                        const float3 c = gc_whitted_area_light(brdf_cos, lm.emission.xyz, cos_light, dist2,
                                                               e.pmf / e.area);
                        if (gc_whitted_nonzero(c) &&
                            gc_whitted_unoccluded(GC_BVH_ARGS, gc_offset_ray_origin(s.p, gc_whitted_side(s.ng, wi), s.spawn_scale),
                                                  gc_offset_ray_origin(p_light, gc_whitted_side(la.ng.xyz, -wi), gc_spawn_scale(s.p, la.ng.w))))
                            direct += c;
                    }
                }
            }
            L += weight * direct;
        }

        /* Secondary rays: segment depth + 1 <= max_depth. */
        const GcWhittedSpecular spec = gc_whitted_specular(m, s.ns, wo);
        gc_whitted_push(stack_ray, stack_weight, stack_depth, &sp,
                        gc_make_ray(gc_offset_ray_origin(s.p, gc_whitted_side(s.ng, spec.refract_dir), s.spawn_scale),
                                    spec.refract_dir, 0.0f, GC_RAY_UNBOUNDED),
                        weight * spec.refract_weight, depth + 1u);
        gc_whitted_push(stack_ray, stack_weight, stack_depth, &sp,
                        gc_make_ray(gc_offset_ray_origin(s.p, gc_whitted_side(s.ng, spec.reflect_dir), s.spawn_scale),
                                    spec.reflect_dir, 0.0f, GC_RAY_UNBOUNDED),
                        weight * spec.reflect_weight, depth + 1u);
    }
    film[pixel] += (float4)(L, 1.0f);
}

__kernel void whitted_render(const GcRenderParams params,
                             GC_BVH_PARAMS,
                             GC_EMITTERS_PARAM,
                             __global const GcPointLight* point_lights,
                             __global float4* film)
{
    gc_whitted_item(get_global_id(0), params, GC_BVH_ARGS, GC_EMITTERS_ARG, point_lights, film);
}
