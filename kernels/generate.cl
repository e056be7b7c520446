/* generate.cl — camera rays for every pixel of the batch, fresh path state, all queued. */
#include "gc_camera.h"
#include "gc_rng.h"

__kernel void generate(const GcRenderParams params,
                       __global GcRay* rays,
                       __global GcPathState* paths,
                       __global uint* ray_queue,
                       __global uint* counters)
{
    const uint slot = get_global_id(0);
    if (slot >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + slot;
    const float4 jitter = gc_rand4(pixel, params.sample_index, GC_RNG_BLOCK_CAMERA, params.seed);
    rays[slot] = gc_camera_ray(params.camera, params.width, params.height, pixel % params.width,
                               pixel / params.width, jitter.x, jitter.y);
    GcPathState path;
    path.throughput = (float4)(1.0f, 1.0f, 1.0f, 0.0f);
    path.radiance = (float4)(0.0f, 0.0f, 0.0f, 1.0f); /* w: eta^2 scale for Russian roulette */
    path.pixel = pixel;
    path.depth = 0u;
    path.flags = GC_PATH_SPECULAR; /* a camera ray sees emitters with full weight */
    path.pad0 = 0u;
    paths[slot] = path;
    ray_queue[atomic_inc(&counters[GC_COUNTER_RAYS_A])] = slot;
}
