/*
 * gc_vecmath.h — dot and cross products, lengths and normalisation, spelled out.
 *
 * Why not the built-ins: OpenCL leaves the precision of dot, length, normalize, cross and
 * distance to the implementation (a device may fuse the products into FMAs, sum them in
 * another order, or normalise with an approximate reciprocal square root), and GLSL says
 * even less. These decide hits, spawn points and sampling branches, so one ulp of
 * difference is enough to send the same path elsewhere on another device. Written with +, *,
 * a correctly rounded division and sqrt (the program builder asks for
 * -cl-fp32-correctly-rounded-divide-sqrt) in a fixed order, with contraction off
 * (gc_platform.h; the Vulkan reference marks every float operation NoContraction), they give
 * the same bits on every device and on the host. tests/kernels keeps the built-ins out of the
 * kernels (forbidden_builtins.h).
 *
 * Shared dialect (gc_platform.h): OpenCL C 1.2, C++20 (gc::dev) and GLSL 4.50.
 */
#ifndef GC_VECMATH_H
#define GC_VECMATH_H

#include "gc_platform.h"

GC_NAMESPACE_BEGIN

GC_FUNC float gc_dot(float3 a, float3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }

GC_FUNC float3 gc_cross(float3 a, float3 b)
{
    return make_float3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

GC_FUNC float gc_length(float3 v) { return sqrt(gc_dot(v, v)); }

/* v times the reciprocal of its length (one division instead of three). A zero vector gives
 * NaNs, as the built-in does: callers that can meet one check the length first. */
GC_FUNC float3 gc_normalize(float3 v) { return v * (1.0f / gc_length(v)); }

/* The largest |component|: the magnitude that bounds a point's rounding error. */
GC_FUNC float gc_max_abs(float3 v) { return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))); }

GC_NAMESPACE_END

#endif /* GC_VECMATH_H */
