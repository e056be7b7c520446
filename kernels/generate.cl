/* generate.cl — camera rays for every path of the pass, fresh path state, all queued. A pass
 * holds params.samples_in_pass consecutive samples of the batch's pixels: slot
 * p * samples_in_pass + s is sample sample_index + s of the batch's pixel p (pixel_offset + p,
 * or the p-th listed one: gc_batch_pixel). A pixel's
 * samples sit side by side, so a warp's first rays all leave through one or two pixels and
 * share their nodes (docs/decisions/cpu-pass-length.md; same bits either way). Every slot is
 * queued, so the queue is the identity and its count is the pass's size: no atomics. */
#include "gc_camera.h"
#include "gc_path.h"
#include "gc_rng.h"

__kernel void generate(const GcRenderParams params,
                       __global GcRay* rays,
                       __global GcPathState* paths,
                       __global uint* ray_queue,
                       __global uint* counters,
                       __global const uint* pixel_list)
{
    const uint slot = get_global_id(0);
    if (slot >= gc_pass_paths(params)) return;
    const uint pixel = gc_batch_pixel(params, pixel_list, slot / params.samples_in_pass);
    const uint sample = params.sample_index + slot % params.samples_in_pass;
    const float4 jitter = gc_sample4(params, pixel, sample, GC_RNG_BLOCK_CAMERA);
    rays[slot] = gc_camera_sample(params.camera, params.width, params.height, pixel % params.width,
                                  pixel / params.width, jitter);
    paths[slot] = gc_path_start(pixel, sample);
    ray_queue[slot] = slot;
    if (slot == 0u) counters[GC_COUNTER_RAYS_A] = gc_pass_paths(params);
}
