// Scenes and rays built in code for the BVH tests. Random numbers come from std::mt19937,
// whose sequence the standard fixes, turned into floats here (the <random> distributions
// differ between standard libraries), so every machine tests the same rays.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "host/math/ray.h"
#include "host/scene/scene.h"

namespace gc::test {

class Rng {
public:
    explicit Rng(std::uint32_t seed) : m_engine(seed) {}
    float uniform() { return static_cast<float>(m_engine() >> 8) * 0x1p-24f; } // [0, 1)
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(m_engine() % n); }
    Vec3 direction() // uniform on the sphere
    {
        const float z = uniform(-1.0f, 1.0f);
        const float phi = uniform(0.0f, 6.2831853f);
        const float r = std::sqrt(std::fmax(0.0f, 1.0f - z * z));
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
    Point3 point(const Bounds3& b)
    {
        return {uniform(b.lo.x, b.hi.x), uniform(b.lo.y, b.hi.y), uniform(b.lo.z, b.hi.z)};
    }

private:
    std::mt19937 m_engine;
};

inline void add_triangle(Scene& scene, const Point3& a, const Point3& b, const Point3& c)
{
    scene.positions.insert(scene.positions.end(), {a, b, c});
    const Normal3 n(normalize(cross(b - a, c - a)));
    scene.normals.insert(scene.normals.end(), {n, n, n});
    scene.material_ids.push_back(0);
    scene.has_vertex_normals.push_back(0);
}

inline Scene empty_scene()
{
    Scene s;
    s.materials.emplace_back();
    return s;
}

// n triangles with vertices scattered around random centres in [-1, 1]^3; edge scale `size`.
inline Scene random_soup(std::size_t n, std::uint32_t seed, float size = 0.05f)
{
    Scene s = empty_scene();
    Rng rng(seed);
    const Bounds3 cube(Point3(-1, -1, -1), Point3(1, 1, 1));
    for (std::size_t i = 0; i < n; ++i) {
        const Point3 c = rng.point(cube);
        add_triangle(s, c + size * rng.direction(), c + size * rng.direction(), c + size * rng.direction());
    }
    return s;
}

// UV sphere of radius r around the origin, closed (poles are fans), shared vertices computed
// once so neighbouring triangles use bit-identical coordinates.
inline Scene uv_sphere(int stacks, int slices, float radius)
{
    Scene s = empty_scene();
    std::vector<Point3> grid;
    for (int i = 0; i <= stacks; ++i) {
        const float theta = 3.14159265f * static_cast<float>(i) / static_cast<float>(stacks);
        for (int j = 0; j < slices; ++j) {
            const float phi = 6.2831853f * static_cast<float>(j) / static_cast<float>(slices);
            if (i == 0) grid.emplace_back(0.0f, 0.0f, radius);
            else if (i == stacks) grid.emplace_back(0.0f, 0.0f, -radius);
            else
                grid.emplace_back(radius * std::sin(theta) * std::cos(phi), radius * std::sin(theta) * std::sin(phi),
                                  radius * std::cos(theta));
        }
    }
    auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(i * slices + (j % slices))]; };
    for (int i = 0; i < stacks; ++i) {
        for (int j = 0; j < slices; ++j) {
            if (i != 0) add_triangle(s, at(i, j), at(i + 1, j), at(i, j + 1));
            if (i != stacks - 1) add_triangle(s, at(i, j + 1), at(i + 1, j), at(i + 1, j + 1));
        }
    }
    return s;
}

// A closed tube of `sides` around a (2, 3) torus knot sampled at `segments` points: 2 *
// segments * sides triangles. It stands in for a scanned model such as the Stanford dragon:
// one surface that winds past itself, so that boxes of distant parts overlap and a ray
// crosses many layers, with long thin triangles along the tube. The knot's strands stay at
// least 1.66 apart, so a tube radius below 0.8 does not intersect itself. Shared vertices are
// computed once, as in uv_sphere.
inline Scene torus_knot(int segments, int sides, float tube_radius)
{
    Scene s = empty_scene();
    const auto curve = [](float t) {
        const float r = 2.0f + std::cos(3.0f * t);
        return Vec3(r * std::cos(2.0f * t), r * std::sin(2.0f * t), -std::sin(3.0f * t));
    };
    std::vector<Point3> grid;
    grid.reserve(static_cast<std::size_t>(segments * sides));
    for (int i = 0; i < segments; ++i) {
        const float t = 6.2831853f * static_cast<float>(i) / static_cast<float>(segments);
        const Vec3 c = curve(t);
        const Vec3 tangent = normalize(curve(t + 1e-3f) - curve(t - 1e-3f));
        const Vec3 n = normalize(cross(tangent, Vec3(0, 0, 1)));
        const Vec3 b = cross(tangent, n);
        for (int j = 0; j < sides; ++j) {
            const float phi = 6.2831853f * static_cast<float>(j) / static_cast<float>(sides);
            const Vec3 p = c + tube_radius * (std::cos(phi) * n + std::sin(phi) * b);
            grid.emplace_back(p.x, p.y, p.z);
        }
    }
    auto at = [&](int i, int j) { return grid[static_cast<std::size_t>((i % segments) * sides + (j % sides))]; };
    for (int i = 0; i < segments; ++i)
        for (int j = 0; j < sides; ++j) {
            add_triangle(s, at(i, j), at(i + 1, j), at(i + 1, j + 1));
            add_triangle(s, at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    return s;
}

// Rays with origins in the (enlarged) scene box: half towards random points of random
// triangles (so most hit), half in random directions.
inline std::vector<Ray> mixed_rays(const Scene& scene, std::size_t n, std::uint32_t seed)
{
    Rng rng(seed);
    Bounds3 b = scene.bounds();
    if (b.empty()) b = Bounds3(Point3(-1, -1, -1), Point3(1, 1, 1));
    const Vec3 pad = 0.25f * b.diagonal() + Vec3(1e-3f, 1e-3f, 1e-3f);
    const Bounds3 box(b.lo - pad, b.hi + pad);
    std::vector<Ray> rays;
    rays.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        Ray r;
        r.origin = rng.point(box);
        if (i % 2 == 0 && scene.triangle_count() > 0) {
            const std::size_t t = rng.below(static_cast<std::uint32_t>(scene.triangle_count()));
            float u = rng.uniform();
            float v = rng.uniform();
            if (u + v > 1.0f) {
                u = 1.0f - u;
                v = 1.0f - v;
            }
            r.direction = barycentric(scene.vertex(t, 0), scene.vertex(t, 1), scene.vertex(t, 2), u, v) - r.origin;
        } else {
            r.direction = rng.direction();
        }
        rays.push_back(r);
    }
    return rays;
}

}  // namespace gc::test
