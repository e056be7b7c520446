// A ray with its valid parameter interval: the segment origin + t * direction, t in [tmin, tmax].
#pragma once

#include <limits>

#include "host/math/affine.h"

namespace gc {

struct Ray {
    Point3 origin;
    Vec3 direction;
    float tmin = 0.0f;
    float tmax = std::numeric_limits<float>::infinity();

    Point3 at(float t) const { return origin + t * direction; }
    bool contains(float t) const { return t >= tmin && t <= tmax; }
};

}  // namespace gc
