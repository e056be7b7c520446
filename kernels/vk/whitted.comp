/*
 * whitted.comp — Vulkan compute reference of the `whitted` integrator (kernels/whitted.cl):
 * one invocation per pixel runs one camera sample's ray tree through the same
 * gc_whitted_sample (gc_whitted_tree.h) and adds (radiance, 1) to the film. The host
 * dispatches one sample index at a time. Built a second time with GC_SCENE_INSTANCED for
 * instanced scenes (instances.glsl).
 */
#version 450
#define GC_VK_COMPUTE 1
#include "scene_bindings.glsl"
#ifdef GC_SCENE_INSTANCED
#include "instances.glsl"
#endif
#include "gc_whitted_tree.h"

layout(local_size_x = GC_VK_LOCAL_SIZE) in;
layout(push_constant) uniform Push { uint sample_index; } push;

void main()
{
    GcRenderParams params = params_data;
    params.sample_index = push.sample_index;
    const uint i = gl_GlobalInvocationID.x;
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    film[pixel] += vec4(gc_whitted_sample(GC_INSTANCES_FIRST_ARGS GC_SCENE_ARGS, params, pixel), 1.0f);
}
