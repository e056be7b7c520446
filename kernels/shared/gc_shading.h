/*
 * gc_shading.h — the surface at a ray hit: position, normals, texture coordinates and
 * material, reconstructed from the hit record and the triangle's attributes.
 */
#ifndef GC_SHADING_H
#define GC_SHADING_H

#include "gc_accessors.h"
#include "gc_spawn.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

/* Not a host/device layout: a kernel-local value, so float3 is fine here. */
GC_STRUCT(GcSurface) {
    float3 p;  /* hit point */
    float3 ng; /* unit geometric normal, as wound (not flipped toward the ray) */
    float3 ns; /* unit shading normal, as interpolated (not flipped to ng's side) */
    float2 uv;
    float spawn_scale; /* gc_offset_ray_origin's scale for rays leaving p (gc_spawn.h) */
    uint material;
    uint prim;
} GC_STRUCT_END(GcSurface)

GC_FUNC GcSurface gc_surface_at(GcTriangleAttribs a, GcRay ray, GcHit hit)
{
    GcSurface s;
    const float b0 = 1.0f - hit.u - hit.v;
    s.p = GC_XYZ(ray.org_tmin) + hit.t * GC_XYZ(ray.dir_tmax);
    s.ng = GC_XYZ(a.ng);
    s.spawn_scale = gc_spawn_scale(GC_XYZ(ray.org_tmin), a.ng.w);
    const float3 n = b0 * GC_XYZ(a.n0) + hit.u * GC_XYZ(a.n1) + hit.v * GC_XYZ(a.n2);
    const float len = gc_length(n);
    /* The interpolated normal is kept as the file has it, even where it faces away from the
     * winding (badly authored meshes): as in Mitsuba 3 and pbrt-v4, the shading normal decides
     * which side of a surface a direction is on for the BSDF (a dielectric's inside, the
     * hemisphere a two-sided BRDF reflects into), and the geometric normal only decides which
     * side a new ray starts from (gc_spawn.h) and which face emits. */
    s.ns = len > 0.0f ? n * (1.0f / len) : s.ng;
    s.uv = make_float2(b0 * a.uv01.x + hit.u * a.uv01.z + hit.v * a.uv2_u,
                       b0 * a.uv01.y + hit.u * a.uv01.w + hit.v * a.uv2_v);
    s.material = a.material;
    s.prim = hit.prim;
    return s;
}

GC_NAMESPACE_END

#endif /* GC_SHADING_H */
