/*
 * gc_aov.h — the `aov` integrator's per-pixel values (the seed's "mesh render pass"
 * outputs): which camera ray a pixel uses, and what albedo, shading normal, depth,
 * primitive id or shaded preview it shows. Mirrors kernels/aov.cl, which can call these
 * directly; the Vulkan compute reference (kernels/vk/aov.comp) and the raster pass
 * (kernels/vk/raster.frag, preview) do.
 *
 * Reads the scene through the shade group of gc_scene_buffers.h (GC_SHADE_PARAMS).
 */
#ifndef GC_AOV_H
#define GC_AOV_H

#include "gc_camera.h"
#include "gc_material_eval.h"
#include "gc_rng.h"
#include "gc_shading.h"

GC_NAMESPACE_BEGIN

/* Depth, normal and primitive id are per-pixel facts: they sample the pixel centre. Albedo,
 * the preview and the denoiser's guides are jittered like the path tracer's camera rays
 * (anti-aliasing). */
GC_FUNC GcRay gc_aov_camera_ray(GcRenderParams params, uint pixel)
{
    /* The pixel centre through the lens centre. */
    float4 u = make_float4(0.5f, 0.5f, 0.5f, 0.5f);
    if (params.aov == GC_AOV_PREVIEW || params.aov == GC_AOV_ALBEDO || params.aov == GC_AOV_GUIDE_ALBEDO ||
        params.aov == GC_AOV_GUIDE_NORMAL) {
        u = gc_sample4(params, pixel, params.sample_index, GC_RNG_BLOCK_CAMERA);
    }
    return gc_camera_sample(params.camera, params.width, params.height, pixel % params.width, pixel / params.width, u);
}

/* Albedo under a headlight, plus emitters shown at (clamped) full brightness.
 * Recognisable, not physically based. dir is the viewing ray's direction. */
GC_FUNC float3 gc_aov_preview(float3 albedo, float3 ns, float3 dir, float3 emission)
{
    const float cosine = fabs(gc_dot(ns, dir));
    return albedo * (0.15f + 0.85f * cosine) + fmin(emission, make_float3(1.0f, 1.0f, 1.0f));
}

/* The value of AOV params.aov for a ray that left the scene. */
GC_FUNC float3 gc_aov_miss_value(GcRenderParams params)
{
    if (params.aov == GC_AOV_PRIMID) return make_float3(-1.0f, -1.0f, -1.0f);
    if (params.aov == GC_AOV_PREVIEW) return GC_XYZ(params.env_radiance);
    return make_float3(0.0f, 0.0f, 0.0f);
}

/* The value of AOV params.aov for a camera ray and its hit (hit.prim valid) on a triangle
 * with attributes `tri`, in the ray's space (an instance's taken to world space,
 * gc_scene_trace.h). */
GC_FUNC float3 gc_aov_value_at(GC_SHADE_PARAMS, GcRenderParams params, GcRay ray, GcHit hit, GcTriangleAttribs tri)
{
    GC_SHADE_UNUSED();
    const GcSurface s = gc_surface_at(tri, ray, hit);
    const GcMaterial m = GC_MATERIAL(s.material);
    if (params.aov == GC_AOV_ALBEDO) return gc_shade_albedo(GC_SHADE_ARGS, m, s.uv);
    /* The denoiser's albedo shows emitters too (clamped to 1), so that it sees where a lamp
     * ends and the ceiling around it begins; a lamp's Kd alone often equals its ceiling's. */
    if (params.aov == GC_AOV_GUIDE_ALBEDO)
        return fmin(gc_shade_albedo(GC_SHADE_ARGS, m, s.uv) + gc_shade_emission(GC_SHADE_ARGS, m, s.uv),
                    make_float3(1.0f, 1.0f, 1.0f));
    if (params.aov == GC_AOV_NORMAL) return s.ns;
    /* The denoiser's normal is the one the path tracer shades with: normal maps applied. */
    if (params.aov == GC_AOV_GUIDE_NORMAL)
        return gc_shade_normal(GC_SHADE_ARGS, m, tri, make_float2(hit.u, hit.v), s.ns, s.uv);
    if (params.aov == GC_AOV_DEPTH) return make_float3(hit.t, hit.t, hit.t);
    if (params.aov == GC_AOV_PRIMID) {
        const float id = gc_float(hit.prim);
        return make_float3(id, id, id);
    }
    return gc_aov_preview(gc_shade_albedo(GC_SHADE_ARGS, m, s.uv), s.ns, GC_XYZ(ray.dir_tmax),
                          gc_shade_emission(GC_SHADE_ARGS, m, s.uv));
}

/* The value of AOV params.aov for a camera ray and its closest hit in a flat scene. */
GC_FUNC float3 gc_aov_value(GC_SHADE_PARAMS, GcRenderParams params, GcRay ray, GcHit hit)
{
    if (hit.prim == GC_INVALID) return gc_aov_miss_value(params);
    return gc_aov_value_at(GC_SHADE_ARGS, params, ray, hit, GC_ATTRIB(hit.prim));
}

GC_NAMESPACE_END

#endif /* GC_AOV_H */
