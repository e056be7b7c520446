/* accumulate.cl — adds each path's radiance, and its square, to its pixel. One work-item per
 * pixel slot adds that pixel's samples of the pass in sample order, and passes are in sample
 * order, so every pixel's sums are formed in the same order — bit-identical whether a pass
 * holds one sample or many, and run to run. The squares give the per-pixel sample variance
 * that the image tests' Z-test needs. */
__kernel void accumulate(const GcRenderParams params,
                         __global const GcPathState* paths,
                         __global float4* film,
                         __global float4* film_squares)
{
    const uint slot = get_global_id(0);
    if (slot >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + slot;
    float4 sum = film[pixel];
    float4 squares = film_squares[pixel];
    for (uint s = 0u; s < params.samples_in_pass; ++s) {
        const GcPathState path = paths[s * params.pixel_count + slot];
        /* A NaN or infinite sample would poison the pixel forever: drop it (counted as black). */
        const float3 L = path.radiance.xyz;
        const bool finite = isfinite(L.x) && isfinite(L.y) && isfinite(L.z);
        const float3 sample = finite ? L : (float3)(0.0f);
        sum += (float4)(sample, 1.0f);
        squares += (float4)(sample * sample, 0.0f);
    }
    film[pixel] = sum;
    film_squares[pixel] = squares;
}
