/*
 * gc_aov_trace.h — one sample of the `aov` integrator: the camera ray, its closest hit and
 * the AOV's value there (gc_aov.h). For the denoiser's guides (GC_AOV_GUIDE_ALBEDO,
 * GC_AOV_GUIDE_NORMAL) the ray goes on through smooth dielectrics and pure mirrors to the
 * first surface that is not a delta reflector, as Cycles' and Yocto's denoising features
 * do, so that a denoiser sees what a mirror or a window shows rather than a flat surface.
 * The branch taken at glass is deterministic, so the guides are free of noise. Called by
 * kernels/aov.cl (flat or instanced scenes, gc_scene_trace.h) and the Vulkan reference
 * kernels/vk/aov.comp.
 */
#ifndef GC_AOV_TRACE_H
#define GC_AOV_TRACE_H

#include "gc_aov.h"
#include "gc_scene_trace.h"
#include "gc_spawn.h"
#include "gc_whitted.h"

/* Delta vertices the guides pass through before they give up and show the last one. */
#define GC_AOV_GUIDE_MAX_DELTA 8u

GC_NAMESPACE_BEGIN

/* Surfaces the guides look through: smooth dielectrics, and mirrors whose reflection
 * outweighs their diffuse part (MTL mirrors keep a little Kd: the Cornell sphere's is 0.01
 * beside Ks 0.95). */
GC_FUNC bool gc_aov_guide_passes(GcMaterial m)
{
    if (m.type == GC_MAT_DIELECTRIC) return true;
    if (m.type != GC_MAT_MIRROR || m.albedo_texture != GC_INVALID) return false;
    return fmax(m.specular.x, fmax(m.specular.y, m.specular.z)) > fmax(m.albedo.x, fmax(m.albedo.y, m.albedo.z));
}

/* The AOV's value at h, the closest hit of ray in the program's scene. */
#define gc_aov_scene_value(params, ray, h)                                                                 \
    (gc_scene_hit(h).prim == GC_INVALID                                                                   \
         ? gc_aov_miss_value(params)                                                                       \
         : gc_aov_value_at(GC_SHADE_ARGS, params, ray, gc_scene_hit(h), gc_scene_attribs(h)))

GC_FUNC float3 gc_aov_sample(GC_INSTANCES_FIRST_PARAMS GC_SCENE_PARAMS, GcRenderParams params, uint pixel)
{
    GcRay ray = gc_aov_camera_ray(params, pixel);
    GcSceneHit h = gc_scene_closest(ray);
    if (params.aov != GC_AOV_GUIDE_ALBEDO && params.aov != GC_AOV_GUIDE_NORMAL)
        return gc_aov_scene_value(params, ray, h);

    /* A mirror tints what it shows by its Ks; glass passes it on (in and out, its radiance
     * weights cancel). */
    float3 tint = make_float3(1.0f, 1.0f, 1.0f);
    for (uint bounce = 0u; bounce < GC_AOV_GUIDE_MAX_DELTA && gc_scene_hit(h).prim != GC_INVALID; ++bounce) {
        const GcSurface s = gc_surface_at(gc_scene_attribs(h), ray, gc_scene_hit(h));
        const GcMaterial m = GC_MATERIAL(s.material);
        if (!gc_aov_guide_passes(m)) break;
        const GcWhittedSpecular lobes = gc_whitted_specular(m, s.ns, -GC_XYZ(ray.dir_tmax));
        /* Through glass unless total internal reflection or Fresnel makes the reflection
         * the stronger lobe (grazing angles). */
        const bool through = lobes.refract_weight.x > 0.0f && lobes.refract_weight.x >= lobes.reflect_weight.x;
        const float3 dir = through ? lobes.refract_dir : lobes.reflect_dir;
        if (m.type == GC_MAT_MIRROR) tint = tint * lobes.reflect_weight;
        ray = gc_make_ray(gc_offset_ray_origin(s.p, gc_side_normal(s.ng, dir), s.spawn_scale), dir, 0.0f,
                          GC_RAY_UNBOUNDED);
        h = gc_scene_closest(ray);
    }
    const float3 value = gc_aov_scene_value(params, ray, h);
    return params.aov == GC_AOV_GUIDE_ALBEDO ? value * tint : value;
}

GC_NAMESPACE_END

#endif /* GC_AOV_TRACE_H */
