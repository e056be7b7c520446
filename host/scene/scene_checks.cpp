#include "host/scene/scene_checks.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <glm/glm.hpp>

#include "host/util/error.h"

namespace gc {

bool has_zero_area(const Point3& p0, const Point3& p1, const Point3& p2)
{
    const glm::dvec3 a(p0.glm()), b(p1.glm()), c(p2.glm());
    return glm::cross(b - a, c - a) == glm::dvec3(0.0);
}

void check_some_triangle_has_area(const Scene& scene)
{
    for (std::size_t t = 0; t < scene.triangle_count(); ++t)
        if (!has_zero_area(scene.vertex(t, 0), scene.vertex(t, 1), scene.vertex(t, 2))) return;
    if (scene.triangle_count() > 0)
        throw InputError(scene.name_for_messages() + ": every triangle has zero area (" +
                         std::to_string(scene.triangle_count()) +
                         " triangle(s), corners collinear or coincident): nothing to render");
}

void check_renderable_scale(const Scene& scene)
{
    if (scene.positions.empty()) return;
    const Bounds3 b = scene.bounds();
    const double largest = b.largest_abs_coordinate();
    const Vec3 d = b.diagonal();
    const double size = std::max({double(d.x), double(d.y), double(d.z)});
    std::ostringstream what;
    what.precision(3);
    if (largest > kLargestRenderableCoordinate) {
        what << scene.name_for_messages() << ": scene coordinates reach " << largest
             << "; geocold-cl computes in single precision and renders scenes within +-" << kLargestRenderableCoordinate
             << " units (scale the scene down)";
        throw InputError(what.str());
    }
    if (size < kSmallestRenderableSize) {
        what << scene.name_for_messages() << ": the scene is " << size << " units across; geocold-cl computes in single"
             << " precision and renders scenes at least " << kSmallestRenderableSize << " across (scale the scene up)";
        throw InputError(what.str());
    }
}

}  // namespace gc
