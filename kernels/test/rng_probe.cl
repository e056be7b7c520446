/*
 * rng_probe.cl — evaluates the counter-based samplers for a list of keys, so tests can check
 * that every device draws exactly the numbers the host draws (gc_rng.h on both sides).
 */
#include "gc_rng.h"

/* key: (pixel, sample, block, seed); sobol != 0: gc_sobol_rand4, else gc_rand4. */
__kernel void rng_probe(__global const uint4* keys, __global float4* values, const uint count, const uint sobol)
{
    const uint i = get_global_id(0);
    if (i >= count) return;
    const uint4 k = keys[i];
    values[i] = sobol != 0u ? gc_sobol_rand4(k.x, k.y, k.z, k.w) : gc_rand4(k.x, k.y, k.z, k.w);
}
