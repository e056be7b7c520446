// Instanced test scenes, shared by the host and device tests of the two-level traversal.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "host/scene/instances.h"
#include "test_scenes.h"

namespace gc::test {

// x rounded to a multiple of 2^-10: such coordinates, below 2^9 in size, survive the lattice
// transforms below without rounding.
inline float on_grid(float x) { return std::round(x * 1024.0f) / 1024.0f; }

inline Scene grid_soup(std::size_t n, std::uint32_t seed)
{
    Scene s = random_soup(n, seed, 0.2f);
    for (Point3& p : s.positions) p = Point3(on_grid(p.x), on_grid(p.y), on_grid(p.z));
    return s;
}

// Appends `mesh` to scene.meshes as a new mesh range.
inline void add_mesh(InstancedScene& scene, const Scene& mesh)
{
    Scene& m = scene.meshes;
    if (m.materials.empty()) m.materials = mesh.materials;
    scene.mesh_ranges.push_back({static_cast<std::uint32_t>(m.triangle_count()),
                                 static_cast<std::uint32_t>(mesh.triangle_count())});
    m.positions.insert(m.positions.end(), mesh.positions.begin(), mesh.positions.end());
    m.normals.insert(m.normals.end(), mesh.normals.begin(), mesh.normals.end());
    m.material_ids.insert(m.material_ids.end(), mesh.material_ids.begin(), mesh.material_ids.end());
    m.has_vertex_normals.insert(m.has_vertex_normals.end(), mesh.has_vertex_normals.begin(),
                                mesh.has_vertex_normals.end());
}

// Signed axis permutation `perm` (0..5) with signs `signs` (bits), times 2^scale_log2.
inline glm::mat4 lattice_linear(int perm, int signs, int scale_log2)
{
    static const int p[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {1, 0, 2}, {0, 2, 1}, {2, 1, 0}};
    glm::mat4 m(0.0f);
    const float s = std::ldexp(1.0f, scale_log2);
    for (int c = 0; c < 3; ++c) m[c][p[perm][c]] = ((signs >> c) & 1) ? -s : s;
    m[3][3] = 1.0f;
    return m;
}

// Two meshes on a 3D grid of instances under signed permutations, power-of-two scales and
// integer translations (flattening is exact), plus a twin of instance 0 with the same mesh
// and transform, so every hit on it ties in t and the instance id must decide.
inline InstancedScene lattice_instances(int per_axis, std::uint32_t seed)
{
    InstancedScene s;
    add_mesh(s, grid_soup(60, seed));
    add_mesh(s, grid_soup(25, seed + 1));
    std::mt19937 rng(seed);
    for (int x = 0; x < per_axis; ++x)
        for (int y = 0; y < per_axis; ++y)
            for (int z = 0; z < per_axis; ++z) {
                Instance inst;
                inst.mesh = static_cast<std::uint32_t>(rng() % 2);
                inst.object_to_world = lattice_linear(static_cast<int>(rng() % 6), static_cast<int>(rng() % 8),
                                                      static_cast<int>(rng() % 3) - 1);
                inst.object_to_world[3] = glm::vec4(3.0f * x, 3.0f * y, 3.0f * z, 1.0f);
                s.instances.push_back(inst);
            }
    s.instances.push_back(s.instances.front());
    return s;
}

// Random rotations, non-uniform scales and translations: flattening rounds.
inline InstancedScene rotated_instances(int count, std::uint32_t seed)
{
    InstancedScene s;
    add_mesh(s, uv_sphere(8, 12, 0.8f));
    add_mesh(s, torus_knot(64, 8, 0.15f));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int i = 0; i < count; ++i) {
        Instance inst;
        inst.mesh = static_cast<std::uint32_t>(i % 2);
        const glm::vec3 axis = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0.0f, 0.0f, 1e-3f));
        glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng)));
        m = glm::rotate(m, 3.14159f * u(rng), axis);
        inst.object_to_world = glm::scale(m, glm::vec3(1.0f + 0.5f * u(rng), 1.0f + 0.5f * u(rng), 1.0f));
        s.instances.push_back(inst);
    }
    return s;
}

// Rays with grid origins: half aimed at random triangles of the flattened scene.
inline std::vector<Ray> grid_rays(const Scene& flat, std::size_t n, std::uint32_t seed)
{
    std::vector<Ray> rays = mixed_rays(flat, n, seed);
    for (Ray& r : rays) r.origin = Point3(on_grid(r.origin.x), on_grid(r.origin.y), on_grid(r.origin.z));
    return rays;
}

// The flattened scene's index of triangle `prim` (scene of meshes) of instance `inst`.
struct FlatIndex {
    std::vector<std::uint32_t> first;  // per instance
    explicit FlatIndex(const InstancedScene& s)
    {
        std::uint32_t at = 0;
        for (const Instance& i : s.instances) {
            first.push_back(at);
            at += s.mesh_ranges[i.mesh].triangle_count;
        }
    }
    std::uint32_t operator()(const InstancedScene& s, std::uint32_t inst, std::uint32_t prim) const
    {
        return first[inst] + (prim - s.mesh_ranges[s.instances[inst].mesh].first_triangle);
    }
};

}  // namespace gc::test
