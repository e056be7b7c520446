// kernels/shared/gc_whitted.h on the host: the local shading terms and the specular split
// that kernels/whitted.cl uses, checked against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "gc_whitted.h"

namespace gc::dev {
namespace {

constexpr float kInvPi = static_cast<float>(1.0 / std::numbers::pi);

GcMaterial material(uint type)
{
    GcMaterial m{};
    m.type = type;
    m.albedo = make_float4(0.6f, 0.4f, 0.2f, 1.0f);
    m.specular = make_float4(0.3f, 0.3f, 0.3f, 20.0f);
    m.emission = make_float4(0.0f, 0.0f, 0.0f, 1.5f);
    m.albedo_texture = GC_INVALID;
    m.metallic_roughness_texture = GC_INVALID;
    m.normal_texture = GC_INVALID;
    m.emission_texture = GC_INVALID;
    return m;
}

float3 unit(float x, float y, float z) { return normalize(make_float3(x, y, z)); }

TEST(WhittedMath, LambertBrdfCosIsAlbedoOverPiTimesCos)
{
    const GcMaterial m = material(GC_MAT_LAMBERT);
    const float3 n = make_float3(0.0f, 0.0f, 1.0f);
    const float3 wi = unit(0.3f, -0.2f, 0.8f);
    const float3 f = gc_whitted_brdf_cos(m, GC_XYZ(m.albedo), n, n, unit(0.1f, 0.5f, 0.7f), wi);
    EXPECT_NEAR(f.x, 0.6f * kInvPi * wi.z, 1e-7f);
    EXPECT_NEAR(f.z, 0.2f * kInvPi * wi.z, 1e-7f);
    // Two-sided: the same seen from below with the light below.
    const float3 below = gc_whitted_brdf_cos(m, GC_XYZ(m.albedo), n, n, unit(0.1f, 0.5f, -0.7f),
                                             make_float3(wi.x, wi.y, -wi.z));
    EXPECT_NEAR(below.x, f.x, 1e-7f);
    // Opaque: light on the other side of the geometric surface gives nothing.
    const float3 through = gc_whitted_brdf_cos(m, GC_XYZ(m.albedo), n, n, unit(0.1f, 0.5f, -0.7f), wi);
    EXPECT_EQ(through.x, 0.0f);
}

TEST(WhittedMath, PhongPeakIsNormalisedLobe)
{
    const GcMaterial m = material(GC_MAT_PHONG);
    const float3 n = make_float3(0.0f, 0.0f, 1.0f);
    const float3 wo = unit(0.4f, 0.0f, 0.9f);
    const float3 wi = gc_whitted_reflect(wo, n); // the highlight: cos alpha = 1
    const float3 f = gc_whitted_brdf_cos(m, GC_XYZ(m.albedo), n, n, wo, wi);
    const float want = (0.6f * kInvPi + 0.3f * 22.0f / (2.0f * static_cast<float>(std::numbers::pi))) * wi.z;
    std::printf("phong peak: %.6f want %.6f\n", f.x, want);
    EXPECT_NEAR(f.x, want, 1e-5f);
    // Mirror materials shade only their diffuse part locally.
    const float3 fm = gc_whitted_brdf_cos(material(GC_MAT_MIRROR), GC_XYZ(m.albedo), n, n, wo, wi);
    EXPECT_NEAR(fm.x, 0.6f * kInvPi * wi.z, 1e-7f);
    EXPECT_EQ(gc_whitted_brdf_cos(material(GC_MAT_DIELECTRIC), GC_XYZ(m.albedo), n, n, wo, wi).x, 0.0f);
}

TEST(WhittedMath, LightTerms)
{
    const float3 bc = make_float3(0.1f, 0.2f, 0.3f);
    EXPECT_NEAR(gc_whitted_point_light(bc, make_float3(4.0f, 4.0f, 4.0f), 2.0f).y, 0.4f, 1e-7f);
    EXPECT_EQ(gc_whitted_point_light(bc, make_float3(4.0f, 4.0f, 4.0f), 0.0f).y, 0.0f);
    EXPECT_NEAR(gc_whitted_area_light(bc, make_float3(2.0f, 2.0f, 2.0f), -0.5f, 4.0f, 0.25f).z, 0.3f, 1e-7f);
    const GcMaterial m = material(GC_MAT_LAMBERT);
    EXPECT_NEAR(gc_whitted_ambient(m, GC_XYZ(m.albedo), make_float3(0.5f, 0.5f, 0.5f)).x, 0.3f, 1e-7f);
    EXPECT_EQ(gc_whitted_ambient(material(GC_MAT_DIELECTRIC), GC_XYZ(m.albedo), make_float3(1.0f, 1.0f, 1.0f)).x, 0.0f);
}

TEST(WhittedMath, MirrorReflectsWithKs)
{
    const float3 n = unit(0.0f, 0.3f, 1.0f);
    const float3 wo = unit(0.5f, 0.1f, 0.6f);
    const GcWhittedSpecular s = gc_whitted_specular(material(GC_MAT_MIRROR), n, wo);
    EXPECT_EQ(s.reflect_weight.x, 0.3f);
    EXPECT_EQ(s.refract_weight.x, 0.0f);
    EXPECT_NEAR(dot(s.reflect_dir, n), dot(wo, n), 1e-6f);
    EXPECT_NEAR(length(cross(s.reflect_dir + wo, n)), 0.0f, 1e-6f); // wo + wr is along n
    EXPECT_EQ(gc_whitted_specular(material(GC_MAT_LAMBERT), n, wo).reflect_weight.x, 0.0f);
}

// Fresnel split obeys Snell's law and R + (1 - R) = 1 once the 1/eta^2 radiance scale is undone;
// beyond the critical angle everything reflects.
TEST(WhittedMath, DielectricSplitsByFresnel)
{
    const GcMaterial m = material(GC_MAT_DIELECTRIC);
    const float3 n = make_float3(0.0f, 0.0f, 1.0f);
    const float ior = 1.5f;
    for (float theta_deg : {0.0f, 30.0f, 60.0f, 85.0f}) {
        const float theta = theta_deg * static_cast<float>(std::numbers::pi) / 180.0f;
        // From outside: eta = 1.5.
        const float3 wo = make_float3(std::sin(theta), 0.0f, std::cos(theta));
        const GcWhittedSpecular s = gc_whitted_specular(m, n, wo);
        const float sin_t = std::sqrt(s.refract_dir.x * s.refract_dir.x + s.refract_dir.y * s.refract_dir.y);
        EXPECT_NEAR(std::sin(theta), ior * sin_t, 1e-5f) << theta_deg;
        EXPECT_LT(s.refract_dir.z, 0.0f);
        EXPECT_NEAR(s.reflect_weight.x + s.refract_weight.x * ior * ior, 1.0f, 1e-6f) << theta_deg;
        if (theta_deg == 0.0f) {
            EXPECT_NEAR(s.reflect_weight.x, 0.04f, 1e-6f);
        }
        // From inside (wo below n): eta = 1/1.5, TIR past asin(1/1.5) = 41.8 degrees.
        const GcWhittedSpecular in = gc_whitted_specular(m, n, make_float3(wo.x, wo.y, -wo.z));
        if (theta_deg > 42.0f) {
            EXPECT_EQ(in.reflect_weight.x, 1.0f) << theta_deg;
            EXPECT_EQ(in.refract_weight.x, 0.0f) << theta_deg;
        } else {
            EXPECT_GT(in.refract_dir.z, 0.0f);
            EXPECT_NEAR(in.reflect_weight.x + in.refract_weight.x / (ior * ior), 1.0f, 1e-6f) << theta_deg;
        }
        std::printf("theta %4.0f: R_out %.6f T_out %.6f | R_in %.6f T_in %.6f\n", theta_deg, s.reflect_weight.x,
                    s.refract_weight.x, in.reflect_weight.x, in.refract_weight.x);
    }
}

}  // namespace
}  // namespace gc::dev
