/* accumulate.cl — adds each path's radiance, and its square, to its pixel. One slot per
 * pixel in a pass, and passes are in sample order, so the per-pixel sums are identical run
 * to run. The squares give the per-pixel sample variance that the image tests' Z-test needs. */
__kernel void accumulate(const GcRenderParams params,
                         __global const GcPathState* paths,
                         __global float4* film,
                         __global float4* film_squares)
{
    const uint slot = get_global_id(0);
    if (slot >= params.pixel_count) return;
    const GcPathState path = paths[slot];
    /* A NaN or infinite sample would poison the pixel forever: drop it (counted as black). */
    const float3 L = path.radiance.xyz;
    const bool finite = isfinite(L.x) && isfinite(L.y) && isfinite(L.z);
    const float3 sample = finite ? L : (float3)(0.0f);
    film[path.pixel] += (float4)(sample, 1.0f);
    film_squares[path.pixel] += (float4)(sample * sample, 0.0f);
}
