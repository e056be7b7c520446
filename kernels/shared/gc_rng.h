/*
 * gc_rng.h — counter-based random numbers.
 *
 * A sample's random numbers are a pure function of (pixel, sample index, dimension, seed):
 * never of thread id, queue slot or time, so every device, every batch size and every
 * wavefront ordering draws the same numbers for the same path. The hash is pcg4d from
 * Jarzynski & Olano 2020, "Hash Functions for GPU Rendering" (JCGT 9(3)): integer-only,
 * so it is bit-identical on every device and on the host (tests/render checks that).
 *
 * Dimensions come in blocks of four: one hash gives four uniform floats. Integrators name
 * their blocks (see GC_RNG_BLOCK_* below) so that two uses never share a block.
 */
#ifndef GC_RNG_H
#define GC_RNG_H

#include "gc_platform.h"

GC_NAMESPACE_BEGIN

GC_FUNC uint4 gc_pcg4d(uint4 v)
{
    /* In four scalars rather than one uint4: the same operations and bits, but written on the
     * vector, the hash compiled on CPUs to lane extracts and inserts around every multiply of
     * its dependent chain (PoCL, x86). GPUs compile both forms alike
     * (docs/decisions/random-numbers.md). */
    uint x = v.x * 1664525u + 1013904223u;
    uint y = v.y * 1664525u + 1013904223u;
    uint z = v.z * 1664525u + 1013904223u;
    uint w = v.w * 1664525u + 1013904223u;
    x += y * w;
    y += z * x;
    z += x * y;
    w += y * z;
    x ^= x >> 16u;
    y ^= y >> 16u;
    z ^= z >> 16u;
    w ^= w >> 16u;
    x += y * w;
    y += z * x;
    z += x * y;
    w += y * z;
    return make_uint4(x, y, z, w);
}

/* Maps 32 random bits to a float in [0, 1): the top 24 bits, exactly representable. */
GC_FUNC float gc_uint_to_unit_float(uint bits) { return gc_float(bits >> 8u) * (1.0f / 16777216.0f); }

/* Four uniform numbers in [0, 1) for (pixel, sample, block, seed). */
GC_FUNC float4 gc_rand4(uint pixel, uint sample, uint block, uint seed)
{
    const uint4 h = gc_pcg4d(make_uint4(pixel, sample, block, seed));
    return make_float4(gc_uint_to_unit_float(h.x), gc_uint_to_unit_float(h.y),
                       gc_uint_to_unit_float(h.z), gc_uint_to_unit_float(h.w));
}

/* Block layout shared by every integrator. Block 0 is the camera (pixel jitter); each
 * bounce then owns GC_RNG_BLOCKS_PER_BOUNCE consecutive blocks. */
#define GC_RNG_BLOCK_CAMERA 0u
#define GC_RNG_BLOCKS_PER_BOUNCE 4u
#define GC_RNG_BLOCK_BSDF 0u      /* lobe choice + direction */
#define GC_RNG_BLOCK_LIGHT 1u     /* emitter choice + point on it */
#define GC_RNG_BLOCK_ROULETTE 2u  /* Russian roulette, alpha, misc */
#define GC_RNG_BLOCK_EXTRA 3u

GC_FUNC uint gc_rng_block(uint bounce, uint which) { return 1u + bounce * GC_RNG_BLOCKS_PER_BOUNCE + which; }

GC_NAMESPACE_END

#endif /* GC_RNG_H */
