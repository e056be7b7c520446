/*
 * gc_camera.h — primary rays of the pinhole camera (GcCamera in gc_types.h).
 * Row 0 is the top of the image; (jx, jy) in [0,1)^2 is the position inside the pixel
 * (box filter: a uniform jitter).
 */
#ifndef GC_CAMERA_H
#define GC_CAMERA_H

#include "gc_accessors.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

GC_FUNC GcRay gc_camera_ray(GcCamera cam, uint width, uint height, uint px, uint py, float jx, float jy)
{
    const float sx = 2.0f * ((gc_float(px) + jx) / gc_float(width)) - 1.0f;
    const float sy = 1.0f - 2.0f * ((gc_float(py) + jy) / gc_float(height));
    const float3 dir = GC_XYZ(cam.forward) + sx * GC_XYZ(cam.right) + sy * GC_XYZ(cam.up);
    return gc_make_ray(GC_XYZ(cam.origin), gc_normalize(dir), 0.0f, GC_RAY_UNBOUNDED);
}

GC_NAMESPACE_END

#endif /* GC_CAMERA_H */
