// The Whitted integrator (kernels/whitted.cl) on an OpenCL device, against analytic values:
// a point-lit Lambert plane, an area-lit plane, a mirror, glass slabs, the depth bound and
// run-to-run determinism. Skips when the machine has no OpenCL device.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "gc_camera.h"
#include "gc_rng.h"
#include "host/bvh/bvh.h"
#include "host/render/renderer.h"
#include "host/render/scene_convert.h"
#include "host/scene/load.h"
#include "tests/cl/cl_test_util.h"

namespace gc {
namespace {

namespace fs = std::filesystem;

// Appends the two triangles of the quad a b c d (counter-clockwise seen from the front).
void add_quad(Scene& scene, Point3 a, Point3 b, Point3 c, Point3 d, std::uint32_t material)
{
    const Vec3 n = normalize(cross(b - a, c - a));
    const Normal3 normal(n);
    for (const Point3& p : {a, b, c, a, c, d}) {
        scene.positions.push_back(p);
        scene.normals.push_back(normal);
    }
    for (int k = 0; k < 2; ++k) {
        scene.material_ids.push_back(material);
        scene.has_vertex_normals.push_back(0);
    }
}

// A square in the plane z = height, half-size h, facing +z (up) or -z.
void add_square(Scene& scene, float height, float h, bool up, std::uint32_t material)
{
    const Point3 a(-h, -h, height), b(h, -h, height), c(h, h, height), d(-h, h, height);
    if (up) add_quad(scene, a, b, c, d, material);
    else add_quad(scene, a, d, c, b, material);
}

Material lambert(glm::vec3 albedo)
{
    Material m;
    m.type = MaterialType::Lambert;
    m.albedo = albedo;
    return m;
}

Material emitter(glm::vec3 radiance)
{
    Material m = lambert(glm::vec3(0.0f));
    m.emission = radiance;
    return m;
}

Material glass(float ior)
{
    Material m;
    m.type = MaterialType::Dielectric;
    m.albedo = glm::vec3(0.0f);
    m.ior = ior;
    return m;
}

Camera look(Point3 from, Point3 at, float fov, Vec3 up = Vec3(0, 1, 0))
{
    Camera c;
    c.look_from = from;
    c.look_at = at;
    c.up = up;
    c.vfov_degrees = fov;
    return c;
}

RenderSettings whitted_settings(int width, int height, std::uint32_t spp)
{
    RenderSettings s;
    s.integrator = IntegratorKind::Whitted;
    s.width = width;
    s.height = height;
    s.spp = spp;
    s.seed = 7;
    s.max_depth = 8;
    return s;
}

glm::vec3 rgb(const Film& film, std::uint32_t x, std::uint32_t y)
{
    const Rgba c = film.at(x, y);
    return {c.r, c.g, c.b};
}

double rel(double got, double want) { return std::fabs(got - want) / std::fabs(want); }

class WhittedTest : public cl::test::DeviceTest {
protected:
    Film render(const Scene& scene, const Camera& camera, const RenderSettings& settings)
    {
        const FlatBvh bvh = build_bvh(scene);
        Renderer renderer(*context, scene, bvh, camera, settings);
        for (std::uint32_t k = 0; k < settings.spp; ++k) renderer.render_sample();
        return renderer.film();
    }
};

// (a) Point light over a white Lambert plane: L = I * albedo/pi * cos / d^2 at the point each
// camera sample hits, recomputed on the host with the kernel's own jitter and camera ray.
// A second light below the plane must not reach the side the camera sees.
TEST_F(WhittedTest, PointLitLambertPlaneMatchesAnalytic)
{
    Scene scene;
    scene.materials = {lambert(glm::vec3(0.8f, 0.6f, 0.4f))};
    add_square(scene, 0.0f, 10.0f, true, 0);
    const glm::dvec3 light_pos(0.3, 0.2, 1.0), intensity(4.0, 2.0, 1.0);
    scene.point_lights.push_back({Point3(0.3f, 0.2f, 1.0f), glm::vec3(4.0f, 2.0f, 1.0f)});
    scene.point_lights.push_back({Point3(0.0f, 0.0f, -0.5f), glm::vec3(100.0f)});
    const Camera camera = look(Point3(0, 0, 2), Point3(0, 0, 0), 10.0f);
    const RenderSettings settings = whitted_settings(3, 3, 8);
    const Film film = render(scene, camera, settings);

    const dev::GcCamera cam = make_camera(camera, 3, 3);
    const std::uint32_t px = 1, py = 1, pixel = py * 3 + px;
    glm::dvec3 expected(0.0);
    for (std::uint32_t s = 0; s < settings.spp; ++s) {
        const dev::float4 j = settings.sampler == SamplerKind::Sobol
                                  ? dev::gc_sobol_rand4(pixel, s, GC_RNG_BLOCK_CAMERA, settings.seed)
                                  : dev::gc_rand4(pixel, s, GC_RNG_BLOCK_CAMERA, settings.seed);
        const dev::GcRay ray = dev::gc_camera_ray(cam, 3, 3, px, py, j.x, j.y);
        const glm::dvec3 o(ray.org_tmin.x, ray.org_tmin.y, ray.org_tmin.z);
        const glm::dvec3 d(ray.dir_tmax.x, ray.dir_tmax.y, ray.dir_tmax.z);
        const glm::dvec3 p = o + d * (-o.z / d.z);
        const glm::dvec3 to_light = light_pos - p;
        const double dist2 = glm::dot(to_light, to_light);
        const double cosine = to_light.z / std::sqrt(dist2);
        expected += intensity * glm::dvec3(0.8, 0.6, 0.4) * (cosine / std::numbers::pi / dist2);
    }
    expected /= static_cast<double>(settings.spp);
    const glm::vec3 got = rgb(film, px, py);
    for (int c = 0; c < 3; ++c) {
        std::printf("channel %d: got %.7f expected %.7f rel %.2e\n", c, got[c], expected[c], rel(got[c], expected[c]));
        EXPECT_LT(rel(got[c], expected[c]), 1e-4) << "channel " << c;
    }
}

// Area light: a Le = 2 square of side 1 one unit above a Lambert plane (albedo 0.5). Every
// pixel of a 0.01-degree camera sees the point under the square's centre, so the image mean
// estimates albedo/pi * Le * integral of cos cos / d^2 over the square (quadrature here).
TEST_F(WhittedTest, AreaLightEstimateConverges)
{
    Scene scene;
    scene.materials = {lambert(glm::vec3(0.5f)), emitter(glm::vec3(2.0f))};
    add_square(scene, 0.0f, 10.0f, true, 0);
    add_square(scene, 1.0f, 0.5f, false, 1);
    const Camera camera = look(Point3(0, 0, 0.5f), Point3(0, 0, 0), 0.01f);
    const Film film = render(scene, camera, whitted_settings(32, 32, 16));

    double integral = 0.0;
    const int n = 1000;
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
            const double x = -0.5 + (i + 0.5) / n, y = -0.5 + (k + 0.5) / n;
            const double d2 = x * x + y * y + 1.0;
            integral += 1.0 / (d2 * d2) / (static_cast<double>(n) * n);
        }
    const double expected = 0.5 / std::numbers::pi * 2.0 * integral;
    double sum = 0.0;
    for (std::uint32_t y = 0; y < 32; ++y)
        for (std::uint32_t x = 0; x < 32; ++x) sum += rgb(film, x, y).y;
    const double mean = sum / (32.0 * 32.0);
    std::printf("area light: mean %.6f expected %.6f rel %.2e (16384 samples)\n", mean, expected, rel(mean, expected));
    EXPECT_LT(rel(mean, expected), 0.01);
}

class WhittedObjTest : public WhittedTest {
protected:
    void SetUp() override
    {
        WhittedTest::SetUp();
        if (IsSkipped()) return;
        // A mirror (illum 3, Kd 0, Ks 0.7) at z = 0 facing the camera at z = 2; behind the
        // camera, at z = 4, an emitter facing the mirror; a grey Lambert wall at z = -1 that
        // the camera sees past the mirror's edge.
        cl::test::write_file(dir.path() / "mirror.mtl",
                             "newmtl mirror\nKd 0 0 0\nKs 0.7 0.7 0.7\nillum 3\n"
                             "newmtl light\nKd 0 0 0\nKe 1 0.5 0.25\nillum 1\n"
                             "newmtl wall\nKd 0.5 0.5 0.5\nillum 1\n");
        cl::test::write_file(dir.path() / "mirror.obj",
                             "mtllib mirror.mtl\n"
                             "v -0.2 -0.2 0\nv 0.2 -0.2 0\nv 0.2 0.2 0\nv -0.2 0.2 0\n"
                             "v -3 -3 4\nv -3 3 4\nv 3 3 4\nv 3 -3 4\n"
                             "v -5 -5 -1\nv 5 -5 -1\nv 5 5 -1\nv -5 5 -1\n"
                             "usemtl mirror\nf 1 2 3 4\n"
                             "usemtl light\nf 5 6 7 8\n"
                             "usemtl wall\nf 9 10 11 12\n");
        scene = load_scene(dir.path() / "mirror.obj");
        scene.point_lights.push_back({Point3(1.0f, 0.0f, 1.0f), glm::vec3(1.0f)});
    }

    cl::test::TempDir dir;
    Scene scene;
    Camera camera = look(Point3(0, 0, 2), Point3(0, 0, 0), 30.0f);
};

// (b) The mirror shows what is behind the camera: exactly Ks * Le at the centre.
TEST_F(WhittedObjTest, MirrorReflectsSceneBehindCamera)
{
    const Film film = render(scene, camera, whitted_settings(9, 9, 2));
    const glm::vec3 got = rgb(film, 4, 4);
    const glm::vec3 want = 0.7f * glm::vec3(1.0f, 0.5f, 0.25f);
    std::printf("mirror centre: got (%.7f %.7f %.7f) want (%.7f %.7f %.7f)\n", got.x, got.y, got.z, want.x, want.y,
                want.z);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-6f * want[c]) << "channel " << c;
    // The wall beside the mirror is lit by the emitter and the point light: not black.
    EXPECT_GT(rgb(film, 0, 0).x, 0.0f);
}

// (d) Depth bound: with --max-depth 1 only emitters and the environment appear (the mirror and
// the wall are black, a miss is env); with 2 the mirror shows the emitter and the wall its direct
// light plus the ambient env * kd.
TEST_F(WhittedObjTest, MaxDepthBoundsTheRayTree)
{
    RenderSettings s = whitted_settings(9, 9, 2);
    s.env_radiance = glm::vec3(0.1f, 0.2f, 0.3f);
    s.max_depth = 1;
    const Film one = render(scene, camera, s);
    s.max_depth = 2;
    const Film two = render(scene, camera, s);
    std::printf("depth 1: mirror %.6f wall %.6f; depth 2: mirror %.6f wall %.6f\n", rgb(one, 4, 4).x,
                rgb(one, 0, 0).x, rgb(two, 4, 4).x, rgb(two, 0, 0).x);
    for (std::uint32_t y = 0; y < 9; ++y)
        for (std::uint32_t x = 0; x < 9; ++x) EXPECT_EQ(rgb(one, x, y), glm::vec3(0.0f)) << x << "," << y;
    EXPECT_NEAR(rgb(two, 4, 4).x, 0.7f, 1e-6f);
    EXPECT_GT(rgb(two, 0, 0).z, 0.5f * 0.3f); // ambient alone gives kd * env.b = 0.15

    // Looking away from everything: the environment.
    const Film away = render(scene, look(Point3(0, 0, 4.5f), Point3(0, 0, 10), 30.0f), s);
    EXPECT_EQ(rgb(away, 4, 4), glm::vec3(0.1f, 0.2f, 0.3f));
}

// Glass slab (ior 1.5, faces at z = 0.5 and z = 0) in front of an emitter (Le = 1) seen at
// normal incidence: R = 0.04 per face, so L = (1 - R)^2 (1 + R^2 + R^4) with the in-slab
// bounces that fit in 8 segments. An index-matched slab (ior 1) is invisible.
TEST_F(WhittedTest, GlassSlabTransmitsFresnel)
{
    for (const float ior : {1.5f, 1.0f}) {
        Scene scene;
        scene.materials = {glass(ior), emitter(glm::vec3(1.0f))};
        add_square(scene, 0.5f, 1.0f, true, 0);
        add_square(scene, 0.0f, 1.0f, false, 0);
        add_square(scene, -2.0f, 5.0f, true, 1);
        const Film film = render(scene, look(Point3(0, 0, 3), Point3(0, 0, 0), 1.0f), whitted_settings(3, 3, 2));
        const double r = ior == 1.0f ? 0.0 : 0.04;
        const double want = (1 - r) * (1 - r) * (1 + r * r + r * r * r * r);
        const double got = rgb(film, 1, 1).x;
        std::printf("glass ior %.1f: got %.7f want %.7f rel %.2e\n", ior, got, want, rel(got, want));
        EXPECT_LT(rel(got, want), 1e-4) << "ior " << ior;
    }
}

// A ray tree deeper than the 16-entry stack: at --max-depth 64 the slab's internal bounces
// leave more pending exits than the stack holds, so the lightest are dropped; the sum must
// still reach the infinite series (1 - R)^2 / (1 - R^2) = (1 - R) / (1 + R) to float precision.
TEST_F(WhittedTest, DeepTreeOverflowsStackGracefully)
{
    Scene scene;
    scene.materials = {glass(1.5f), emitter(glm::vec3(1.0f))};
    add_square(scene, 0.5f, 1.0f, true, 0);
    add_square(scene, 0.0f, 1.0f, false, 0);
    add_square(scene, -2.0f, 5.0f, true, 1);
    RenderSettings s = whitted_settings(3, 3, 1);
    s.max_depth = 64;
    const Film film = render(scene, look(Point3(0, 0, 3), Point3(0, 0, 0), 1.0f), s);
    const double want = 0.96 / 1.04;
    const double got = rgb(film, 1, 1).x;
    std::printf("glass slab depth 64: got %.7f want %.7f rel %.2e\n", got, want, rel(got, want));
    EXPECT_LT(rel(got, want), 1e-5);
}

// (c) The same render twice gives the same bits (CornellBox-Sphere: mirror and glass spheres).
TEST_F(WhittedTest, BitIdenticalRuns)
{
    const fs::path path = fs::path(GC_TEST_SOURCE_DIR) / "scenes" / "cornell-box" / "CornellBox-Sphere.obj";
    if (!fs::exists(path)) GTEST_SKIP() << "missing " << path;
    const Scene scene = load_scene(path);
    const Camera camera = look(Point3(0, 1, 3.9f), Point3(0, 1, 0), 39.3077f);
    const RenderSettings s = whitted_settings(32, 32, 2);
    const Film a = render(scene, camera, s);
    const Film b = render(scene, camera, s);
    ASSERT_EQ(a.data().size(), b.data().size());
    EXPECT_EQ(std::memcmp(a.data().data(), b.data().data(), a.data().size() * sizeof(float)), 0);
    double sum = 0.0;
    for (std::size_t k = 0; k < a.data().size(); ++k)
        if (k % 4 != 3) sum += a.data()[k];
    std::printf("cornell sphere 32x32x2: sum of rgb %.6f\n", sum);
    EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace gc
