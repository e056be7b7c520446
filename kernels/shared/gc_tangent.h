/*
 * gc_tangent.h — authored per-vertex tangents (glTF TANGENT), packed into 32 bits so that they
 * ride in the unused .w of GcTriangleAttribs.n0 / n1 / n2 at no extra memory.
 *
 * Packing (octahedral map of the unit tangent, Cigolle et al., "A Survey of Efficient
 * Representations for Independent Unit Vectors", JCGT 2014):
 *   bits  0..14  x of the octahedral point, snorm15: q in [0, 32766] is (q - 16383) / 16383
 *   bits 15..29  y, the same
 *   bit  30      always 0: the exponent of the float that carries the word can then never be
 *                all ones, so the word is never a NaN or infinity pattern, which a driver
 *                would be free to canonicalise on its way through a float
 *   bit  31      bitangent sign: set means w = -1 (B = w * cross(N, T), as glTF defines it)
 * Whether a triangle carries such tangents at all is its GC_TRIF_HAS_TANGENTS flag.
 *
 * The decode is integer ops and correctly rounded float multiplies and adds (no division, no
 * contraction: gc_platform.h turns FP_CONTRACT off), so every device gets the same octahedral
 * point; the normalisation after it uses length(), as the rest of the shading does.
 */
#ifndef GC_TANGENT_H
#define GC_TANGENT_H

#include "gc_types.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

#define GC_TANGENT_Q 16383.0f
/* 1 / 16383 rounded to float, written out so no compiler folds a division its own way. */
#define GC_TANGENT_INV_Q 6.10388815e-05f
#define GC_TANGENT_SIGN_BIT 0x80000000u

GC_FUNC float gc_sign_not_zero(float x) { return x >= 0.0f ? 1.0f : -1.0f; }

/* t: a nonzero finite tangent (need not be unit); w: its bitangent sign (negative = -1). */
GC_FUNC uint gc_tangent_encode(float3 t, float w)
{
    const float l1 = fabs(t.x) + fabs(t.y) + fabs(t.z);
    float x = t.x / l1;
    float y = t.y / l1;
    if (t.z < 0.0f) {
        /* Lower hemisphere: fold over the diagonals onto the outer triangles of the square. */
        const float fx = (1.0f - fabs(y)) * gc_sign_not_zero(x);
        const float fy = (1.0f - fabs(x)) * gc_sign_not_zero(y);
        x = fx;
        y = fy;
    }
    const uint qx = gc_uint(floor(clamp(x, -1.0f, 1.0f) * GC_TANGENT_Q + 0.5f) + GC_TANGENT_Q);
    const uint qy = gc_uint(floor(clamp(y, -1.0f, 1.0f) * GC_TANGENT_Q + 0.5f) + GC_TANGENT_Q);
    return qx | (qy << 15) | (w < 0.0f ? GC_TANGENT_SIGN_BIT : 0u);
}

/* xyz: the unit tangent; w: the bitangent sign, +1 or -1. */
GC_FUNC float4 gc_tangent_decode(uint bits)
{
    const float x = gc_float(gc_int(bits & 0x7fffu) - 16383) * GC_TANGENT_INV_Q;
    const float y = gc_float(gc_int((bits >> 15) & 0x7fffu) - 16383) * GC_TANGENT_INV_Q;
    const float z = 1.0f - fabs(x) - fabs(y);
    const float3 o = z < 0.0f ? make_float3((1.0f - fabs(y)) * gc_sign_not_zero(x),
                                            (1.0f - fabs(x)) * gc_sign_not_zero(y), z)
                              : make_float3(x, y, z);
    /* |o| >= 1/sqrt(3) for every code: never a division by zero. */
    const float3 t = o * (1.0f / gc_length(o));
    return make_float4(t.x, t.y, t.z, (bits & GC_TANGENT_SIGN_BIT) != 0u ? -1.0f : 1.0f);
}

/* The tangent frame normal maps use at barycentrics (u, v) of v1 and v2: the authored
 * tangents interpolated (not renormalised: gc_shade_normal orthonormalises against the
 * shading normal anyway) with the sign of the interpolated w, else the triangle's generated
 * tangent (xyz zero where its uvs are degenerate). */
GC_FUNC float4 gc_triangle_tangent(GcTriangleAttribs a, float u, float v)
{
    if ((a.flags & GC_TRIF_HAS_TANGENTS) == 0u) return a.tangent;
    const float4 t0 = gc_tangent_decode(gc_as_uint(a.n0.w));
    const float4 t1 = gc_tangent_decode(gc_as_uint(a.n1.w));
    const float4 t2 = gc_tangent_decode(gc_as_uint(a.n2.w));
    const float b0 = 1.0f - u - v;
    const float4 t = t0 * b0 + t1 * u + t2 * v;
    return make_float4(t.x, t.y, t.z, t.w < 0.0f ? -1.0f : 1.0f);
}

GC_NAMESPACE_END

#endif /* GC_TANGENT_H */
