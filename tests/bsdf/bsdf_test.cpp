// gc_bsdf.h against its own contract: densities integrate to the non-delta probability,
// samples follow the density (chi-square), sample() agrees with eval()/pdf(), white furnace,
// reciprocity, two-sidedness, and the dielectric's Fresnel, TIR and energy balance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "gc_bsdf.h"
#include "tests/bsdf/chi2.h"

namespace gc::dev {
namespace {

using test::kPi;
using test::Uniform;

GcMaterial make_material(uint type, float3 kd, float3 ks = make_float3(0, 0, 0), float exponent = 0.0f,
                         float ior = 1.0f)
{
    GcMaterial m{};
    m.type = type;
    m.albedo = make_float4(kd.x, kd.y, kd.z, 1.0f);
    m.specular = make_float4(ks.x, ks.y, ks.z, exponent);
    m.emission = make_float4(0.0f, 0.0f, 0.0f, ior);
    m.albedo_texture = GC_INVALID;
    m.metallic_roughness_texture = GC_INVALID;
    m.normal_texture = GC_INVALID;
    m.emission_texture = GC_INVALID;
    return m;
}

float3 grey(float v) { return make_float3(v, v, v); }

// Direction at polar angle theta_deg from +z (values above 90 are below the surface).
float3 dir_deg(float theta_deg, float phi = 0.7f)
{
    return test::spherical(theta_deg * kPi / 180.0, phi);
}

float3 kd_of(const GcMaterial& m) { return GC_XYZ(m.albedo); }

struct Case {
    std::string name;
    GcMaterial m;
    float3 wo;
};

// Non-delta materials (the mirror has a diffuse part) with several parameter sets and
// outgoing directions, including wo below the surface (two-sided).
std::vector<Case> non_delta_cases()
{
    return {
        {"lambert wo=30", make_material(GC_MAT_LAMBERT, make_float3(0.8f, 0.5f, 0.2f)), dir_deg(30)},
        {"lambert wo=120 (back side)", make_material(GC_MAT_LAMBERT, make_float3(0.8f, 0.5f, 0.2f)), dir_deg(120)},
        {"phong kd.5 ks.4 n10 wo=5", make_material(GC_MAT_PHONG, grey(0.5f), grey(0.4f), 10.0f), dir_deg(5)},
        {"phong kd.5 ks.4 n10 wo=45", make_material(GC_MAT_PHONG, grey(0.5f), grey(0.4f), 10.0f), dir_deg(45)},
        {"phong kd.2 ks.7 n100 wo=60", make_material(GC_MAT_PHONG, grey(0.2f), make_float3(0.7f, 0.6f, 0.5f), 100.0f),
         dir_deg(60)},
        {"phong kd0 ks1 n1 wo=80", make_material(GC_MAT_PHONG, grey(0.0f), grey(1.0f), 1.0f), dir_deg(80)},
        {"phong kd.3 ks.6 n30 wo=140 (back)", make_material(GC_MAT_PHONG, make_float3(0.3f, 0.1f, 0.2f), grey(0.6f), 30.0f),
         dir_deg(140)},
        {"mirror kd.4 ks.5 wo=30", make_material(GC_MAT_MIRROR, grey(0.4f), grey(0.5f)), dir_deg(30)},
        {"mirror kd.6 ks.2 wo=110 (back)", make_material(GC_MAT_MIRROR, make_float3(0.6f, 0.3f, 0.1f), grey(0.2f)),
         dir_deg(110)},
    };
}

// Probability that gc_bsdf_sample returns a delta sample.
double delta_probability(const GcMaterial& m)
{
    if (m.type != GC_MAT_MIRROR) return 0.0;
    return gc_bsdf_specular_prob(kd_of(m), GC_XYZ(m.specular));
}

GcBsdfSample draw(const GcMaterial& m, float3 wo, Uniform& u)
{
    const float u0 = u.next();
    const float u1 = u.next();
    const float u2 = u.next();
    return gc_bsdf_sample(m, kd_of(m), wo, u0, u1, u2);
}

TEST(Bsdf, PdfIntegratesToNonDeltaProbability)
{
    for (const Case& c : non_delta_cases()) {
        const double integral = test::integrate_sphere(
            [&](glm::vec3 wi) { return static_cast<double>(gc_bsdf_pdf(c.m, kd_of(c.m), c.wo, wi)); });
        // The Phong lobe loses the part of its mass below the horizon (those samples fail):
        // measure that fraction by sampling and require integral + lost == 1 - P(delta).
        const int n = 200000;
        Uniform u(21);
        int failed = 0;
        for (int k = 0; k < n; ++k)
            if (draw(c.m, c.wo, u).flags == 0u) ++failed;
        const double lost = static_cast<double>(failed) / n;
        const double sigma = std::sqrt(lost * (1.0 - lost) / n);
        const double expected = 1.0 - delta_probability(c.m) - lost;
        const double tol = 2e-3 + 5.0 * sigma;
        std::printf("[pdf integral] %-36s %.5f  expected %.5f (lost %.5f)  tolerance %.1e\n", c.name.c_str(), integral,
                    expected, lost, tol);
        EXPECT_NEAR(integral, expected, tol) << c.name;
        EXPECT_LE(integral, 1.0 + 2e-3) << c.name;
    }
}

TEST(Bsdf, PhongPdfIsExactlyNormalisedAtNormalIncidence)
{
    // At wo = +z the specular lobe lies wholly above the horizon: nothing is lost.
    for (float e : {1.0f, 10.0f, 100.0f}) {
        const GcMaterial m = make_material(GC_MAT_PHONG, grey(0.3f), grey(0.6f), e);
        const double integral = test::integrate_sphere(
            [&](glm::vec3 wi) { return static_cast<double>(gc_bsdf_pdf(m, kd_of(m), make_float3(0, 0, 1), wi)); });
        std::printf("[pdf integral] phong n=%-5g wo=+z  %.6f (tolerance 1e-3)\n", e, integral);
        EXPECT_NEAR(integral, 1.0, 1e-3);
    }
}

TEST(Bsdf, SamplesFollowPdfChiSquare)
{
    for (const Case& c : non_delta_cases()) {
        const test::Chi2Result r = test::chi2_sphere(
            c.name,
            [&](Uniform& u) -> std::optional<glm::vec3> {
                const GcBsdfSample s = draw(c.m, c.wo, u);
                if (s.flags == 0u || (s.flags & GC_BSDF_SPECULAR) != 0u) return std::nullopt;
                return s.wi;
            },
            [&](glm::vec3 wi) { return static_cast<double>(gc_bsdf_pdf(c.m, kd_of(c.m), c.wo, wi)); });
        EXPECT_GT(r.p_value, r.threshold) << c.name;
    }
}

TEST(Bsdf, SampleAgreesWithEvalAndPdf)
{
    for (const Case& c : non_delta_cases()) {
        Uniform u(31);
        int delta = 0;
        for (int k = 0; k < 20000; ++k) {
            const GcBsdfSample s = draw(c.m, c.wo, u);
            if (s.flags == 0u) continue;
            ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-5f) << c.name;
            ASSERT_EQ(s.flags & GC_BSDF_TRANSMISSION, 0u) << c.name;
            ASSERT_GT(s.wi.z * c.wo.z, 0.0f) << c.name << ": reflection stays on wo's side";
            if ((s.flags & GC_BSDF_SPECULAR) != 0u) {
                ++delta;
                const float3 ks = GC_XYZ(c.m.specular);
                const float p = gc_bsdf_specular_prob(kd_of(c.m), ks);
                ASSERT_LT(glm::length(s.wi - gc_reflect_z(c.wo)), 1e-6f);
                ASSERT_NEAR(s.pdf_w, p, 1e-6f);
                ASSERT_LT(glm::length(s.weight - ks / p), 1e-5f);
                ASSERT_LT(glm::length(s.f * std::fabs(s.wi.z) / s.pdf_w - s.weight), 1e-5f);
                continue;
            }
            const float pdf = gc_bsdf_pdf(c.m, kd_of(c.m), c.wo, s.wi);
            const float3 f = gc_bsdf_eval(c.m, kd_of(c.m), c.wo, s.wi);
            ASSERT_EQ(s.pdf_w, pdf) << c.name;
            ASSERT_EQ(s.f.x, f.x) << c.name;
            ASSERT_EQ(s.f.y, f.y) << c.name;
            ASSERT_EQ(s.f.z, f.z) << c.name;
            const float3 w = f * std::fabs(s.wi.z) / pdf;
            ASSERT_LT(glm::length(s.weight - w), 1e-5f * (1.0f + glm::length(w))) << c.name;
        }
        EXPECT_EQ(delta > 0, delta_probability(c.m) > 0.0) << c.name;
    }
}

TEST(Bsdf, Reciprocity)
{
    for (const Case& c : non_delta_cases()) {
        Uniform u(41);
        float worst = 0.0f;
        for (int k = 0; k < 20000; ++k) {
            float3 a = gc_sample_uniform_sphere(u.next(), u.next());
            float3 b = gc_sample_uniform_sphere(u.next(), u.next());
            if (a.z * b.z < 0.0f) b.z = -b.z; // same side, so f is not trivially zero
            const float3 fab = gc_bsdf_eval(c.m, kd_of(c.m), a, b);
            const float3 fba = gc_bsdf_eval(c.m, kd_of(c.m), b, a);
            const float err = glm::length(fab - fba) / (1e-3f + glm::length(fab));
            worst = std::fmax(worst, err);
        }
        std::printf("[reciprocity] %-36s max relative |f(a,b) - f(b,a)| = %.2e\n", c.name.c_str(), worst);
        EXPECT_LT(worst, 1e-4f) << c.name;
    }
}

TEST(Bsdf, TwoSidedAndNoTransmission)
{
    for (const Case& c : non_delta_cases()) {
        Uniform u(43);
        for (int k = 0; k < 2000; ++k) {
            float3 a = gc_sample_uniform_sphere(u.next(), u.next());
            float3 b = gc_sample_uniform_sphere(u.next(), u.next());
            const float3 flipped_a = make_float3(a.x, a.y, -a.z);
            const float3 flipped_b = make_float3(b.x, b.y, -b.z);
            // Mirroring both directions through the surface changes nothing.
            const float3 f = gc_bsdf_eval(c.m, kd_of(c.m), a, b);
            ASSERT_EQ(f, gc_bsdf_eval(c.m, kd_of(c.m), flipped_a, flipped_b)) << c.name;
            ASSERT_EQ(gc_bsdf_pdf(c.m, kd_of(c.m), a, b), gc_bsdf_pdf(c.m, kd_of(c.m), flipped_a, flipped_b));
            // Opposite sides: nothing passes through a non-dielectric.
            if (a.z * b.z < 0.0f) {
                ASSERT_EQ(f, grey(0.0f)) << c.name;
                ASSERT_EQ(gc_bsdf_pdf(c.m, kd_of(c.m), a, b), 0.0f) << c.name;
            }
        }
    }
}

// Directional albedo rho(wo) = integral of f cos over wi, estimated as the mean sample
// weight (this includes delta lobes). Returns the mean and its standard error (luminance).
struct Albedo {
    double mean;
    double stderr_;
};

Albedo directional_albedo(const GcMaterial& m, float3 wo, int n, std::uint32_t seed)
{
    Uniform u(seed);
    double sum = 0.0;
    double sum2 = 0.0;
    for (int k = 0; k < n; ++k) {
        const GcBsdfSample s = draw(m, wo, u);
        const double w = s.flags == 0u ? 0.0 : gc_luminance(s.weight);
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(Bsdf, WhiteFurnace)
{
    struct Furnace {
        std::string name;
        GcMaterial m;
        bool expect_one; // exactly 1 for every wo (no lobe mass lost below the horizon)
    };
    const std::vector<Furnace> cases = {
        {"lambert albedo 1", make_material(GC_MAT_LAMBERT, grey(1.0f)), true},
        {"phong kd.5 ks.5 n10", make_material(GC_MAT_PHONG, grey(0.5f), grey(0.5f), 10.0f), false},
        {"phong kd0 ks1 n1", make_material(GC_MAT_PHONG, grey(0.0f), grey(1.0f), 1.0f), false},
        {"phong kd.1 ks.9 n200", make_material(GC_MAT_PHONG, grey(0.1f), grey(0.9f), 200.0f), false},
        {"phong kd.8 ks.2 n1000", make_material(GC_MAT_PHONG, grey(0.8f), grey(0.2f), 1000.0f), false},
        {"mirror kd0 ks1", make_material(GC_MAT_MIRROR, grey(0.0f), grey(1.0f)), true},
        {"mirror kd.3 ks.7", make_material(GC_MAT_MIRROR, grey(0.3f), grey(0.7f)), true},
    };
    for (const Furnace& c : cases) {
        Uniform dirs(51);
        double lo = 1e9;
        double hi = -1e9;
        for (int k = 0; k < 64; ++k) {
            const float3 wo = gc_sample_uniform_sphere(dirs.next(), dirs.next());
            const Albedo a = directional_albedo(c.m, wo, 20000, 100 + k);
            lo = std::min(lo, a.mean);
            hi = std::max(hi, a.mean);
            EXPECT_LE(a.mean, 1.0 + 1e-3 + 4.0 * a.stderr_) << c.name << " wo.z = " << wo.z;
            if (c.expect_one) {
                EXPECT_NEAR(a.mean, 1.0, 0.01) << c.name << " wo.z = " << wo.z;
            }
        }
        std::printf("[furnace] %-24s directional albedo over 64 wo: min %.4f  max %.4f\n", c.name.c_str(), lo, hi);
    }
    // The (n+2)/(2 pi) normalisation: a pure Phong lobe with ks = 1 has albedo 1 at normal
    // incidence, for any exponent (Lafortune & Willems 1994).
    for (float e : {1.0f, 10.0f, 100.0f, 1000.0f}) {
        const GcMaterial m = make_material(GC_MAT_PHONG, grey(0.0f), grey(1.0f), e);
        const Albedo a = directional_albedo(m, make_float3(0, 0, 1), 200000, 7);
        std::printf("[furnace] phong ks1 n=%-6g wo=+z albedo %.5f +- %.5f\n", e, a.mean, a.stderr_);
        EXPECT_NEAR(a.mean, 1.0, 0.01);
    }
    // The same figure for Lambert by quadrature, independent of the sampler.
    const GcMaterial white = make_material(GC_MAT_LAMBERT, grey(1.0f));
    const float3 wo = dir_deg(40);
    const double q = test::integrate_sphere(
        [&](glm::vec3 wi) { return gc_bsdf_eval(white, kd_of(white), wo, wi).x * std::fabs(static_cast<double>(wi.z)); },
        512, 1024);
    std::printf("[furnace] lambert albedo 1 by quadrature: %.6f\n", q);
    EXPECT_NEAR(q, 1.0, 1e-3);
}

// ------------------------------------------------------------------ dielectric

TEST(Dielectric, FresnelAtNormalIncidence)
{
    for (float ior : {1.33f, 1.5f, 2.4f}) {
        const float expected = ((ior - 1.0f) / (ior + 1.0f)) * ((ior - 1.0f) / (ior + 1.0f));
        const float outside = gc_fresnel_dielectric(1.0f, ior);
        const float inside = gc_fresnel_dielectric(1.0f, 1.0f / ior);
        std::printf("[fresnel] ior %.2f at normal incidence: %.6f (outside) %.6f (inside), expected %.6f\n", ior,
                    outside, inside, expected);
        EXPECT_NEAR(outside, expected, 1e-6f);
        EXPECT_NEAR(inside, expected, 1e-6f);
    }
    // Grazing incidence reflects everything; index-matched interfaces reflect nothing.
    EXPECT_NEAR(gc_fresnel_dielectric(0.0f, 1.5f), 1.0f, 1e-6f);
    EXPECT_NEAR(gc_fresnel_dielectric(0.6f, 1.0f), 0.0f, 1e-7f);
}

TEST(Dielectric, TotalInternalReflection)
{
    const float ior = 1.5f;
    const GcMaterial m = make_material(GC_MAT_DIELECTRIC, grey(1.0f), grey(0.0f), 0.0f, ior);
    const double critical = std::asin(1.0 / ior) * 180.0 / kPi;
    std::printf("[tir] critical angle for ior 1.5: %.3f deg\n", critical);
    for (float deg : {42.5f, 50.0f, 70.0f, 89.0f}) {
        const float3 wo = dir_deg(180.0f - deg); // inside the glass
        EXPECT_EQ(gc_fresnel_dielectric(std::fabs(wo.z), gc_dielectric_eta(m, wo)), 1.0f) << deg;
        Uniform u(61);
        for (int k = 0; k < 1000; ++k) {
            const GcBsdfSample s = draw(m, wo, u);
            ASSERT_EQ(s.flags, GC_BSDF_REFLECTION | GC_BSDF_SPECULAR) << deg;
            ASSERT_LT(glm::length(s.wi - gc_reflect_z(wo)), 1e-6f);
            ASSERT_LT(glm::length(s.weight - grey(1.0f)), 1e-6f);
        }
    }
    // Just inside the critical angle some light still leaves.
    const float3 wo = dir_deg(180.0f - 40.0f);
    const float fr = gc_fresnel_dielectric(std::fabs(wo.z), gc_dielectric_eta(m, wo));
    std::printf("[tir] F at 40 deg inside: %.4f\n", fr);
    EXPECT_LT(fr, 1.0f);
    EXPECT_EQ(gc_bsdf_sample(m, grey(1.0f), wo, 0.9999f, 0.5f, 0.5f).flags, GC_BSDF_TRANSMISSION | GC_BSDF_SPECULAR);
}

TEST(Dielectric, EnergyBalanceAndSnell)
{
    for (float ior : {1.33f, 1.5f, 2.4f}) {
        const GcMaterial m = make_material(GC_MAT_DIELECTRIC, grey(1.0f), grey(0.0f), 0.0f, ior);
        for (float deg : {0.5f, 20.0f, 45.0f, 75.0f, 89.0f, 120.0f, 150.0f, 179.5f}) {
            const float3 wo = dir_deg(deg);
            const float eta = gc_dielectric_eta(m, wo);
            const float fr = gc_fresnel_dielectric(std::fabs(wo.z), eta);
            Uniform u(71);
            const int n = 40000;
            int reflected = 0;
            double energy = 0.0;
            for (int k = 0; k < n; ++k) {
                const GcBsdfSample s = draw(m, wo, u);
                ASSERT_NE(s.flags & GC_BSDF_SPECULAR, 0u);
                ASSERT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
                ASSERT_LT(glm::length(s.f * std::fabs(s.wi.z) / s.pdf_w - s.weight), 1e-4f * glm::length(s.weight));
                if ((s.flags & GC_BSDF_REFLECTION) != 0u) {
                    ++reflected;
                    ASSERT_LT(glm::length(s.wi - gc_reflect_z(wo)), 1e-6f);
                    energy += s.weight.x;
                    continue;
                }
                ASSERT_EQ(s.flags, GC_BSDF_TRANSMISSION | GC_BSDF_SPECULAR);
                ASSERT_LT(s.wi.z * wo.z, 0.0f) << "refraction crosses the surface";
                // Snell: sin_t = sin_i / eta, in the plane of incidence (tangent parts opposite).
                const float sin_i = std::sqrt(wo.x * wo.x + wo.y * wo.y);
                const float sin_t = std::sqrt(s.wi.x * s.wi.x + s.wi.y * s.wi.y);
                ASSERT_NEAR(sin_t * eta, sin_i, 1e-5f);
                ASSERT_LE(s.wi.x * wo.x + s.wi.y * wo.y, 1e-7f);
                // Radiance scaling: weight = 1 / eta^2; undo it for the energy balance.
                ASSERT_NEAR(s.weight.x, 1.0f / (eta * eta), 1e-5f / (eta * eta));
                energy += s.weight.x * eta * eta;
            }
            // The delta coefficients themselves: f |cos| is F for the reflected lobe and
            // T / eta^2 for the refracted one, so R + T (eta^2 undone) must be 1.
            const GcBsdfSample r = gc_bsdf_sample(m, grey(1.0f), wo, 0.0f, 0.5f, 0.5f);
            const GcBsdfSample t = gc_bsdf_sample(m, grey(1.0f), wo, 0.99999994f, 0.5f, 0.5f);
            const double big_r = (r.flags & GC_BSDF_REFLECTION) != 0u ? r.f.x * std::fabs(r.wi.z) : 0.0;
            double big_t = 0.0;
            if ((t.flags & GC_BSDF_TRANSMISSION) != 0u) big_t = t.f.x * std::fabs(t.wi.z) * eta * eta;
            else EXPECT_EQ(fr, 1.0f) << "only total internal reflection may refuse to refract";
            EXPECT_NEAR(big_r, fr, 1e-6);
            EXPECT_NEAR(big_r + big_t, 1.0, 1e-5);
            const double frac = static_cast<double>(reflected) / n;
            const double sigma = std::sqrt(fr * (1.0 - fr) / n) + 1e-9;
            std::printf("[dielectric] ior %.2f wo %5.1f deg: F %.4f, reflected fraction %.4f, R + T %.6f, "
                        "mean weight (eta^2 undone) %.6f\n",
                        ior, deg, fr, frac, big_r + big_t, energy / n);
            EXPECT_NEAR(frac, fr, 5.0 * sigma + 1e-4);
            EXPECT_NEAR(energy / n, 1.0, 1e-5);
        }
    }
}

TEST(Dielectric, EvalAndPdfAreZero)
{
    const GcMaterial m = make_material(GC_MAT_DIELECTRIC, grey(1.0f), grey(0.0f), 0.0f, 1.5f);
    const float3 wo = dir_deg(30);
    EXPECT_TRUE(gc_bsdf_is_delta(m));
    EXPECT_EQ(gc_bsdf_eval(m, grey(1.0f), wo, gc_reflect_z(wo)), grey(0.0f));
    EXPECT_EQ(gc_bsdf_pdf(m, grey(1.0f), wo, gc_reflect_z(wo)), 0.0f);
    EXPECT_FALSE(gc_bsdf_is_delta(make_material(GC_MAT_MIRROR, grey(0.5f), grey(0.5f))));
}

}  // namespace
}  // namespace gc::dev
