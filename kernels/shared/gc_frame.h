/*
 * gc_frame.h — an orthonormal shading frame built from a unit normal, and the change of basis
 * between world space and the local frame in which every BSDF is written (normal = +z).
 *
 * Shared dialect (gc_platform.h): OpenCL C 1.2, C++20 (gc::dev) and GLSL 4.50. GcFrame holds
 * float3 fields, so it is for registers only — never put it in a buffer.
 */
#ifndef GC_FRAME_H
#define GC_FRAME_H

#include "gc_platform.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

/* Right-handed: cross(t, b) == n. */
GC_STRUCT(GcFrame) {
    float3 t; /* tangent: local +x */
    float3 b; /* bitangent: local +y */
    float3 n; /* normal: local +z */
} GC_STRUCT_END(GcFrame)

/* Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an Orthonormal
 * Basis, Revisited" (JCGT 6(1)): Frisvad's branch-free construction with the singularity at
 * n.z = -1 removed by choosing the sign of n.z. sign(0) must be +1 (also for -0.0), which the
 * comparison below gives; copysign is avoided because GLSL lacks it. n must be unit length. */
GC_FUNC GcFrame gc_frame_from_normal(float3 n)
{
    float s = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (s + n.z);
    float c = n.x * n.y * a;
    GcFrame fr;
    fr.t = make_float3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
    fr.b = make_float3(c, s + n.y * n.y * a, -n.y);
    fr.n = n;
    return fr;
}

/* World -> local: the frame is orthonormal, so the inverse is the transpose. */
GC_FUNC float3 gc_frame_to_local(GcFrame fr, float3 v)
{
    return make_float3(gc_dot(v, fr.t), gc_dot(v, fr.b), gc_dot(v, fr.n));
}

/* Local -> world. */
GC_FUNC float3 gc_frame_to_world(GcFrame fr, float3 v)
{
    return fr.t * v.x + fr.b * v.y + fr.n * v.z;
}

GC_NAMESPACE_END

#endif /* GC_FRAME_H */
