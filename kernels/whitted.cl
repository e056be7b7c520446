/*
 * whitted.cl — the `whitted` integrator: one work-item per pixel of the batch runs one camera
 * sample's ray tree (gc_whitted_sample, gc_whitted_tree.h, which holds the model; the Vulkan
 * reference kernels/vk/whitted.comp runs the same function; an instanced scene's buffers come
 * first, gc_scene_trace.h). The work-item owns film[pixel]
 * and adds (radiance, 1), so the sum needs no atomics and the image is the same bits run to
 * run.
 */
#include "gc_whitted_tree.h"

/* One pixel's sample, out of line on CPUs (GC_ITEM_BODY, gc_platform.h): PoCL compiled three
 * 10 KB copies of it inlined. */
GC_ITEM_BODY gc_whitted_item(const uint i, const GcRenderParams params, GC_INSTANCES_FIRST_PARAMS GC_SCENE_PARAMS,
                             __global float4* film)
{
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    film[pixel] += (float4)(gc_whitted_sample(GC_INSTANCES_FIRST_ARGS GC_SCENE_ARGS, params, pixel), 1.0f);
}

__kernel void whitted_render(const GcRenderParams params, GC_INSTANCES_FIRST_PARAMS GC_SCENE_PARAMS,
                             __global float4* film)
{
    gc_whitted_item(get_global_id(0), params, GC_INSTANCES_FIRST_ARGS GC_SCENE_ARGS, film);
}
