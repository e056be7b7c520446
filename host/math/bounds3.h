// Axis-aligned bounding box. A default-constructed box is empty (lo > hi), so union with
// anything gives that thing.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "host/math/affine.h"

namespace gc {

struct Bounds3 {
    Point3 lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
              std::numeric_limits<float>::infinity()};
    Point3 hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
              -std::numeric_limits<float>::infinity()};

    Bounds3() = default;
    explicit Bounds3(const Point3& p) : lo(p), hi(p) {}
    Bounds3(const Point3& a, const Point3& b) : lo(min(a, b)), hi(max(a, b)) {}

    bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    // The largest |coordinate| of the box (0 when empty): the magnitude that bounds the
    // rounding of anything computed from points inside it.
    float largest_abs_coordinate() const
    {
        if (empty()) return 0.0f;
        return std::max({std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z), std::fabs(hi.x), std::fabs(hi.y),
                         std::fabs(hi.z)});
    }
    Vec3 diagonal() const { return hi - lo; }
    Point3 centroid() const { return midpoint(lo, hi); }

    // Index of the longest axis.
    int max_extent() const
    {
        const Vec3 d = diagonal();
        return (d.x > d.y && d.x > d.z) ? 0 : (d.y > d.z ? 1 : 2);
    }

    float surface_area() const
    {
        if (empty()) return 0.0f;
        const Vec3 d = diagonal();
        return 2.0f * (d.x * d.y + d.y * d.z + d.z * d.x);
    }

    // Position of p relative to the box: lo -> (0,0,0), hi -> (1,1,1).
    Vec3 offset(const Point3& p) const
    {
        Vec3 o = p - lo;
        const Vec3 d = diagonal();
        if (d.x > 0) o.x /= d.x;
        if (d.y > 0) o.y /= d.y;
        if (d.z > 0) o.z /= d.z;
        return o;
    }

    bool contains(const Point3& p) const
    {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    }
    bool contains(const Bounds3& b) const { return b.empty() || (contains(b.lo) && contains(b.hi)); }
};

inline Bounds3 unite(const Bounds3& a, const Bounds3& b)
{
    Bounds3 r;
    r.lo = min(a.lo, b.lo);
    r.hi = max(a.hi, b.hi);
    return r;
}

inline Bounds3 unite(const Bounds3& a, const Point3& p)
{
    Bounds3 r;
    r.lo = min(a.lo, p);
    r.hi = max(a.hi, p);
    return r;
}

}  // namespace gc
