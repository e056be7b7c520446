/*
 * gc_grad_slots.h — where the adjoint of the path integrator (kernels/adjoint.cl) adds each
 * parameter's gradient, and how: one 64-bit fixed-point slot per scalar parameter.
 *
 * Layout (read by the host, host/render/gradients.cpp):
 *     material i, field f     i * GC_GRAD_MATERIAL_STRIDE + f   (GC_GRAD_FIELD_*)
 *     environment radiance    env_slot + channel                 (env_slot = materials * stride)
 *     texel j of a texture    view_slots[view] + 4 j + channel   (views of textures asked for;
 *                                                                 GC_INVALID for the others)
 *
 * Only the slots of the parameters asked for are added to: `wanted` has a bit per material and
 * environment slot (texels have slots only where asked for), so a pass for one wall's colour
 * does not pay every vertex's atomics to the lights' emission and the other materials' slots.
 *
 * Fixed point, not floating-point atomics (docs/decisions/deterministic-gradients.md):
 * integer addition is associative, so the sum is the same bits in whatever order the
 * work-items add. A contribution x becomes round(x * scale), scale = 2^e chosen by the host
 * so that no sum can overflow; the largest |x| of the pass is kept (an atomic max on its
 * float bits, also order-independent) so that the host can check that choice afterwards.
 * Devices with cl_khr_int64_base_atomics add with one 64-bit atomic; others with two 32-bit
 * ones, the low word's carry added to the high word (the final value is the same, exact).
 */
#ifndef GC_GRAD_SLOTS_H
#define GC_GRAD_SLOTS_H

#define GC_GRAD_MATERIAL_STRIDE 16u
#define GC_GRAD_FIELD_BASE_COLOR 0u     /* rgb */
#define GC_GRAD_FIELD_EMISSION 3u       /* rgb */
#define GC_GRAD_FIELD_SPECULAR 6u       /* rgb: Phong's Ks, the mirror's reflectance */
#define GC_GRAD_FIELD_PHONG_EXPONENT 9u
#define GC_GRAD_FIELD_METALLIC 10u
#define GC_GRAD_FIELD_ROUGHNESS 11u
#define GC_GRAD_ENV_SLOTS 3u
/* The largest contribution's value once a slot or view index was out of range: above every
 * float's bits, so the atomic max keeps it, and the host reports the pass as failed. */
#define GC_GRAD_OUT_OF_RANGE 0xFFFFFFFFu

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)

#if defined(cl_khr_int64_base_atomics) && !defined(GC_GRAD_SPLIT_ATOMICS)
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#define GC_GRAD_INT64_ATOMICS 1
#endif

/* Where the adjoint's gradients go. */
typedef struct {
    __global ulong* slots;
    __global uint* max_bits; /* the largest |contribution| of the pass, as float bits */
    __global const uint* view_slots; /* per texture view: its texels' first slot, or GC_INVALID */
    __global const uint* wanted;     /* bit i of word i / 32: slot i < texel_slot was asked for */
    float scale;             /* 2^e: one unit of a slot is 1 / scale */
    uint env_slot;
    uint texel_slot;         /* the first texel slot: env_slot + GC_GRAD_ENV_SLOTS */
    uint slot_count;         /* slots' length: an index beyond it is a bug, flagged, not written */
    uint view_count;         /* view_slots' length */
} GcGradTarget;

/* Adds v to the 64-bit slot i of `slots`, exactly and in any order. Without 64-bit atomics:
 * little-endian, the low word first; both words wrap modulo 2^32 and the carry out of the low
 * word goes into the high one, so the two words end as the 64-bit sum. */
#if defined(GC_GRAD_INT64_ATOMICS)
#define GC_GRAD_ATOMIC_ADD(slots, i, v) atom_add(&(slots)[i], (ulong)(v))
#else
#define GC_GRAD_ATOMIC_ADD(slots, i, v)                                            \
    do {                                                                           \
        __global uint* words_ = (__global uint*)(slots);                           \
        const uint lo_ = (uint)((ulong)(v));                                       \
        const uint hi_ = (uint)((ulong)(v) >> 32);                                 \
        const uint old_ = atomic_add(&words_[2u * (i)], lo_);                      \
        const uint carry_ = old_ + lo_ < old_ ? 1u : 0u;                           \
        if (hi_ + carry_ != 0u) atomic_add(&words_[2u * (i) + 1u], hi_ + carry_);  \
    } while (0)
#endif

/* Marks the pass as failed: an index was out of range (a bug); nothing is written there. */
static inline void gc_grad_flag_out_of_range(GcGradTarget g) { atomic_max(g.max_bits, GC_GRAD_OUT_OF_RANGE); }

/* Adds the contribution x to slot i. Non-finite ones are dropped, as the film drops
 * non-finite samples (gc_film_value). */
static inline void gc_grad_add(GcGradTarget g, uint i, float x)
{
    if (!isfinite(x) || x == 0.0f) return;
    if (i >= g.slot_count) {
        gc_grad_flag_out_of_range(g);
        return;
    }
    if (i < g.texel_slot && ((g.wanted[i >> 5] >> (i & 31u)) & 1u) == 0u) return;
    /* Every work-item's every contribution would meet at this one address. The largest only
     * grows, so a plain read that is already at least |x| (a stale one is only smaller) makes
     * the atomic redundant; the final value is the same. */
    const uint bits = as_uint(fabs(x));
    if (bits > *g.max_bits) atomic_max(g.max_bits, bits);
    const long v = convert_long_sat_rte(x * g.scale);
    if (v != 0) GC_GRAD_ATOMIC_ADD(g.slots, i, v);
}

static inline void gc_grad_add3(GcGradTarget g, uint first, float3 x)
{
    gc_grad_add(g, first, x.x);
    gc_grad_add(g, first + 1u, x.y);
    gc_grad_add(g, first + 2u, x.z);
}

static inline uint gc_grad_material_slot(uint material, uint field) { return material * GC_GRAD_MATERIAL_STRIDE + field; }

#endif /* OpenCL C */

#endif /* GC_GRAD_SLOTS_H */
