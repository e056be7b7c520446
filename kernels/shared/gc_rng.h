/*
 * gc_rng.h — counter-based random numbers, independent or low-discrepancy.
 *
 * A sample's random numbers are a pure function of (pixel, sample index, dimension, seed):
 * never of thread id, queue slot or time, so every device, every batch size and every
 * wavefront ordering draws the same numbers for the same path. The hash is pcg4d from
 * Jarzynski & Olano 2020, "Hash Functions for GPU Rendering" (JCGT 9(3)): integer-only,
 * so it is bit-identical on every device and on the host (tests/render checks that).
 *
 * Dimensions come in blocks of four: one call gives four uniform floats. Integrators name
 * their blocks (see GC_RNG_BLOCK_* below) so that two uses never share a block.
 *
 * Two samplers give those four numbers (GcRenderParams.flags picks, gc_sample4):
 *   independent  gc_rand4: the hash of (pixel, sample, block, seed).
 *   sobol        gc_sobol_rand4: Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT
 *                9(4)): the first four dimensions of Sobol's sequence at the sample index,
 *                padded from block to block by shuffling the index with a nested uniform
 *                scramble seeded by (pixel, block, seed), each dimension Owen-scrambled with
 *                a seed of its own. Any 2^m consecutive samples from a multiple of 2^m are
 *                stratified in every block, so chunked and adaptive renders keep it; the
 *                estimate stays unbiased (each number is uniform) and integer-only, so
 *                bit-identical everywhere too. Sobol's dimensions 0 and 1 form a (0,2)-
 *                sequence, the best pair: they go to each block's 2D point, (x, y) in the
 *                camera's block (pixel position) and (y, z) in the others (gc_bsdf_sample's
 *                and gc_sample_light's direction or point after a choice in x).
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

/* Reverses the 32 bits of x (GLSL's bitfieldReverse; OpenCL C has none). */
GC_FUNC uint gc_reverse_bits(uint x)
{
    x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
    x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
    x = ((x >> 4u) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4u);
    x = ((x >> 8u) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8u);
    return (x >> 16u) | (x << 16u);
}

/* Laine & Karras' hash, in Burley's improved constants: each output bit depends only on the
 * input bits below it, so on a bit-reversed fraction it is an Owen scramble (nested uniform:
 * each bit flipped by a hash of the bits above it). */
GC_FUNC uint gc_laine_karras_permutation(uint x, uint seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/* Dimensions 0-3 of Sobol's sequence at a 16-bit index, each as its 32-bit fraction with the
 * bits reversed (the form the scramble below takes). Dimension 0 is the van der Corput
 * sequence (reversed: the index itself); 1-3 use the primitive polynomials x + 1, x^2 + x + 1
 * and x^3 + x + 1 with initial numbers 1; 1, 3; 1, 3, 1 (Joe & Kuo's first entries). Their
 * direction numbers are literal constants, added under a mask per bit: no table to index and
 * no branch, so GPU lanes and CPU SIMD lanes stay together (tests/bsdf/sobol_sampler_test.cpp
 * checks them against the recurrence). */
#define GC_SOBOL_BIT(k, v1, v2, v3)                \
    {                                              \
        const uint m_ = 0u - ((index >> (k)) & 1u); \
        r.y ^= (v1) & m_;                          \
        r.z ^= (v2) & m_;                          \
        r.w ^= (v3) & m_;                          \
    }
GC_FUNC uint4 gc_sobol4_reversed(uint index)
{
    uint4 r = make_uint4(index & 0xFFFFu, 0u, 0u, 0u);
    GC_SOBOL_BIT(0u, 0x00000001u, 0x00000001u, 0x00000001u)
    GC_SOBOL_BIT(1u, 0x00000003u, 0x00000003u, 0x00000003u)
    GC_SOBOL_BIT(2u, 0x00000005u, 0x00000006u, 0x00000004u)
    GC_SOBOL_BIT(3u, 0x0000000Fu, 0x00000009u, 0x0000000Au)
    GC_SOBOL_BIT(4u, 0x00000011u, 0x00000017u, 0x0000001Fu)
    GC_SOBOL_BIT(5u, 0x00000033u, 0x0000003Au, 0x0000002Eu)
    GC_SOBOL_BIT(6u, 0x00000055u, 0x00000071u, 0x00000045u)
    GC_SOBOL_BIT(7u, 0x000000FFu, 0x000000A3u, 0x000000C9u)
    GC_SOBOL_BIT(8u, 0x00000101u, 0x00000116u, 0x0000011Bu)
    GC_SOBOL_BIT(9u, 0x00000303u, 0x00000339u, 0x000002A4u)
    GC_SOBOL_BIT(10u, 0x00000505u, 0x00000677u, 0x0000079Au)
    GC_SOBOL_BIT(11u, 0x00000F0Fu, 0x000009AAu, 0x00000B67u)
    GC_SOBOL_BIT(12u, 0x00001111u, 0x00001601u, 0x0000101Eu)
    GC_SOBOL_BIT(13u, 0x00003333u, 0x00003903u, 0x0000302Du)
    GC_SOBOL_BIT(14u, 0x00005555u, 0x00007706u, 0x00004041u)
    GC_SOBOL_BIT(15u, 0x0000FFFFu, 0x0000AA09u, 0x0000A0C3u)
    return r;
}
#undef GC_SOBOL_BIT

/* Owen's scramble of a fraction given bit-reversed, returned in the usual order. */
GC_FUNC uint gc_owen_scramble_reversed(uint reversed, uint seed)
{
    return gc_reverse_bits(gc_laine_karras_permutation(reversed, seed));
}

/* Four low-discrepancy numbers in [0, 1) for (pixel, sample, block, seed): see the header.
 * The Sobol index has 16 bits: each run of 2^16 samples (sample >> 16) is scrambled with keys
 * of its own, so windows of up to 2^16 samples stay stratified with 16 direction numbers. */
GC_FUNC float4 gc_sobol_rand4(uint pixel, uint sample, uint block, uint seed)
{
    const uint4 key = gc_pcg4d(make_uint4(pixel, block, seed, (sample >> 16u) ^ 0x5EED50B0u));
    /* The index shuffled within every aligned window (Owen's scramble of its 16 bits): the
     * padding that keeps one block's points from pairing with another's. */
    const uint index = gc_owen_scramble_reversed(gc_reverse_bits(sample) & 0xFFFF0000u, key.x) & 0xFFFFu;
    const uint4 s = gc_sobol4_reversed(index);
    const float d0 = gc_uint_to_unit_float(gc_owen_scramble_reversed(s.x, key.y));
    const float d1 = gc_uint_to_unit_float(gc_owen_scramble_reversed(s.y, key.z));
    const float d2 = gc_uint_to_unit_float(gc_owen_scramble_reversed(s.z, key.w));
    const float d3 = gc_uint_to_unit_float(gc_owen_scramble_reversed(s.w, key.x ^ key.y));
    return block == GC_RNG_BLOCK_CAMERA ? make_float4(d0, d1, d2, d3) : make_float4(d2, d0, d1, d3);
}

/* The render's sampler's four numbers for (pixel, sample, block): GC_RENDER_SOBOL in flags
 * picks the low-discrepancy one. */
#define gc_sample4(params, pixel, sample, block)                                             \
    (((params).flags & GC_RENDER_SOBOL) != 0u ? gc_sobol_rand4(pixel, sample, block, (params).seed) \
                                              : gc_rand4(pixel, sample, block, (params).seed))

GC_NAMESPACE_END

#endif /* GC_RNG_H */
