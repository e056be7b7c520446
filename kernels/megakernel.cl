/*
 * megakernel.cl — the path integrator as one kernel: one work-item per pixel of the batch
 * (or per few neighbours, below) traces that pixel's samples of the pass one after the other,
 * each path from camera to termination (generate -> [extend -> shade -> shadow]* ->
 * accumulate of wavefront.cl in a loop, as the Vulkan reference kernels/vk/path.comp does).
 *
 * Why a second form: on CPUs (PoCL) the wavefront's ~30 launches, queue atomics, counter
 * read-backs and path-state round trips through memory per pass cost more than the
 * divergence they avoid, and they serialise the pass between bounces. The work per path is
 * the same calls in the same order with the same random-number keys (gc_shade_vertex), and
 * each pixel's samples are added in sample order, so the image is the same bits as the
 * wavefront's on the same device (tests/validation/determinism_test.cpp checks it).
 *
 * Camera rays in packets: on the BVH8 (CPUs with 8-wide SIMD) a work-item traces the camera
 * rays of six to eight of its pixel's samples as one packet (gc_packet8.h), then follows each
 * path alone; fewer go one by one, for which the packet is slower. The rays leave through
 * one pixel, so one traversal serves all of them; the hits are the single-ray traversal's
 * bits. Against one camera ray at a time, path samples per second with the planner's
 * passes, H200 host's 16 PoCL cores / 2-core VM (two runs each): bunny 1.21-1.27x /
 * 1.32-1.49x, dragon 1.18-1.19x / 1.32-1.34x, Cornell box 1.00-1.11x / 1.00x (its camera
 * rays are one of about nine rays per sample), 5.2M triangles 1.05-1.11x / 0.98-1.04x.
 * A pass of one to four samples has too few for a packet, so there a work-item takes two to
 * eight neighbouring pixels of a row and packs their camera rays together
 * (gc_packet_lanes.h). Such passes start every render and fill the first seconds of a large
 * image on few cores. 2-core VM, both cores, against one pixel per work-item, 2-3
 * interleaved rounds: one sample per pass, bunny 1.29x and dragon 1.11-1.18x; two, 1.32x
 * and 1.16x; four, 1.23x and 1.33x; the Cornell box 0.98-1.03x.
 * Shadow rays stay single: eight paths in lock step, to make packets of their shadow rays,
 * lost (docs/decisions/shadow-ray-packets.md).
 *
 * One inline path loop serves both: the same loop behind helper functions (the camera ray,
 * the path, the film update each a function) ran one sample per pass at 0.87-0.93x of the
 * loop before the packets on the 2-core VM; this form runs it at 0.95-1.00x (4 rounds).
 */
#include "gc_traverse.h"
#include "gc_packet8.h"
#include "gc_path_vertex.h"
#include "gc_camera.h"
#include "gc_rng.h"

/* One work-item's pixels, out of line on CPUs (GC_ITEM_BODY, gc_platform.h). Inlined, PoCL
 * compiled three copies of this loop with its shading and packet code; called, once, and its
 * object shrank from 62 KB to 30 KB. Cold first image, 4 interleaved rounds, medians of
 * per-round ratios: 2-core VM (PoCL 3.1) Cornell box 0.75x, dragon 0.82x (about 1 s less);
 * H200 host's 16 cores (PoCL 5) 0.92x and 0.78x. Path samples 0.99-1.00x (Cornell box) and
 * 1.00-1.10x (dragon) on both: one call per work-item is nothing against its paths. */
GC_ITEM_BODY gc_megakernel_item(const uint item,
                                const GcRenderParams params,
                                GC_SCENE_PARAMS,
                                __global float4* film,
                                __global float4* film_squares)
{
    /* This work-item's pixels: pixels_per_item neighbours in the batch (gc_packet_lanes.h). */
    const uint per_item = max(params.pixels_per_item, 1u);
    const uint first = item * per_item;
    const uint samples = params.samples_in_pass;
    if (first >= params.pixel_count || samples == 0u) return;
    const uint pixels = min(per_item, params.pixel_count - first);
    /* Its (pixel, sample) pairs, pixel by pixel and each pixel's samples in order, in groups of
     * at most eight, as even as they can be made. */
    const uint pairs = pixels * samples;
    const uint groups = (pairs + 7u) / 8u;
    uint pixel = GC_INVALID; /* whose sums are open */
    float4 sum = (float4)(0.0f);
    float4 squares = (float4)(0.0f);
    for (uint g = 0u, p0 = 0u; g < groups; ++g) {
        const uint lanes = pairs / groups + (g < pairs % groups ? 1u : 0u);
        /* generate.cl */
        GcRay cam[8];
        for (uint k = 0u; k < lanes; ++k) {
            const uint px = params.pixel_offset + first + (p0 + k) / samples;
            const uint sample = params.sample_index + (p0 + k) % samples;
            const float4 jitter = gc_rand4(px, sample, GC_RNG_BLOCK_CAMERA, params.seed);
            cam[k] = gc_camera_ray(params.camera, params.width, params.height, px % params.width, px / params.width,
                                   jitter.x, jitter.y);
        }
        /* The group's camera rays, which leave through one pixel or a few neighbours, as one
         * packet (gc_packet8.h) when there are enough of them; else each path traces its own. */
        GcHit cam_hit[8];
        bool cam_traced = false;
#if defined(GC_HAVE_PACKET8)
        if (lanes >= GC_PACKET_MIN_LANES) {
            int active[8];
            for (uint k = 0u; k < 8u; ++k) {
                active[k] = k < lanes;
                if (k >= lanes) cam[k] = cam[lanes - 1u]; /* idle lanes: a copy, never traced */
            }
            gc_packet_closest_hits8(GC_BVH_ARGS, cam, active, cam_hit);
            cam_traced = true;
        }
#endif
        for (uint k = 0u; k < lanes; ++k) {
            const uint px = params.pixel_offset + first + (p0 + k) / samples;
            if (px != pixel) {
                if (pixel != GC_INVALID) {
                    film[pixel] = sum;
                    film_squares[pixel] = squares;
                }
                pixel = px;
                sum = film[pixel];
                squares = film_squares[pixel];
            }
            GcRay ray = cam[k];
            GcPathState path = gc_path_start(pixel, params.sample_index + (p0 + k) % samples);
            /* extend -> shade -> shadow until the path ends (gc_shade_vertex stops it at max_depth). */
            for (bool first_segment = true;; first_segment = false) {
                const GcHit hit = first_segment && cam_traced ? cam_hit[k] : gc_trace_closest(GC_BVH_ARGS, ray);
                const GcVertexResult res = gc_shade_vertex(GC_SHADE_ARGS, params, path, ray, hit);
                path = res.path;
                if ((res.flags & GC_VERTEX_SHADOW) != 0u && !gc_trace_any(GC_BVH_ARGS, res.shadow.ray))
                    path.radiance += res.shadow.contribution;
                if ((res.flags & GC_VERTEX_CONTINUE) == 0u) break;
                ray = res.next;
            }
            /* accumulate.cl, in sample order */
            const float3 value = gc_film_value(path.radiance.xyz);
            sum += (float4)(value, 1.0f);
            squares += (float4)(value * value, 0.0f);
        }
        p0 += lanes;
    }
    film[pixel] = sum;
    film_squares[pixel] = squares;
}

__kernel void path_megakernel(const GcRenderParams params,
                              GC_SCENE_PARAMS,
                              __global float4* film,
                              __global float4* film_squares)
{
    gc_megakernel_item(get_global_id(0), params, GC_SCENE_ARGS, film, film_squares);
}
