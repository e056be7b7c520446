/*
 * aov.cl — the `aov` integrator: one camera ray per pixel and sample, and the primary
 * hit's albedo, shading normal, depth, primitive id or a simple shaded preview (the seed's
 * "mesh render pass" outputs). The values come from gc_aov.h, which the Vulkan compute
 * reference and raster pass share; an instanced scene's buffers come first (gc_scene_trace.h).
 * One work-item per pixel of the batch; each work-item owns its film slot, so the sum needs
 * no atomics.
 */
#include "gc_aov_trace.h"

__kernel void aov_render(const GcRenderParams params, GC_INSTANCES_FIRST_PARAMS GC_SCENE_PARAMS, __global float4* film)
{
    const uint i = get_global_id(0);
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    film[pixel] += (float4)(gc_aov_sample(GC_INSTANCES_FIRST_ARGS GC_SCENE_ARGS, params, pixel), 1.0f);
}
