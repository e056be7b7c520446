#include "tools/bench/large_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace gc::bench {
namespace {

using V3 = std::array<double, 3>;

V3 normalized(const V3& v)
{
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return {v[0] / len, v[1] / len, v[2] / len};
}

// A small integer hash (splitmix-style) for per-sphere parameters: no std:: random engine,
// whose distributions differ between standard libraries.
double hash01(std::uint32_t a, std::uint32_t b)
{
    std::uint64_t x = (std::uint64_t{a} << 32) ^ b ^ 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
    return static_cast<double>(x >> 11) * (1.0 / 9007199254740992.0);
}

// Unit icosphere: the icosahedron with every face split into four `levels` times, midpoints
// pushed onto the sphere (a shared edge's midpoint is made once, so the mesh is closed).
void icosphere(int levels, std::vector<V3>& verts, std::vector<std::array<std::uint32_t, 3>>& faces)
{
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    verts = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
             {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (V3& v : verts) v = normalized(v);
    faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
             {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto it = midpoints.find(key);
            if (it != midpoints.end()) return it->second;
            const V3& p = verts[a];
            const V3& q = verts[b];
            verts.push_back(normalized({p[0] + q[0], p[1] + q[1], p[2] + q[2]}));
            const auto index = static_cast<std::uint32_t>(verts.size() - 1);
            midpoints.emplace(key, index);
            return index;
        };
        std::vector<std::array<std::uint32_t, 3>> next;
        next.reserve(faces.size() * 4);
        for (const auto& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]);
            const std::uint32_t bc = midpoint(f[1], f[2]);
            const std::uint32_t ca = midpoint(f[2], f[0]);
            next.push_back({f[0], ab, ca});
            next.push_back({f[1], bc, ab});
            next.push_back({f[2], ca, bc});
            next.push_back({ab, bc, ca});
        }
        faces = std::move(next);
    }
}

void add_triangle(Scene& scene, const Point3& a, const Point3& b, const Point3& c, std::uint32_t material)
{
    const Vec3 n = cross(b - a, c - a);
    const float len = length(n);
    const Normal3 nn = len > 0.0f ? Normal3(n / len) : Normal3(0.0f, 1.0f, 0.0f);
    scene.positions.insert(scene.positions.end(), {a, b, c});
    scene.normals.insert(scene.normals.end(), {nn, nn, nn});
    scene.material_ids.push_back(material);
    scene.has_vertex_normals.push_back(0);
}

}  // namespace

Scene make_large_mesh(int grid, int levels)
{
    Scene scene;
    scene.source_path = "<generated large mesh>";
    Material ground;
    ground.name = "ground";
    ground.albedo = glm::vec3(0.6f);
    Material body;
    body.name = "spheres";
    body.albedo = glm::vec3(0.7f, 0.5f, 0.3f);
    Material light;
    light.name = "light";
    light.albedo = glm::vec3(0.0f);
    light.emission = glm::vec3(20.0f);
    scene.materials = {ground, body, light};

    std::vector<V3> unit;
    std::vector<std::array<std::uint32_t, 3>> faces;
    icosphere(levels, unit, faces);
    const std::size_t total = static_cast<std::size_t>(grid) * grid * faces.size() + 4;
    scene.positions.reserve(3 * total);
    scene.normals.reserve(3 * total);
    scene.material_ids.reserve(total);
    scene.has_vertex_normals.reserve(total);

    // Spheres of radius ~0.4..0.6 on a unit grid, jittered, overlapping their neighbours a
    // little so rays bounce between them (incoherent secondary rays, deep overlaps).
    std::vector<Point3> displaced(unit.size());
    for (int gz = 0; gz < grid; ++gz) {
        for (int gx = 0; gx < grid; ++gx) {
            const auto id = static_cast<std::uint32_t>(gz * grid + gx);
            const double radius = 0.4 + 0.2 * hash01(id, 1);
            const double cx = gx + 0.3 * (hash01(id, 2) - 0.5);
            const double cz = gz + 0.3 * (hash01(id, 3) - 0.5);
            const double cy = radius * 0.8;
            const double f1 = 3.0 + 6.0 * hash01(id, 4);
            const double f2 = 7.0 + 10.0 * hash01(id, 5);
            const double phase = 6.283185307179586 * hash01(id, 6);
            for (std::size_t i = 0; i < unit.size(); ++i) {
                const V3& u = unit[i];
                const double bump = 0.12 * std::sin(f1 * u[0] + phase) * std::sin(f1 * u[1] - phase) +
                                    0.04 * std::sin(f2 * (u[0] + u[2]) + 2.0 * phase);
                const double r = radius * (1.0 + bump);
                displaced[i] = Point3(static_cast<float>(cx + r * u[0]), static_cast<float>(cy + r * u[1]),
                                      static_cast<float>(cz + r * u[2]));
            }
            for (const auto& f : faces) add_triangle(scene, displaced[f[0]], displaced[f[1]], displaced[f[2]], 1);
        }
    }
    const float lo = -1.0f;
    const float hi = static_cast<float>(grid);
    add_triangle(scene, {lo, 0, lo}, {lo, 0, hi}, {hi, 0, hi}, 0);
    add_triangle(scene, {lo, 0, lo}, {hi, 0, hi}, {hi, 0, lo}, 0);
    const float c = 0.5f * (grid - 1);
    const float h = 0.15f * grid;
    const float y = 2.5f;
    add_triangle(scene, {c - h, y, c - h}, {c + h, y, c - h}, {c + h, y, c + h}, 2);
    add_triangle(scene, {c - h, y, c - h}, {c + h, y, c + h}, {c - h, y, c + h}, 2);
    return scene;
}

}  // namespace gc::bench
