// Warps of gc_sampling.h and the frame of gc_frame.h: samples land in their domain, densities
// integrate to 1, sample distributions match the densities (chi-square), the frame is
// orthonormal for every normal including (0, 0, -1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "gc_frame.h"
#include "gc_sampling.h"
#include "tests/bsdf/chi2.h"

namespace gc::dev {
namespace {

using test::kPi;
using test::Uniform;

TEST(Sampling, LuminanceOfWhiteIsOne)
{
    const float y = gc_luminance(make_float3(1.0f, 1.0f, 1.0f));
    std::printf("luminance(1,1,1) = %.7f\n", y);
    EXPECT_NEAR(y, 1.0f, 1e-6f);
    EXPECT_GT(gc_luminance(make_float3(0.0f, 1.0f, 0.0f)), gc_luminance(make_float3(1.0f, 0.0f, 0.0f)));
}

TEST(Sampling, ConcentricDiskIsInsideAndUniform)
{
    // Equal-area cells: r^2 and phi uniform for a uniform disk.
    const int n_r = 10;
    const int n_phi = 20;
    const int n = 400000;
    std::vector<double> observed(n_r * n_phi, 0.0);
    Uniform u(11);
    float max_r2 = 0.0f;
    for (int k = 0; k < n; ++k) {
        const float2 d = gc_sample_concentric_disk(u.next(), u.next());
        const float r2 = d.x * d.x + d.y * d.y;
        max_r2 = std::fmax(max_r2, r2);
        double phi = std::atan2(d.y, d.x);
        if (phi < 0.0) phi += 2.0 * kPi;
        const int ir = std::min(n_r - 1, static_cast<int>(r2 * n_r));
        const int ip = std::min(n_phi - 1, static_cast<int>(phi / (2.0 * kPi) * n_phi));
        observed[ir * n_phi + ip] += 1.0;
    }
    std::printf("max r^2 = %.7f\n", max_r2);
    EXPECT_LE(max_r2, 1.0f + 1e-6f);
    const std::vector<double> expected(n_r * n_phi, static_cast<double>(n) / (n_r * n_phi));
    const test::Chi2Result r = test::chi2_test("concentric disk", observed, expected);
    EXPECT_GT(r.p_value, r.threshold);
    // The centre and the corners of the square map to the centre and the rim.
    const float2 c = gc_sample_concentric_disk(0.5f, 0.5f);
    EXPECT_EQ(c.x, 0.0f);
    EXPECT_EQ(c.y, 0.0f);
}

TEST(Sampling, CosineHemisphere)
{
    const double integral =
        test::integrate_sphere([](glm::vec3 w) { return static_cast<double>(gc_cosine_hemisphere_pdf(w.z)); });
    std::printf("integral of cosine-hemisphere pdf = %.6f (tolerance 1e-4)\n", integral);
    EXPECT_NEAR(integral, 1.0, 1e-4);

    Uniform u(3);
    for (int k = 0; k < 100000; ++k) {
        const float3 w = gc_sample_cosine_hemisphere(u.next(), u.next());
        ASSERT_GE(w.z, 0.0f);
        ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
    }
    const test::Chi2Result r = test::chi2_sphere(
        "cosine hemisphere", [](Uniform& v) { return std::optional<glm::vec3>(gc_sample_cosine_hemisphere(v.next(), v.next())); },
        [](glm::vec3 w) { return static_cast<double>(gc_cosine_hemisphere_pdf(w.z)); });
    EXPECT_GT(r.p_value, r.threshold);
}

TEST(Sampling, UniformSphere)
{
    const double integral = test::integrate_sphere([](glm::vec3) { return static_cast<double>(gc_uniform_sphere_pdf()); });
    std::printf("integral of uniform-sphere pdf = %.6f (tolerance 1e-4)\n", integral);
    EXPECT_NEAR(integral, 1.0, 1e-4);
    Uniform u(5);
    for (int k = 0; k < 100000; ++k) ASSERT_NEAR(glm::length(gc_sample_uniform_sphere(u.next(), u.next())), 1.0f, 1e-5f);
    const test::Chi2Result r = test::chi2_sphere(
        "uniform sphere", [](Uniform& v) { return std::optional<glm::vec3>(gc_sample_uniform_sphere(v.next(), v.next())); },
        [](glm::vec3) { return static_cast<double>(gc_uniform_sphere_pdf()); });
    EXPECT_GT(r.p_value, r.threshold);
}

TEST(Sampling, UniformTriangle)
{
    // Split the triangle into m^2 congruent sub-triangles (equal areas, equal expected
    // counts): in barycentrics (b1, b2), cell (i, j) and whether frac(b1 m) + frac(b2 m) > 1.
    const int m = 8;
    const int n = 400000;
    std::vector<double> observed(2 * m * m, 0.0);
    Uniform u(13);
    for (int k = 0; k < n; ++k) {
        const float3 b = gc_sample_uniform_triangle(u.next(), u.next());
        ASSERT_GE(b.x, 0.0f);
        ASSERT_GE(b.y, 0.0f);
        ASSERT_GE(b.z, -1e-6f);
        ASSERT_NEAR(b.x + b.y + b.z, 1.0f, 1e-6f);
        const double x = b.y * m;
        const double y = b.z * m;
        const int i = std::min(m - 1, static_cast<int>(x));
        const int j = std::min(m - 1, static_cast<int>(std::max(0.0, y)));
        const int upper = (x - i) + (y - j) > 1.0 ? 1 : 0;
        observed[2 * (i * m + j) + upper] += 1.0;
    }
    // Cells with i + j >= m (and the upper halves with i + j == m - 1) lie outside the
    // triangle: they expect 0, and must receive ~0 (chi2_test fails a pool over 20).
    std::vector<double> expected(2 * m * m, 0.0);
    for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j) {
            if (i + j < m) expected[2 * (i * m + j)] = static_cast<double>(n) / (m * m);
            if (i + j < m - 1) expected[2 * (i * m + j) + 1] = static_cast<double>(n) / (m * m);
        }
    const test::Chi2Result r = test::chi2_test("uniform triangle (64 sub-triangles)", observed, expected);
    EXPECT_GT(r.p_value, r.threshold);
}

TEST(Sampling, PhongLobeAroundAxis)
{
    const float exponents[] = {1.0f, 20.0f, 200.0f};
    const float3 axis = glm::normalize(make_float3(0.3f, -0.5f, 0.6f));
    for (float e : exponents) {
        const auto pdf = [&](glm::vec3 w) { return static_cast<double>(gc_phong_lobe_pdf(glm::dot(w, axis), e)); };
        const double integral = test::integrate_sphere(pdf);
        std::printf("integral of Phong lobe pdf, n = %g: %.6f (tolerance 2e-3)\n", e, integral);
        EXPECT_NEAR(integral, 1.0, 2e-3);
        char name[64];
        std::snprintf(name, sizeof name, "Phong lobe n=%g", e);
        const test::Chi2Result r = test::chi2_sphere(
            name,
            [&](Uniform& v) { return std::optional<glm::vec3>(gc_sample_phong_lobe(axis, e, v.next(), v.next())); }, pdf);
        EXPECT_GT(r.p_value, r.threshold);
    }
}

TEST(Sampling, PowerHeuristic)
{
    EXPECT_FLOAT_EQ(gc_power_heuristic(1.0f, 1.0f), 0.5f);
    EXPECT_FLOAT_EQ(gc_power_heuristic(3.0f, 1.0f), 0.9f);
    EXPECT_FLOAT_EQ(gc_power_heuristic(1.0f, 3.0f) + gc_power_heuristic(3.0f, 1.0f), 1.0f);
    EXPECT_EQ(gc_power_heuristic(0.0f, 2.0f), 0.0f);
    EXPECT_EQ(gc_power_heuristic(2.0f, 0.0f), 1.0f);
    EXPECT_EQ(gc_power_heuristic(1e30f, 1e-30f), 1.0f);
    EXPECT_EQ(gc_power_heuristic(INFINITY, 1.0f), 1.0f);
    EXPECT_EQ(gc_power_heuristic(1.0f, INFINITY), 0.0f);
}

void expect_orthonormal(float3 n)
{
    const GcFrame f = gc_frame_from_normal(n);
    const float tol = 2e-6f;
    EXPECT_NEAR(glm::length(f.t), 1.0f, tol) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(glm::length(f.b), 1.0f, tol);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.0f, tol);
    EXPECT_NEAR(glm::dot(f.t, n), 0.0f, tol);
    EXPECT_NEAR(glm::dot(f.b, n), 0.0f, tol);
    EXPECT_LT(glm::length(glm::cross(f.t, f.b) - n), 4.0f * tol) << "frame must be right-handed";
    const float3 v = make_float3(0.2f, -0.7f, 0.4f);
    const float3 local = gc_frame_to_local(f, v);
    EXPECT_NEAR(local.z, glm::dot(v, n), tol);
    EXPECT_LT(glm::length(gc_frame_to_world(f, local) - v), 4.0f * tol);
}

TEST(Frame, OrthonormalForAllNormals)
{
    // Includes the pole Frisvad's original construction fails at, normals just beside it,
    // and z = -0.0 (whose sign must count as +1).
    const float3 special[] = {make_float3(0, 0, 1),       make_float3(0, 0, -1), make_float3(1, 0, 0),
                              make_float3(0, -1, -0.0f), glm::normalize(make_float3(1e-4f, -2e-4f, -1.0f)),
                              glm::normalize(make_float3(-3e-7f, 1e-7f, -1.0f))};
    for (const float3& n : special) expect_orthonormal(n);
    Uniform u(17);
    for (int k = 0; k < 20000; ++k) expect_orthonormal(gc_sample_uniform_sphere(u.next(), u.next()));
}

}  // namespace
}  // namespace gc::dev
