#include "host/scene/scene_checks.h"

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

}  // namespace gc
