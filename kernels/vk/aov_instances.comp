/*
 * aov_instances.comp — Vulkan compute reference of kernels/aov_instances.cl: first-hit AOVs
 * of an instanced scene through the two-level BVH (gc_traverse_instances.h; the bindings and
 * accessors of instances.glsl).
 */
#version 450
#define GC_VK_COMPUTE 1
#include "scene_bindings.glsl"
#include "instances.glsl"
#include "gc_aov_instance.h"
#include "gc_traverse_instances.h"

layout(local_size_x = GC_VK_LOCAL_SIZE) in;
layout(push_constant) uniform Push { uint sample_index; } push;

void main()
{
    GcRenderParams params = params_data;
    params.sample_index = push.sample_index;
    const uint i = gl_GlobalInvocationID.x;
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    const GcRay ray = gc_aov_camera_ray(params, pixel);
    const GcInstanceHit h = gc_trace_instances(GC_INSTANCE_ARGS, GC_BVH_ARGS, ray, false);
    vec3 value;
    if (h.instance == GC_INVALID) {
        value = gc_aov_value(GC_SHADE_ARGS, params, ray, h.hit);
    } else {
        value = gc_aov_instance_value(GC_SHADE_ARGS, params, gc_instances[h.slot], ray, h.hit);
    }
    film[pixel] += vec4(value, 1.0f);
}
