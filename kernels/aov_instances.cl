/*
 * aov_instances.cl — the `aov` integrator's first-hit values (gc_aov.h) for an instanced
 * scene: the camera ray through the two-level BVH (gc_traverse_instances.h), the surface
 * evaluated in the hit instance's object space (the scene's attributes are per mesh), and
 * normals taken to world space. Depth and albedo need no conversion: t is the world t, and
 * materials and uvs belong to the mesh. The instance buffers come before the scene's.
 */
#include "gc_aov_instance.h"
#include "gc_traverse_instances.h"

__kernel void aov_instances_render(const GcRenderParams params, GC_INSTANCE_PARAMS, GC_SCENE_PARAMS,
                                   __global float4* film)
{
    const uint i = get_global_id(0);
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    const GcRay ray = gc_aov_camera_ray(params, pixel);
    const GcInstanceHit h = gc_trace_instances(GC_INSTANCE_ARGS, GC_BVH_ARGS, ray, false);
    float3 value;
    if (h.instance == GC_INVALID) {
        value = gc_aov_value(GC_SHADE_ARGS, params, ray, h.hit);
    } else {
        value = gc_aov_instance_value(GC_SHADE_ARGS, params, gc_instances[h.slot], ray, h.hit);
    }
    film[pixel] += (float4)(value, 1.0f);
}
