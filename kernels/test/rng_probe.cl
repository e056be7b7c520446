/*
 * rng_probe.cl — evaluates the counter-based RNG for a list of keys, so tests can check that
 * every device draws exactly the numbers the host draws (gc_rng.h on both sides).
 */
#include "gc_rng.h"

__kernel void rng_probe(__global const uint4* keys, __global float4* values, const uint count)
{
    const uint i = get_global_id(0);
    if (i >= count) return;
    const uint4 k = keys[i];
    values[i] = gc_rand4(k.x, k.y, k.z, k.w);
}
