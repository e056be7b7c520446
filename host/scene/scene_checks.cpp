#include "host/scene/scene_checks.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
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

std::uint64_t physical_memory_bytes()
{
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page_size = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || page_size <= 0) return std::numeric_limits<std::uint64_t>::max();
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

std::string gibibytes(std::uint64_t bytes)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GiB", static_cast<double>(bytes) / double(1ull << 30));
    return text;
}

bool flat_triangles_fit(std::uint64_t triangles, std::string& why)
{
    const std::uint64_t memory = triangles > std::numeric_limits<std::uint64_t>::max() / kHostBytesPerFlatTriangle
                                     ? std::numeric_limits<std::uint64_t>::max()
                                     : triangles * kHostBytesPerFlatTriangle;
    if (triangles <= kMaxFlatTriangles && memory <= physical_memory_bytes()) return true;
    why = "about " + gibibytes(memory) + " of host memory (this machine has " + gibibytes(physical_memory_bytes()) +
          "; at most " + std::to_string(kMaxFlatTriangles) + " triangles are supported)";
    return false;
}

}  // namespace gc
