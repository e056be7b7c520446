/*
 * gc_aov_instance.h — gc_aov_value (gc_aov.h) for a hit on an instance: the surface is
 * evaluated in the instance's object space, where its mesh's attributes are, and what has a
 * direction is taken to world space: the normals, and the preview's headlight cosine, which
 * is computed with the world normal and the world ray (object space would distort it under a
 * non-uniform scale). Depth (t is the world t), albedo and the primitive id (the triangle of
 * the scene of meshes) need no conversion. Shared dialect (gc_platform.h).
 */
#ifndef GC_AOV_INSTANCE_H
#define GC_AOV_INSTANCE_H

#include "gc_aov.h"
#include "gc_instance.h"

GC_NAMESPACE_BEGIN

GC_FUNC float3 gc_aov_instance_value(GC_SHADE_PARAMS, GcRenderParams params, GcInstance inst, GcRay ray, GcHit hit)
{
    const GcRay object_ray = gc_instance_ray(inst, ray);
    if (params.aov == GC_AOV_NORMAL || params.aov == GC_AOV_GUIDE_NORMAL)
        return gc_instance_normal_to_world(inst, gc_aov_value(GC_SHADE_ARGS, params, object_ray, hit));
    if (params.aov != GC_AOV_PREVIEW) return gc_aov_value(GC_SHADE_ARGS, params, object_ray, hit);
    const GcSurface s = gc_surface_at(GC_ATTRIB(hit.prim), object_ray, hit);
    const GcMaterial m = GC_MATERIAL(s.material);
    return gc_aov_preview(gc_shade_albedo(GC_SHADE_ARGS, m, s.uv), gc_instance_normal_to_world(inst, s.ns),
                          GC_XYZ(ray.dir_tmax), gc_shade_emission(GC_SHADE_ARGS, m, s.uv));
}

GC_NAMESPACE_END

#endif /* GC_AOV_INSTANCE_H */
