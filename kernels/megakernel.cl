/*
 * megakernel.cl — the path integrator as one kernel: one work-item per pixel of the batch
 * traces that pixel's samples of the pass one after the other, each path from camera to
 * termination (generate -> [extend -> shade -> shadow]* -> accumulate of wavefront.cl in a
 * loop, as the Vulkan reference kernels/vk/path.comp does).
 *
 * Why a second form: on CPUs (PoCL) the wavefront's ~30 launches, queue atomics, counter
 * read-backs and path-state round trips through memory per pass cost more than the
 * divergence they avoid, and they serialise the pass between bounces. The work per path is
 * the same calls in the same order with the same random-number keys (gc_shade_vertex), and
 * each pixel's samples are added in sample order, so the image is the same bits as the
 * wavefront's on the same device (tests/validation/determinism_test.cpp checks it).
 */
#include "gc_alpha.h"
#include "gc_traverse.h"
#include "gc_path_vertex.h"
#include "gc_camera.h"
#include "gc_rng.h"

__kernel void path_megakernel(const GcRenderParams params,
                              GC_SCENE_PARAMS,
                              __global float4* film,
                              __global float4* film_squares)
{
    const uint slot = get_global_id(0);
    if (slot >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + slot;
    float4 sum = film[pixel];
    float4 squares = film_squares[pixel];
    for (uint s = 0u; s < params.samples_in_pass; ++s) {
        /* generate.cl */
        const uint sample = params.sample_index + s;
        const float4 jitter = gc_rand4(pixel, sample, GC_RNG_BLOCK_CAMERA, params.seed);
        GcRay ray = gc_camera_ray(params.camera, params.width, params.height, pixel % params.width,
                                  pixel / params.width, jitter.x, jitter.y);
        GcPathState path = gc_path_start(pixel, sample);

        /* extend -> shade -> shadow until the path ends (gc_shade_vertex stops it at max_depth). */
        for (;;) {
            const GcHit hit = gc_trace_closest(GC_BVH_ARGS, ray);
            const GcVertexResult res = gc_shade_vertex(GC_SHADE_ARGS, params, path, ray, hit);
            path = res.path;
            if ((res.flags & GC_VERTEX_SHADOW) != 0u && !gc_trace_any(GC_BVH_ARGS, res.shadow.ray))
                path.radiance += res.shadow.contribution;
            if ((res.flags & GC_VERTEX_CONTINUE) == 0u) break;
            ray = res.next;
        }

        /* accumulate.cl */
        const float3 value = gc_film_value(path.radiance.xyz);
        sum += (float4)(value, 1.0f);
        squares += (float4)(value * value, 0.0f);
    }
    film[pixel] = sum;
    film_squares[pixel] = squares;
}
