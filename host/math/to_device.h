// The one place typed host math becomes the plain structs of kernels/shared/gc_types.h.
#pragma once

#include "gc_accessors.h"
#include "host/math/ray.h"

namespace gc {

inline dev::GcRay to_device(const Ray& ray)
{
    return dev::gc_make_ray(ray.origin.glm(), ray.direction.glm(), ray.tmin, ray.tmax);
}

}  // namespace gc
