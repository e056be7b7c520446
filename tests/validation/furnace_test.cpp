// White furnace: the camera inside a closed sphere whose every triangle emits Le and reflects
// with Lambert albedo a, Le = 1 - a per channel. Radiance is then the same everywhere and
// solves L = Le + a L, so L = Le / (1 - a) = 1 in every pixel, whatever the mesh.
// max_depth D keeps the first D terms of the series: L_D = 1 - a^D, a truncation bias of a^D
// (0.5^64 = 5e-20, 0.8^64 = 6e-7: far below the 1% tolerance). Russian roulette is unbiased.
// Exercises emission (one-sided, front faces inward), NEE + MIS with thousands of emitters,
// BSDF sampling and throughput bookkeeping: any energy gain or loss moves the mean.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include "tests/cl/cl_test_util.h"
#include "tests/validation/validation_util.h"

namespace gc {
namespace {

// A UV sphere of radius r around the origin, triangles wound to face the centre.
Scene inward_sphere(int rings, int segments, float r, const Material& material)
{
    Scene scene;
    scene.materials = {material};
    auto at = [&](int i, int j) {
        const double theta = std::numbers::pi * i / rings, phi = 2.0 * std::numbers::pi * j / segments;
        return Point3(float(r * std::sin(theta) * std::cos(phi)), float(r * std::cos(theta)),
                      float(r * std::sin(theta) * std::sin(phi)));
    };
    auto add = [&](Point3 a, Point3 b, Point3 c) {
        Vec3 n = cross(b - a, c - a);
        if (length(n) < 1e-9f) return;  // the degenerate halves of the pole quads
        const Vec3 centroid_dir = (a - Point3::origin()) + (b - Point3::origin()) + (c - Point3::origin());
        if (dot(n, centroid_dir) > 0) {  // outward: flip to inward
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
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
            add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
        }
    return scene;
}

class FurnaceTest : public cl::test::DeviceTest {};

TEST_F(FurnaceTest, ClosedEmissiveSphereGivesOneEverywhere)
{
    const glm::vec3 albedo(0.5f, 0.8f, 0.2f);
    Material m;
    m.type = MaterialType::Lambert;
    m.albedo = albedo;
    m.emission = glm::vec3(1.0f) - albedo;
    const Scene scene = inward_sphere(24, 48, 1.0f, m);

    Camera camera;
    camera.look_from = Point3(0.1f, -0.2f, 0.3f);  // off centre: radiance is uniform anyway
    camera.look_at = Point3(0.5f, 0.0f, -1.0f);
    camera.vfov_degrees = 90.0f;
    RenderSettings s;
    s.integrator = IntegratorKind::Path;
    s.width = 32;
    s.height = 32;
    s.spp = 64;
    s.seed = 3;
    s.max_depth = 64;
    const validation::Rendered got = validation::render(*context, scene, camera, s);

    double sum[3] = {0, 0, 0}, var[3] = {0, 0, 0}, worst = 0;
    for (int y = 0; y < s.height; ++y)
        for (int x = 0; x < s.width; ++x) {
            const float* p = got.mean.pixel(std::uint32_t(x), std::uint32_t(y));
            const float* v = got.variance.pixel(std::uint32_t(x), std::uint32_t(y));
            for (int c = 0; c < 3; ++c) {
                sum[c] += p[c];
                var[c] += v[c];
                worst = std::max(worst, std::fabs(double(p[c]) - 1.0));
            }
        }
    const double n = double(s.width) * s.height;
    std::printf("furnace (%u tris, %dx%d, %u spp, max depth %u, %.1f s): mean R %.5f G %.5f B %.5f "
                "(expected 1 - a^64: 1, 1 - 6e-7, 1; standard errors %.5f %.5f %.5f), worst pixel |L - 1| %.3f\n",
                unsigned(scene.triangle_count()), s.width, s.height, s.spp, s.max_depth, got.seconds, sum[0] / n,
                sum[1] / n, sum[2] / n, std::sqrt(var[0] / s.spp) / n, std::sqrt(var[1] / s.spp) / n,
                std::sqrt(var[2] / s.spp) / n, worst);
    for (int c = 0; c < 3; ++c) {
        const double expected = 1.0 - std::pow(double(albedo[c]), double(s.max_depth));
        EXPECT_NEAR(sum[c] / n, expected, 0.01) << "channel " << c;
    }
}

}  // namespace
}  // namespace gc
