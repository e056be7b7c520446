/*
 * gc_spawn.h — where a ray that leaves a surface starts: the hit point moved off the surface
 * by a distance that holds at every scale and is the same on every device.
 *
 * Shared dialect (gc_platform.h): OpenCL C 1.2, C++20 (gc::dev) and GLSL 4.50.
 */
#ifndef GC_SPAWN_H
#define GC_SPAWN_H

#include "gc_platform.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

/* Moves p off its surface along the geometric normal n (unit, pointing to the side the new
 * ray leaves from) far enough that the new ray cannot hit the surface again.
 *
 * How far depends on how wrong p can be, and that is set by the magnitudes that entered it,
 * not by p's own coordinates (as Wächter & Binder's offset, Ray Tracing Gems ch. 6, assumes):
 * o + t d rounds by about an ulp of the ray origin o (the sum cancels when the camera is far
 * from the surface), and the watertight test's t carries error in proportion to the
 * vertices' distance from o (Woop et al. 2013), more so on needle-thin triangles. So the
 * step is a fixed fraction of M, the largest |coordinate| among o and the triangle's
 * vertices (gc_spawn_scale): 2^-16 M, which also covers 1000:1 slivers
 * (docs/decisions/spawn-offset.md). + and * only, contraction off: the same bits on every
 * device. */
#define GC_SPAWN_OFFSET 1.52587890625e-05f /* 2^-16 */

/* The largest |coordinate| of the ray origin o and of the hit triangle (tri_extent, kept
 * in GcTriangleAttribs.ng.w). The floor keeps the offset a normal float in degenerate
 * scenes (everything at the origin). */
GC_FUNC float gc_spawn_scale(float3 o, float tri_extent)
{
    return fmax(fmax(gc_max_abs(o), tri_extent), 1.0e-30f);
}

GC_FUNC float3 gc_offset_ray_origin(float3 p, float3 n, float scale)
{
    const float step = GC_SPAWN_OFFSET * scale;
    return make_float3(p.x + n.x * step, p.y + n.y * step, p.z + n.z * step);
}

/* The geometric normal on the side that direction w leaves into. */
GC_FUNC float3 gc_side_normal(float3 ng, float3 w) { return gc_dot(ng, w) >= 0.0f ? ng : -ng; }

GC_NAMESPACE_END

#endif /* GC_SPAWN_H */
