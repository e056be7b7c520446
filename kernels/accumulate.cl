/* accumulate.cl — adds each path's radiance, and its square, to its pixel. One work-item per
 * pixel slot adds that pixel's samples of the pass in sample order, and passes are in sample
 * order, so every pixel's sums are formed in the same order — bit-identical whether a pass
 * holds one sample or many, and run to run. The squares give the per-pixel sample variance
 * that the image tests' Z-test needs. */
#include "gc_path.h"

__kernel void accumulate(const GcRenderParams params,
                         __global const GcPathState* paths,
                         __global float4* film,
                         __global float4* film_squares)
{
    const uint slot = get_global_id(0);
    if (slot >= params.pixel_count) return;
    const uint pixel = paths[slot * params.samples_in_pass].pixel; /* generate.cl's gc_batch_pixel */
    float4 sum = film[pixel];
    float4 squares = film_squares[pixel];
    for (uint s = 0u; s < params.samples_in_pass; ++s) {
        const float3 sample = gc_film_value(paths[slot * params.samples_in_pass + s].radiance.xyz);
        sum += (float4)(sample, 1.0f);
        squares += (float4)(sample * sample, 0.0f);
    }
    film[pixel] = sum;
    film_squares[pixel] = squares;
}
