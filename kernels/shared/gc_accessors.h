/*
 * gc_accessors.h — named reads of the integer payloads that gc_types.h packs into float .w
 * lanes, so no kernel or host code decodes bit patterns by hand.
 */
#ifndef GC_ACCESSORS_H
#define GC_ACCESSORS_H

#include "gc_types.h"

/* +infinity as a bit pattern: none of the three languages shares an INFINITY spelling.
 * (Qualified on the host so the macro also works outside namespace gc::dev.) */
#if defined(GC_HOST)
#define GC_INFINITY (::gc::dev::gc_as_float(0x7f800000u))
#else
#define GC_INFINITY gc_as_float(0x7f800000u)
#endif

/* t_max of a ray with no far bound. +inf rather than FLT_MAX: vectorising compilers form
 * 1/d (gc_ray_precompute) by dividing the register that holds (d, t_max) whole, and
 * 1/FLT_MAX is subnormal, which costs x86 a microcode assist on every ray
 * (docs/decisions/denormals.md); 1/inf is 0. Every finite hit distance is below either
 * bound. */
#define GC_RAY_UNBOUNDED GC_INFINITY

GC_NAMESPACE_BEGIN

GC_FUNC uint gc_node_first(GcBvhNode n) { return gc_as_uint(n.lo.w); }
GC_FUNC uint gc_node_count(GcBvhNode n) { return gc_as_uint(n.hi.w); }
GC_FUNC bool gc_node_is_leaf(GcBvhNode n) { return gc_node_count(n) != 0u; }
GC_FUNC uint gc_triangle_prim(GcTriangle t) { return gc_as_uint(t.v0.w); }
GC_FUNC uint gc_triangle_flags(GcTriangle t) { return gc_as_uint(t.v1.w); }

/* Path slots of a wavefront pass: samples_in_pass samples of pixel_count pixels. */
GC_FUNC uint gc_pass_paths(GcRenderParams p) { return p.pixel_count * p.samples_in_pass; }

GC_FUNC float gc_ray_tmin(GcRay r) { return r.org_tmin.w; }
GC_FUNC float gc_ray_tmax(GcRay r) { return r.dir_tmax.w; }
GC_FUNC GcRay gc_make_ray(float3 org, float3 dir, float tmin, float tmax)
{
    GcRay r;
    r.org_tmin = make_float4(org.x, org.y, org.z, tmin);
    r.dir_tmax = make_float4(dir.x, dir.y, dir.z, tmax);
    return r;
}

GC_NAMESPACE_END

#endif /* GC_ACCESSORS_H */
