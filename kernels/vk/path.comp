/*
 * path.comp — Vulkan compute reference of the path integrator: one invocation runs a whole
 * path (a megakernel), calling the same gc_shade_vertex as the OpenCL wavefront
 * (kernels/shade.cl) with the same random-number keying (gc_rng.h: pixel, sample index,
 * block, seed), so both make the same decisions. The order of operations on a path's
 * radiance is the wavefront's: a vertex's emission, then its shadow ray's contribution.
 * The film sum runs in sample order, as accumulate.cl's does. Built a second time with
 * GC_SCENE_INSTANCED for instanced scenes: the two-level BVH of instances.glsl, traced and
 * shaded through gc_scene_trace.h as megakernel.cl does.
 */
#version 450
#define GC_VK_COMPUTE 1
#include "scene_bindings.glsl"
#ifdef GC_SCENE_INSTANCED
#include "instances.glsl"
#endif
#include "gc_scene_trace.h"
#include "gc_path_vertex.h"
#include "gc_camera.h"

layout(local_size_x = GC_VK_LOCAL_SIZE) in;
layout(push_constant) uniform Push { uint sample_index; } push;

void main()
{
    GcRenderParams params = params_data;
    params.sample_index = push.sample_index;
    const uint i = gl_GlobalInvocationID.x;
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;

    /* generate.cl */
    const vec4 jitter = gc_sample4(params, pixel, params.sample_index, GC_RNG_BLOCK_CAMERA);
    GcRay ray = gc_camera_sample(params.camera, params.width, params.height, pixel % params.width,
                                 pixel / params.width, jitter);
    GcPathState path = gc_path_start(pixel, params.sample_index);

    /* extend -> shade -> shadow until the path ends (at most max_depth vertices). */
    for (;;) {
        const GcSceneHit hit = gc_scene_closest(ray);
        const GcVertexResult res = gc_shade_scene_vertex(params, path, ray, hit);
        path = res.path;
        if ((res.flags & GC_VERTEX_SHADOW) != 0u && !gc_scene_occluded(res.shadow.ray))
            path.radiance += res.shadow.contribution;
        if ((res.flags & GC_VERTEX_CONTINUE) == 0u) break;
        ray = res.next;
    }

    /* accumulate.cl: a NaN or infinite sample counts as black. */
    const vec3 L = path.radiance.xyz;
    const bool finite = !any(isnan(L)) && !any(isinf(L));
    film[pixel] += vec4(finite ? L : vec3(0.0f), 1.0f);
}
