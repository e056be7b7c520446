// KHR_materials_volume against Beer-Lambert: a slab of thickness d (a box 100 x 100 x d) of
// smooth refracting glass (ior 1.5, roughness 0, transmission 1) with attenuationColor c at
// attenuationDistance d0, seen head-on through a 2-degree camera in front of a constant white
// environment L = 1. At normal incidence each face reflects R = F0 = 0.04 and lets 1 - R through
// (the 1/eta^2 going in cancels coming out), the inside transmits T = c^(d / d0) per crossing,
// so summing the internal reflections the slab transmits (1 - R)^2 T / (1 - R^2 T^2) of the
// light behind it and reflects R + (1 - R)^2 R T^2 / (1 - R^2 T^2) of the light in front: the
// pixel is  L (R + (1 - R)^2 (T + R T^2) / (1 - R^2 T^2))  per channel (exactly L when T = 1,
// a furnace).
// The metric: the image mean per channel against that value, within 4 standard errors of the
// mean plus 0.5% (the 1-degree ray tilt lengthens the path by 1.5e-4 of d: negligible).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tests/cl/cl_test_util.h"
#include "tests/validation/validation_util.h"

namespace gc {
namespace {

// An axis-aligned box with outward-wound triangles and flat normals.
Scene box(Point3 lo, Point3 hi, const Material& material)
{
    Scene scene;
    scene.materials = {material};
    auto corner = [&](int i) { return Point3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
    const Point3 centre((lo.x + hi.x) / 2, (lo.y + hi.y) / 2, (lo.z + hi.z) / 2);
    const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
    for (const auto& f : faces) {
        for (const auto& tri : {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}}) {
            Point3 a = corner(tri[0]), b = corner(tri[1]), c = corner(tri[2]);
            Vec3 n = cross(b - a, c - a);
            if (dot(n, a - centre) < 0) {  // inward: flip to outward
                std::swap(b, c);
                n = -n;
            }
            const Normal3 normal(normalize(n));
            for (const Point3& p : {a, b, c}) {
                scene.positions.push_back(p);
                scene.normals.push_back(normal);
            }
            scene.material_ids.push_back(0);
            scene.has_vertex_normals.push_back(0);
        }
    }
    return scene;
}

class VolumeTest : public cl::test::DeviceTest {};

TEST_F(VolumeTest, SlabTransmitsBeerLambert)
{
    const float thickness = 1.0f, distance = 0.8f;
    const glm::vec3 colour(1.0f, 0.6f, 0.2f);
    Material m;
    m.type = MaterialType::Pbr;
    m.albedo = glm::vec3(1.0f);
    m.metallic = 0.0f;
    m.roughness = 0.0f;
    m.transmission = 1.0f;
    m.ior = 1.5f;
    m.layers.volume_on = true;
    m.layers.attenuation_color = colour;
    m.layers.attenuation_distance = distance;
    const Scene scene = box(Point3(-50, -50, -thickness / 2), Point3(50, 50, thickness / 2), m);

    Camera camera;
    camera.look_from = Point3(0, 0, 5);
    camera.look_at = Point3(0, 0, 0);
    camera.vfov_degrees = 2.0f;
    RenderSettings s;
    s.integrator = IntegratorKind::Path;
    s.width = 16;
    s.height = 16;
    s.spp = 256;
    s.seed = 5;
    s.max_depth = 24;
    s.env_radiance = glm::vec3(1.0f);
    const validation::Rendered got = validation::render(*context, scene, camera, s);

    double sum[3] = {0, 0, 0}, var[3] = {0, 0, 0};
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const float* p = got.mean.pixel(std::uint32_t(x), std::uint32_t(y));
            const float* v = got.variance.pixel(std::uint32_t(x), std::uint32_t(y));
            for (int c = 0; c < 3; ++c) {
                sum[c] += p[c];
                var[c] += v[c];
            }
        }
    const double n = double(s.width) * s.height;
    const double r = 0.04;
    for (int c = 0; c < 3; ++c) {
        const double t = std::pow(double(colour[c]), double(thickness / distance));
        const double expected = r + (1 - r) * (1 - r) * (t + r * t * t) / (1 - r * r * t * t);
        const double mean = sum[c] / n;
        const double se = std::sqrt(var[c] / s.spp) / n;
        std::printf("[beer-lambert] channel %d: T = %.4f, mean %.5f expected %.5f (standard error %.5f)\n", c, t, mean,
                    expected, se);
        EXPECT_NEAR(mean, expected, 4.0 * se + 0.005 * expected) << "channel " << c;
    }
}

}  // namespace
}  // namespace gc
