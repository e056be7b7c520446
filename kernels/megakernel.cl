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
 *
 * Camera rays in packets: on the BVH8 (CPUs with 8-wide SIMD) a work-item traces the camera
 * rays of up to eight of its pixel's samples as one packet (gc_packet8.h), then follows each
 * path alone. The rays leave through one pixel, so one traversal serves all of them; the
 * hits are the single-ray traversal's bits. Against one camera ray at a time, path samples
 * per second, H200 host's 16 PoCL cores / 2-core VM: bunny 1.21x / 1.49x, dragon 1.18x /
 * 1.34x, Cornell box 1.11x / 1.00x (its camera rays are one of about nine rays per sample),
 * 5.2M triangles 1.05x / 0.98x. Shadow rays stay single: eight paths in lock step, to make
 * packets of their shadow rays, lost (tools/bench/experiments/README.md).
 */
#include "gc_alpha.h"
#include "gc_traverse.h"
#include "gc_packet8.h"
#include "gc_path_vertex.h"
#include "gc_camera.h"
#include "gc_rng.h"

/* generate.cl: the camera ray of `sample` of `pixel`. */
static GcRay camera_ray(const GcRenderParams* params, uint pixel, uint sample)
{
    const float4 jitter = gc_rand4(pixel, sample, GC_RNG_BLOCK_CAMERA, params->seed);
    return gc_camera_ray(params->camera, params->width, params->height, pixel % params->width, pixel / params->width,
                         jitter.x, jitter.y);
}

/* extend -> shade -> shadow from the camera ray's hit until the path ends (gc_shade_vertex
 * stops it at max_depth), then accumulate.cl's value: the path's radiance, or black. */
static float3 trace_path(GC_SCENE_PARAMS, const GcRenderParams* params, uint pixel, uint sample, GcRay ray, GcHit hit)
{
    GcPathState path = gc_path_start(pixel, sample);
    for (;;) {
        const GcVertexResult res = gc_shade_vertex(GC_SHADE_ARGS, *params, path, ray, hit);
        path = res.path;
        if ((res.flags & GC_VERTEX_SHADOW) != 0u && !gc_trace_any(GC_BVH_ARGS, res.shadow.ray))
            path.radiance += res.shadow.contribution;
        if ((res.flags & GC_VERTEX_CONTINUE) == 0u) break;
        ray = res.next;
        hit = gc_trace_closest(GC_BVH_ARGS, ray);
    }
    return gc_film_value(path.radiance.xyz);
}

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
#if defined(GC_HAVE_PACKET8)
    /* Up to eight samples at a time: their camera rays, which leave through this pixel, are
     * traced as one packet (gc_packet8.h), then each path goes on alone, in sample order. */
    for (uint s0 = 0u; s0 < params.samples_in_pass; s0 += 8u) {
        const uint lanes = min(8u, params.samples_in_pass - s0);
        GcRay cam[8];
        float ox[8], oy[8], oz[8], dx[8], dy[8], dz[8];
        int active[8];
        for (uint k = 0u; k < 8u; ++k) {
            /* Lanes past the pass's samples repeat the last ray, inactive. */
            cam[k] = camera_ray(&params, pixel, params.sample_index + s0 + min(k, lanes - 1u));
            ox[k] = cam[k].org_tmin.x; oy[k] = cam[k].org_tmin.y; oz[k] = cam[k].org_tmin.z;
            dx[k] = cam[k].dir_tmax.x; dy[k] = cam[k].dir_tmax.y; dz[k] = cam[k].dir_tmax.z;
            active[k] = k < lanes ? -1 : 0;
        }
        GcRays8 rays;
        rays.ox = vload8(0, ox); rays.oy = vload8(0, oy); rays.oz = vload8(0, oz);
        rays.dx = vload8(0, dx); rays.dy = vload8(0, dy); rays.dz = vload8(0, dz);
        rays.tmin = (float8)(0.0f);
        rays.tmax = (float8)(GC_RAY_UNBOUNDED);
        rays.active = vload8(0, active);
        const GcHits8 hits = gc_trace_closest8(GC_BVH_ARGS, rays);
        float ht[8], hu[8], hv[8];
        uint hp[8];
        vstore8(hits.t, 0, ht); vstore8(hits.u, 0, hu); vstore8(hits.v, 0, hv); vstore8(hits.prim, 0, hp);
        for (uint k = 0u; k < lanes; ++k) {
            GcHit hit;
            hit.t = ht[k];
            hit.u = hu[k];
            hit.v = hv[k];
            hit.prim = hp[k];
            const float3 value = trace_path(GC_SCENE_ARGS, &params, pixel, params.sample_index + s0 + k, cam[k], hit);
            sum += (float4)(value, 1.0f);
            squares += (float4)(value * value, 0.0f);
        }
    }
#else
    for (uint s = 0u; s < params.samples_in_pass; ++s) {
        const uint sample = params.sample_index + s;
        const GcRay ray = camera_ray(&params, pixel, sample);
        const float3 value = trace_path(GC_SCENE_ARGS, &params, pixel, sample, ray, gc_trace_closest(GC_BVH_ARGS, ray));
        sum += (float4)(value, 1.0f);
        squares += (float4)(value * value, 0.0f);
    }
#endif
    film[pixel] = sum;
    film_squares[pixel] = squares;
}
