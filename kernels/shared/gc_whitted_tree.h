/*
 * gc_whitted_tree.h — one camera sample of the `whitted` integrator: Whitted 1980, "An
 * Improved Illumination Model for Shaded Display" (CACM 23(6)), in radiometric units, with
 * the pure pieces from gc_whitted.h. The OpenCL kernel (kernels/whitted.cl) and the Vulkan
 * reference (kernels/vk/whitted.comp) both call gc_whitted_sample, so the two trace the same
 * tree with the same random numbers.
 *
 * Model, per camera sample (pixel jitter from gc_sample4(params, pixel, sample, GC_RNG_BLOCK_CAMERA),
 * a box filter, so more spp anti-alias):
 *   - a ray that leaves the scene adds weight * env (--env: the constant radiance, or the
 *     map's scale; the texels of a map are not looked up);
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
 * No recursion (neither OpenCL C nor GLSL has it): the ray tree is walked depth-first with an
 * explicit private stack of (ray, weight, depth). Depth-first holds at most one pending
 * sibling per level, so the stack never holds more than max_depth entries and
 * GC_WHITTED_STACK = 16 covers --max-depth <= 16 exactly. Beyond that, a push onto a full
 * stack keeps the heavier of the new entry and the lightest stacked one (gc_whitted_priority)
 * and drops the other: deep glass paths lose their dimmest branches instead of overflowing.
 *
 * Sibling rays of one dielectric (same depth) share their area-light random numbers: each
 * estimate stays unbiased, only correlated.
 *
 * Scene buffers come in as the scene-buffer group scene, GC_SCENE_PARAMS (gc_scene_buffers.h;
 * GLSL reads the SSBOs of kernels/vk/scene_bindings.glsl), after the instance buffers of an
 * instanced scene (gc_scene_trace.h). Its traversal skips alpha-MASK cut-outs, as the path
 * kernels' does (gc_traverse.h).
 */
#ifndef GC_WHITTED_TREE_H
#define GC_WHITTED_TREE_H

#include "gc_scene_trace.h"
#include "gc_camera.h"
#include "gc_lights.h"
#include "gc_material_eval.h"
#include "gc_path.h"
#include "gc_rng.h"
#include "gc_shading.h"
#include "gc_spawn.h"
#include "gc_whitted.h"

#define GC_WHITTED_STACK 16u

GC_NAMESPACE_BEGIN

/* True when nothing blocks the segment from `origin` to `target` (both already offset off
 * their surfaces). */
GC_FUNC bool gc_whitted_unoccluded(GC_INSTANCES_FIRST_PARAMS GC_BVH_PARAMS, float3 origin, float3 target)
{
    const float3 d = target - origin;
    const float len = gc_length(d);
    if (!(len > 0.0f)) return true;
    return !gc_scene_occluded(gc_make_ray(origin, d / len, 0.0f, len));
}

/* The radiance camera sample params.sample_index of `pixel` brings back. */
GC_FUNC float3 gc_whitted_sample(GC_INSTANCES_FIRST_PARAMS GC_SCENE_PARAMS, GcRenderParams params, uint pixel)
{
    const float3 env = GC_XYZ(params.env_radiance);

    GcRay stack_ray[GC_WHITTED_STACK];
    float3 stack_weight[GC_WHITTED_STACK];
    uint stack_depth[GC_WHITTED_STACK];

    const float4 jitter = gc_sample4(params, pixel, params.sample_index, GC_RNG_BLOCK_CAMERA);
    stack_ray[0] = gc_camera_sample(params.camera, params.width, params.height, pixel % params.width,
                                    pixel / params.width, jitter);
    stack_weight[0] = make_float3(1.0f, 1.0f, 1.0f);
    stack_depth[0] = 1u;
    uint sp = 1u;

    float3 L = make_float3(0.0f, 0.0f, 0.0f);
    while (sp > 0u) {
        --sp;
        const GcRay ray = stack_ray[sp];
        const float3 weight = stack_weight[sp];
        const uint depth = stack_depth[sp];

        const GcSceneHit closest = gc_scene_closest(ray);
        const GcHit hit = gc_scene_hit(closest);
        if (hit.prim == GC_INVALID) {
            L += weight * env;
            continue;
        }
        const GcSurface s = gc_surface_at(gc_scene_attribs(closest), ray, hit);
        const GcMaterial m = GC_MATERIAL(s.material);
        const float3 wo = -gc_normalize(GC_XYZ(ray.dir_tmax));

        if (gc_whitted_nonzero(GC_XYZ(m.emission)) && gc_emits_toward(m, gc_dot(s.ng, wo))) L += weight * GC_XYZ(m.emission);
        if (depth >= params.max_depth) continue;

        /* Local shading: ambient + shadowed direct light. */
        if (m.type != GC_MAT_DIELECTRIC) {
            const float3 albedo = gc_shade_albedo(GC_SHADE_ARGS, m, s.uv);
            float3 direct = gc_whitted_ambient(m, albedo, env);

            const uint light_count = gc_has_point_lights(params) ? params.num_point_lights : 0u;
            for (uint k = 0u; k < light_count; ++k) {
                const GcPointLight light = GC_POINT_LIGHT(k);
                const float3 to_light = GC_XYZ(light.position) - s.p;
                const float dist2 = gc_dot(to_light, to_light);
                if (!(dist2 > 0.0f)) continue;
                const float3 wi = to_light / sqrt(dist2);
                const float3 brdf_cos = gc_whitted_brdf_cos(m, albedo, s.ns, s.ng, wo, wi);
                const float3 c = gc_whitted_point_light(brdf_cos, GC_XYZ(light.intensity), dist2);
                if (gc_whitted_nonzero(c) &&
                    gc_whitted_unoccluded(GC_INSTANCES_FIRST_ARGS GC_BVH_ARGS, gc_offset_ray_origin(s.p, gc_side_normal(s.ng, wi), s.spawn_scale),
                                          GC_XYZ(light.position)))
                    direct += c;
            }

            if (params.num_emitters > 0u) {
                const float4 r = gc_sample4(params, pixel, params.sample_index, gc_rng_block(depth - 1u, GC_RNG_BLOCK_LIGHT));
                const GcEmitter e = GC_EMITTER(gc_pick_emitter(GC_EMITTERS_ARG, params.num_emitters, r.x));
                const float3 b = gc_sample_uniform_triangle(r.y, r.z);
                const float3 p_light = b.x * GC_XYZ(e.v0) + b.y * GC_XYZ(e.v1) + b.z * GC_XYZ(e.v2);
                const GcTriangleAttribs la = GC_ATTRIB(e.triangle);
                const GcMaterial lm = GC_MATERIAL(la.material);
                const float3 to_light = p_light - s.p;
                const float dist2 = gc_dot(to_light, to_light);
                if (dist2 > 0.0f && e.area > 0.0f) {
                    const float3 wi = to_light / sqrt(dist2);
                    const float cos_light = gc_dot(GC_XYZ(la.ng), -wi);
                    if (gc_emits_toward(lm, cos_light)) {
                        const float3 brdf_cos = gc_whitted_brdf_cos(m, albedo, s.ns, s.ng, wo, wi);
                        const float3 c = gc_whitted_area_light(brdf_cos, GC_XYZ(lm.emission), cos_light, dist2,
                                                               e.pmf / e.area);
                        if (gc_whitted_nonzero(c) &&
                            gc_whitted_unoccluded(GC_INSTANCES_FIRST_ARGS GC_BVH_ARGS, gc_offset_ray_origin(s.p, gc_side_normal(s.ng, wi), s.spawn_scale),
                                                  gc_offset_ray_origin(p_light, gc_side_normal(GC_XYZ(la.ng), -wi), gc_spawn_scale(s.p, la.ng.w))))
                            direct += c;
                    }
                }
            }
            L += weight * direct;
        }

        /* Secondary rays, segment depth + 1: the refraction is pushed first, so the reflection
         * is walked first. A full stack keeps the heavier of the new ray and its lightest entry
         * (see the file comment). */
        const GcWhittedSpecular spec = gc_whitted_specular(m, s.ns, wo);
        for (uint k = 0u; k < 2u; ++k) {
            const float3 dir = k == 0u ? spec.refract_dir : spec.reflect_dir;
            const float3 w = weight * (k == 0u ? spec.refract_weight : spec.reflect_weight);
            if (!gc_whitted_nonzero(w)) continue;
            uint slot = sp;
            if (slot >= GC_WHITTED_STACK) {
                slot = 0u;
                for (uint j = 1u; j < GC_WHITTED_STACK; ++j)
                    if (gc_whitted_priority(stack_weight[j]) < gc_whitted_priority(stack_weight[slot])) slot = j;
                if (!(gc_whitted_priority(w) > gc_whitted_priority(stack_weight[slot]))) continue;
            } else {
                sp = slot + 1u;
            }
            stack_ray[slot] = gc_make_ray(gc_offset_ray_origin(s.p, gc_side_normal(s.ng, dir), s.spawn_scale), dir, 0.0f,
                                          GC_RAY_UNBOUNDED);
            stack_weight[slot] = w;
            stack_depth[slot] = depth + 1u;
        }
    }
    return L;
}

GC_NAMESPACE_END

#endif /* GC_WHITTED_TREE_H */
