/*
 * aov.comp — Vulkan compute reference of the `aov` integrator (kernels/aov.cl): one camera
 * ray per pixel and sample through the same BVH, the value from gc_aov.h, added to the film.
 * One invocation per pixel; the host dispatches one sample index at a time. Built a second
 * time with GC_SCENE_INSTANCED for instanced scenes (instances.glsl).
 */
#version 450
#define GC_VK_COMPUTE 1
#include "scene_bindings.glsl"
#ifdef GC_SCENE_INSTANCED
#include "instances.glsl"
#endif
#include "gc_aov_trace.h"

layout(local_size_x = GC_VK_LOCAL_SIZE) in;
layout(push_constant) uniform Push { uint sample_index; } push;

void main()
{
    GcRenderParams params = params_data;
    params.sample_index = push.sample_index;
    const uint i = gl_GlobalInvocationID.x;
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    film[pixel] += vec4(gc_aov_sample(GC_INSTANCES_FIRST_ARGS GC_SCENE_ARGS, params, pixel), 1.0f);
}
