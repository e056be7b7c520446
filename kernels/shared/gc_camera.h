/*
 * gc_camera.h — primary rays of the camera (GcCamera in gc_types.h): a pinhole, or a thin
 * lens when cam.origin.w (the aperture radius) is positive.
 * Row 0 is the top of the image; (jx, jy) in [0,1)^2 is the position inside the pixel
 * (box filter: a uniform jitter).
 */
#ifndef GC_CAMERA_H
#define GC_CAMERA_H

#include "gc_accessors.h"
#include "gc_sampling.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

GC_FUNC GcRay gc_camera_ray(GcCamera cam, uint width, uint height, uint px, uint py, float jx, float jy)
{
    const float sx = 2.0f * ((gc_float(px) + jx) / gc_float(width)) - 1.0f;
    const float sy = 1.0f - 2.0f * ((gc_float(py) + jy) / gc_float(height));
    const float3 dir = GC_XYZ(cam.forward) + sx * GC_XYZ(cam.right) + sy * GC_XYZ(cam.up);
    return gc_make_ray(GC_XYZ(cam.origin), gc_normalize(dir), 0.0f, GC_RAY_UNBOUNDED);
}

/* The ray of camera sample u: (u.x, u.y) the position in the pixel, (u.z, u.w) the point on
 * the lens. Thin lens as pbrt-v4's PerspectiveCamera and Mitsuba 3's `thinlens`: the ray
 * leaves a point of the aperture disk (radius cam.origin.w, concentric map) towards where the
 * pinhole ray meets the plane in focus, cam.forward.w along the view axis (the pinhole
 * direction forward + sx right + sy up has a forward component of exactly 1). A zero aperture
 * is the pinhole, bit for bit. */
GC_FUNC GcRay gc_camera_sample(GcCamera cam, uint width, uint height, uint px, uint py, float4 u)
{
    if (!(cam.origin.w > 0.0f)) return gc_camera_ray(cam, width, height, px, py, u.x, u.y);
    const float sx = 2.0f * ((gc_float(px) + u.x) / gc_float(width)) - 1.0f;
    const float sy = 1.0f - 2.0f * ((gc_float(py) + u.y) / gc_float(height));
    const float3 dir = GC_XYZ(cam.forward) + sx * GC_XYZ(cam.right) + sy * GC_XYZ(cam.up);
    const float3 focus = GC_XYZ(cam.origin) + dir * cam.forward.w;
    const float2 disk = gc_sample_concentric_disk(u.z, u.w);
    const float3 lens = GC_XYZ(cam.origin) + (disk.x * cam.origin.w / gc_length(GC_XYZ(cam.right))) * GC_XYZ(cam.right) +
                        (disk.y * cam.origin.w / gc_length(GC_XYZ(cam.up))) * GC_XYZ(cam.up);
    return gc_make_ray(lens, gc_normalize(focus - lens), 0.0f, GC_RAY_UNBOUNDED);
}

GC_NAMESPACE_END

#endif /* GC_CAMERA_H */
