/* accumulate.cl — adds each path's radiance to its pixel. One slot per pixel in a pass, and
 * passes are in sample order, so the per-pixel sums are identical run to run. */
__kernel void accumulate(const GcRenderParams params,
                         __global const GcPathState* paths,
                         __global float4* film)
{
    const uint slot = get_global_id(0);
    if (slot >= params.pixel_count) return;
    const GcPathState path = paths[slot];
    /* A NaN or infinite sample would poison the pixel forever: drop it (counted as black). */
    const float3 L = path.radiance.xyz;
    const bool finite = isfinite(L.x) && isfinite(L.y) && isfinite(L.z);
    film[path.pixel] += (float4)(finite ? L : (float3)(0.0f), 1.0f);
}
