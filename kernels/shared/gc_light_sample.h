/*
 * gc_light_sample.h — next-event estimation's light sample from a shading point, and the
 * radiance a path gathers when it escapes the scene, MIS-weighted with the same densities
 * (gc_lights.h: group choice, environment-map density; gc_path.h: emitter choice by power).
 * One light group is chosen uniformly among those the scene has, then one light in it;
 * emitted radiance is evaluated through the material (gc_material_eval.h), so an emissive
 * texture lights the scene as it is seen.
 *
 * Scene buffers come in as the scene-buffer group shade (gc_scene_buffers.h), which holds the
 * lights group (gc_lights.h) and the emitters.
 */
#ifndef GC_LIGHT_SAMPLE_H
#define GC_LIGHT_SAMPLE_H

#include "gc_lights.h"
#include "gc_material_eval.h"
#include "gc_path.h"
#include "gc_sampling.h"
#include "gc_scene_buffers.h"
#include "gc_spawn.h"

GC_NAMESPACE_BEGIN

/* Radiance a path gathers when its ray leaves the scene in direction d: the environment,
 * MIS-weighted against environment-map sampling unless the last bounce was specular. */
GC_FUNC float3 gc_escaped_radiance(GC_SHADE_PARAMS, GcRenderParams params, GcPathState path, float3 d)
{
    GC_SHADE_UNUSED();
    const float3 Le = gc_env_radiance(GC_LIGHTS_ARGS, params, d);
    if (!gc_has_env_map(params) || (path.flags & GC_PATH_SPECULAR) != 0u) return Le;
    const float pdf_light = gc_light_group_pmf(params) * gc_env_pdf_w(GC_LIGHTS_ARGS, params, d);
    return Le * gc_power_heuristic(path.throughput.w, pdf_light);
}

/* Next-event estimation's light sample from the shading point p: r.x picks a light group
 * (emitters, point lights, environment map, in that order, uniformly among those present)
 * and, rescaled, the light within it; r.y, r.z pick the point on it. */
GC_FUNC GcLightSample gc_sample_light(GC_SHADE_PARAMS, GcRenderParams params, float3 p, float4 r)
{
    GC_SHADE_UNUSED();
    GcLightSample ls;
    ls.wi = make_float3(0.0f, 0.0f, 1.0f);
    ls.radiance = make_float3(0.0f, 0.0f, 0.0f);
    ls.target = p;
    ls.pdf_w = 0.0f;
    ls.dist = 0.0f;
    ls.kind = GC_LIGHT_NONE;
    ls.material = GC_INVALID;
    ls.uv = make_float2(0.0f, 0.0f);
    const float group_pmf = gc_light_group_pmf(params);
    if (!(group_pmf > 0.0f)) return ls;
    const uint groups = gc_uint(1.0f / group_pmf + 0.5f);
    float u = r.x * gc_float(groups);
    uint group = gc_uint(u);
    if (group >= groups) group = groups - 1u;
    u = fmin(u - gc_float(group), 0.99999994f);
    if (params.num_emitters == 0u) group += 1u;                  /* no emitter group */
    if (group == 1u && !gc_has_point_lights(params)) group = 2u; /* no point-light group */

    if (group == 0u) {
        const GcEmitter e = GC_EMITTER(gc_pick_emitter(GC_EMITTERS_ARG, params.num_emitters, u));
        const float3 b = gc_sample_uniform_triangle(r.y, r.z);
        const float3 p_light = b.x * GC_XYZ(e.v0) + b.y * GC_XYZ(e.v1) + b.z * GC_XYZ(e.v2);
        const GcTriangleAttribs la = GC_ATTRIB(e.triangle);
        const GcMaterial lm = GC_MATERIAL(la.material);
        const float3 to_light = p_light - p;
        const float dist = gc_length(to_light);
        if (!(dist > 0.0f)) return ls;
        ls.wi = to_light / dist;
        const float cos_light = gc_dot(GC_XYZ(la.ng), -ls.wi);
        if (!gc_emits_toward(lm, cos_light)) return ls;
        ls.uv = gc_triangle_uv(la, b);
        ls.radiance = gc_shade_emission(GC_SHADE_ARGS, lm, ls.uv);
        ls.pdf_w = group_pmf * gc_light_pdf_w(GC_XYZ(lm.emission), params.emitter_power, dist, cos_light);
        /* The shadow ray from p must stop short of the light's own triangle: its t there carries
         * error in proportion to both ends' magnitudes. */
        ls.target = gc_offset_ray_origin(p_light, gc_side_normal(GC_XYZ(la.ng), -ls.wi), gc_spawn_scale(p, la.ng.w));
        ls.dist = dist;
        ls.kind = GC_LIGHT_AREA;
        ls.material = la.material;
        return ls;
    }
    /* The constants drop each group's code from programs built for scenes without it. */
    if (GC_POINT_LIGHT_CODE != 0 && group == 1u) {
        uint i = gc_uint(u * gc_float(params.num_point_lights));
        if (i >= params.num_point_lights) i = params.num_point_lights - 1u;
        const GcPointLight light = GC_POINT_LIGHT(i);
        const float3 to_light = GC_XYZ(light.position) - p;
        const float dist = gc_length(to_light);
        if (!(dist > 0.0f)) return ls;
        ls.wi = to_light / dist;
        ls.radiance = GC_XYZ(light.intensity) * (1.0f / (dist * dist));
        ls.pdf_w = group_pmf / gc_float(params.num_point_lights);
        ls.target = GC_XYZ(light.position);
        ls.dist = dist;
        ls.kind = GC_LIGHT_POINT;
        return ls;
    }
    if (GC_ENV_MAP_CODE != 0) {
        /* Environment map: a row from the marginal cdf, a column from that row's conditional
         * cdf, continuous offsets inside the texel (pbrt's PiecewiseConstant2D). */
        const uint w = params.env_width;
        const uint h = params.env_height;
        const uint row = gc_env_search(GC_LIGHTS_ARGS, true, 0u, h, r.y);
        const float m0 = GC_ENV_MARGINAL(row);
        const float m1 = GC_ENV_MARGINAL(row + 1u);
        const float fy = m1 > m0 ? (r.y - m0) / (m1 - m0) : 0.5f;
        const uint base = row * (w + 1u);
        const uint col = gc_env_search(GC_LIGHTS_ARGS, false, base, w, r.z);
        const float c0 = GC_ENV_CONDITIONAL(base + col);
        const float c1 = GC_ENV_CONDITIONAL(base + col + 1u);
        const float fx = c1 > c0 ? (r.z - c0) / (c1 - c0) : 0.5f;
        ls.wi = gc_env_direction((gc_float(col) + fx) / gc_float(w), (gc_float(row) + fy) / gc_float(h));
        /* The density is re-evaluated from the direction, exactly as gc_escaped_radiance's
         * MIS weight will be, so the two strategies agree on every sample. */
        ls.pdf_w = group_pmf * gc_env_pdf_w(GC_LIGHTS_ARGS, params, ls.wi);
        ls.radiance = gc_env_radiance(GC_LIGHTS_ARGS, params, ls.wi);
        ls.dist = GC_FLOAT_MAX;
        ls.kind = GC_LIGHT_ENV;
    }
    return ls;
}

GC_NAMESPACE_END

#endif /* GC_LIGHT_SAMPLE_H */
