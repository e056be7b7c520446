// Environment-map importance sampling (kernels/shared/gc_lights.h and gc_light_sample.h +
// host/render/environment): the density integrates to one over the sphere, samples land where
// the density says, and the one-sample estimator of the incident radiance integral is unbiased.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "gc_light_sample.h"
#include "host/render/environment.h"

namespace gc {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A dim sky with a small, very bright "sun": the case importance sampling exists for.
EnvironmentMap sun_map()
{
    Film image(64, 32);
    image.fill(Rgba{0.2f, 0.3f, 0.4f, 1.0f});
    for (std::uint32_t y = 8; y < 11; ++y)
        for (std::uint32_t x = 40; x < 43; ++x) image.set(x, y, Rgba{400.0f, 350.0f, 300.0f, 1.0f});
    return make_environment_map(image);
}

struct EnvFixture {
    EnvironmentMap map = sun_map();
    dev::GcRenderParams params{};
    // Unused scene buffers: the environment branch never reads them.
    dev::GcTriangleAttribs attrib{};
    dev::GcMaterial material{};
    dev::GcTexture texture{};
    std::uint32_t texel = 0;
    dev::GcEmitter emitter{};
    dev::GcPointLight point_light{};

    EnvFixture()
    {
        params.env_width = map.width;
        params.env_height = map.height;
        params.env_radiance = {1.0f, 1.0f, 1.0f, 0.0f};
    }
    float pdf(const glm::vec3& d) const
    {
        return dev::gc_env_pdf_w(&point_light, map.pixels.data(), map.marginal_cdf.data(), map.conditional_cdf.data(),
                                 params, d);
    }
    glm::vec3 radiance(const glm::vec3& d) const
    {
        return dev::gc_env_radiance(&point_light, map.pixels.data(), map.marginal_cdf.data(),
                                    map.conditional_cdf.data(), params, d);
    }
    dev::GcLightSample sample(const glm::vec4& r) const
    {
        return dev::gc_sample_light(&attrib, &material, &texture, &texel, &emitter, &point_light, map.pixels.data(),
                                    map.marginal_cdf.data(), map.conditional_cdf.data(), params, glm::vec3(0.0f), r);
    }
};

TEST(EnvironmentLight, MappingRoundTrips)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u01(0.001f, 0.999f);
    for (int i = 0; i < 1000; ++i) {
        const float u = u01(rng), v = u01(rng);
        const glm::vec2 uv = dev::gc_env_uv(dev::gc_env_direction(u, v));
        EXPECT_NEAR(uv.x, u, 1e-4f);
        EXPECT_NEAR(uv.y, v, 1e-4f);
    }
    // +Y is up (v = 0), u = 0 looks down -Z.
    EXPECT_NEAR(dev::gc_env_direction(0.3f, 0.0f).y, 1.0f, 1e-6f);
    const glm::vec3 d = dev::gc_env_direction(0.0f, 0.5f);
    EXPECT_NEAR(d.z, -1.0f, 1e-6f);
}

TEST(EnvironmentLight, DensityIntegratesToOne)
{
    const EnvFixture f;
    // Midpoint quadrature in (theta, phi), fine enough to resolve every texel.
    const int nt = 512, np = 1024;
    double integral = 0.0;
    for (int i = 0; i < nt; ++i) {
        const double theta = kPi * (i + 0.5) / nt;
        for (int j = 0; j < np; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / np;
            const glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            integral += f.pdf(d) * std::sin(theta) * (kPi / nt) * (2.0 * kPi / np);
        }
    }
    std::printf("[env] integral of pdf_w over the sphere: %.5f\n", integral);
    EXPECT_NEAR(integral, 1.0, 5e-3);
}

TEST(EnvironmentLight, EstimatorIsUnbiasedAndSamplesFollowTheDensity)
{
    const EnvFixture f;
    // Reference: the integral of luminance over the sphere, by quadrature.
    const int nt = 512, np = 1024;
    double reference = 0.0;
    for (int i = 0; i < nt; ++i) {
        const double theta = kPi * (i + 0.5) / nt;
        for (int j = 0; j < np; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / np;
            const glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
            reference += f.radiance(d).y * std::sin(theta) * (kPi / nt) * (2.0 * kPi / np);
        }
    }
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    const int n = 200000;
    double estimate = 0.0;
    int in_sun = 0, mismatched_pdf = 0;
    for (int i = 0; i < n; ++i) {
        const dev::GcLightSample s = f.sample({u01(rng), u01(rng), u01(rng), u01(rng)});
        ASSERT_EQ(s.kind, GC_LIGHT_ENV);
        ASSERT_GT(s.pdf_w, 0.0f);
        ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
        if (std::fabs(s.pdf_w - f.pdf(s.wi)) > 1e-6f * s.pdf_w) ++mismatched_pdf;
        estimate += s.radiance.y / s.pdf_w;
        if (s.radiance.y > 100.0f) ++in_sun;
    }
    estimate /= n;
    std::printf("[env] one-sample estimate %.4f vs quadrature %.4f (rel %.2e); %.1f%% of samples in the sun\n",
                estimate, reference, std::fabs(estimate - reference) / reference, 100.0 * in_sun / n);
    EXPECT_EQ(mismatched_pdf, 0);
    EXPECT_NEAR(estimate / reference, 1.0, 0.01);
    // The sun holds most of the luminance-weighted mass, so most samples go there.
    EXPECT_GT(in_sun, n / 2);
}

TEST(EnvironmentLight, BlackMapIsEmpty)
{
    Film black(8, 4);
    black.fill(Rgba{0, 0, 0, 1});
    EXPECT_TRUE(make_environment_map(black).empty());
}

}  // namespace
}  // namespace gc
