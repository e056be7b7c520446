#include "host/vk/agreement.h"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "host/util/error.h"

namespace gc::vk {

bool project_triangle(const Scene& scene, const dev::GcCamera& camera, std::uint32_t width, std::uint32_t height,
                      std::size_t tri, double xy[3][2])
{
    // The inverse of gc_camera_ray: p - origin is parallel to forward + sx right + sy up.
    const glm::dvec3 o(camera.origin), f(camera.forward), r(camera.right), u(camera.up);
    for (int k = 0; k < 3; ++k) {
        const Point3 p = scene.vertex(tri, k);
        const glm::dvec3 d = glm::dvec3(p.x, p.y, p.z) - o;
        const double z = glm::dot(d, f);
        if (!(z > 0.0)) return false;
        const double sx = glm::dot(d, r) / (glm::dot(r, r) * z);
        const double sy = glm::dot(d, u) / (glm::dot(u, u) * z);
        xy[k][0] = 0.5 * (sx + 1.0) * width;
        xy[k][1] = 0.5 * (1.0 - sy) * height;
    }
    return true;
}

namespace {

double segment_distance(double px, double py, const double a[2], const double b[2])
{
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    const double len2 = ex * ex + ey * ey;
    double t = len2 > 0.0 ? ((px - a[0]) * ex + (py - a[1]) * ey) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const double dx = px - (a[0] + t * ex), dy = py - (a[1] + t * ey);
    return std::sqrt(dx * dx + dy * dy);
}

// True when the pixel centre (px, py) is within edge_px of an edge of triangle `id`.
bool near_edge(const Scene& scene, const dev::GcCamera& camera, std::uint32_t width, std::uint32_t height,
               std::int32_t id, double px, double py, double edge_px)
{
    if (id < 0) return false;
    if (static_cast<std::size_t>(id) >= scene.triangle_count()) return true; // nonsense id: leave it to the id check
    double xy[3][2];
    if (!project_triangle(scene, camera, width, height, static_cast<std::size_t>(id), xy)) return true;
    for (int k = 0; k < 3; ++k)
        if (segment_distance(px, py, xy[k], xy[(k + 1) % 3]) <= edge_px) return true;
    return false;
}

}  // namespace

std::vector<std::uint8_t> edge_pixels(const Scene& scene, const dev::GcCamera& camera,
                                      const std::vector<std::int32_t>& ref_ids,
                                      const std::vector<std::int32_t>& test_ids, std::uint32_t width,
                                      std::uint32_t height, double edge_px)
{
    const std::size_t n = std::size_t(width) * height;
    if (ref_ids.size() != n || test_ids.size() != n)
        throw InputError("edge_pixels: id images are not " + std::to_string(width) + "x" + std::to_string(height));
    std::vector<std::uint8_t> edge(n, 0);
    for (std::uint32_t y = 0; y < height; ++y)
        for (std::uint32_t x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            const double px = x + 0.5, py = y + 0.5;
            edge[i] = (near_edge(scene, camera, width, height, ref_ids[i], px, py, edge_px) ||
                       (test_ids[i] != ref_ids[i] && near_edge(scene, camera, width, height, test_ids[i], px, py, edge_px)))
                          ? 1
                          : 0;
        }
    return edge;
}

IdDepthAgreement compare_ids_depth(const std::vector<std::int32_t>& ref_ids, const std::vector<float>& ref_depth,
                                   const std::vector<std::int32_t>& test_ids, const std::vector<float>& test_depth,
                                   const std::vector<std::uint8_t>& exclude)
{
    const std::size_t n = ref_ids.size();
    if (test_ids.size() != n || ref_depth.size() != n || test_depth.size() != n || (!exclude.empty() && exclude.size() != n))
        throw InputError("compare_ids_depth: the id, depth and exclusion images differ in size");
    IdDepthAgreement r;
    double depth_sum = 0.0;
    std::size_t depth_count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (ref_ids[i] < 0 && test_ids[i] < 0) continue;
        ++r.covered;
        if (!exclude.empty() && exclude[i]) {
            ++r.edge_excluded;
            continue;
        }
        ++r.compared;
        if (ref_ids[i] != test_ids[i]) continue;
        ++r.equal_ids;
        const double d_ref = ref_depth[i];
        const double err = d_ref > 0.0 ? std::fabs(double(test_depth[i]) - d_ref) / d_ref
                                       : (test_depth[i] == ref_depth[i] ? 0.0 : 1.0);
        r.max_depth_rel_error = std::max(r.max_depth_rel_error, std::isfinite(err) ? err : 1.0);
        depth_sum += std::isfinite(err) ? err : 1.0;
        ++depth_count;
    }
    r.id_agreement = r.compared > 0 ? double(r.equal_ids) / double(r.compared) : 1.0;
    r.mean_depth_rel_error = depth_count > 0 ? depth_sum / double(depth_count) : 0.0;
    return r;
}

std::vector<std::int32_t> ids_from_film(const Film& film)
{
    std::vector<std::int32_t> ids(film.pixel_count());
    for (std::uint32_t y = 0; y < film.height(); ++y)
        for (std::uint32_t x = 0; x < film.width(); ++x) {
            const float v = film.pixel(x, y)[0];
            ids[std::size_t(y) * film.width() + x] = v < 0.0f ? -1 : static_cast<std::int32_t>(std::lround(v));
        }
    return ids;
}

std::vector<float> depth_from_film(const Film& film)
{
    std::vector<float> depth(film.pixel_count());
    for (std::uint32_t y = 0; y < film.height(); ++y)
        for (std::uint32_t x = 0; x < film.width(); ++x) depth[std::size_t(y) * film.width() + x] = film.pixel(x, y)[0];
    return depth;
}

}  // namespace gc::vk
