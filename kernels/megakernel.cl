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
 * bits. The gain is largest where camera rays are a large share of a sample's rays and the
 * tree is large (docs/decisions/camera-ray-packets.md).
 * A pass of one to four samples has too few for a packet, so there a work-item takes two to
 * eight neighbouring pixels of a row and packs their camera rays together
 * (gc_packet_lanes.h). Such passes start every render and fill the first seconds of a large
 * image on few cores.
 * Shadow rays stay single: eight paths in lock step, to make packets of their shadow rays,
 * lost (docs/decisions/shadow-ray-packets.md).
 *
 * One inline path loop serves both: the same loop behind helper functions (the camera ray,
 * the path, the film update each a function) runs one-sample passes measurably slower on
 * PoCL (docs/decisions/camera-ray-packets.md).
 */
#include "gc_traverse.h"
#include "gc_packet8.h"
#include "gc_path_vertex.h"
#include "gc_camera.h"
#include "gc_rng.h"
#include "gc_scene_trace.h"

/* Camera rays go in packets on the BVH8 of a flat scene; an instanced scene's (-D
 * GC_SCENE_INSTANCED, gc_scene_trace.h) every ray goes through the two-level BVH alone. */
#if defined(GC_HAVE_PACKET8) && !defined(GC_SCENE_INSTANCED)
#define GC_PATH_CAMERA_PACKETS
#endif

/* One work-item's pixels, out of line on CPUs (GC_ITEM_BODY, gc_platform.h). Inlined, PoCL
 * compiles three copies of this loop with its shading and packet code (the kernel and its two
 * work-group launchers); called, once, which halves the object and shortens a cold start. One
 * call per work-item is nothing against its paths (docs/decisions/cold-start.md). */
GC_ITEM_BODY gc_megakernel_item(const uint item,
                                const GcRenderParams params,
                                GC_INSTANCES_FIRST_PARAMS GC_SCENE_PARAMS,
                                __global float4* film,
                                __global float4* film_squares,
                                __global const uint* pixel_list)
{
    /* This work-item's pixels: pixels_per_item neighbours in the batch (gc_packet_lanes.h;
     * neighbours in the pixel list when the batch is listed, gc_batch_pixel). */
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
            const uint px = gc_batch_pixel(params, pixel_list, first + (p0 + k) / samples);
            const uint sample = params.sample_index + (p0 + k) % samples;
            const float4 jitter = gc_sample4(params, px, sample, GC_RNG_BLOCK_CAMERA);
            cam[k] = gc_camera_sample(params.camera, params.width, params.height, px % params.width, px / params.width,
                                      jitter);
        }
        /* The group's camera rays, which leave through one pixel or a few neighbours, as one
         * packet (gc_packet8.h) when there are enough of them; else each path traces its own. */
        GcSceneHit cam_hit[8];
        bool cam_traced = false;
#if defined(GC_PATH_CAMERA_PACKETS)
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
            const uint px = gc_batch_pixel(params, pixel_list, first + (p0 + k) / samples);
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
                const GcSceneHit hit = first_segment && cam_traced ? cam_hit[k] : gc_scene_closest(ray);
                const GcVertexResult res = gc_shade_scene_vertex(params, path, ray, hit);
                path = res.path;
                if ((res.flags & GC_VERTEX_SHADOW) != 0u && !gc_scene_occluded(res.shadow.ray))
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
                              GC_INSTANCES_FIRST_PARAMS GC_SCENE_PARAMS,
                              __global float4* film,
                              __global float4* film_squares,
                              __global const uint* pixel_list)
{
    gc_megakernel_item(get_global_id(0), params, GC_INSTANCES_FIRST_ARGS GC_SCENE_ARGS, film, film_squares, pixel_list);
}
