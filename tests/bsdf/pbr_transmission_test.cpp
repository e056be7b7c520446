// GC_MAT_PBR's rough KHR_materials_transmission lobe (GC_MATF_ROUGH_TRANSMISSION, gc_bsdf.h)
// against gc_bsdf.h's contract: the density over the whole sphere integrates to one less what
// the sampler loses, samples follow it (chi-square), sample() agrees with eval()/pdf() and flags
// refractions, the sampled albedo matches quadrature, energy (a white rough dielectric reflects
// and transmits at most what it receives, once the 1/eta^2 of radiance is undone), generalised
// reciprocity of the btdf (f(wo, wi) / n_i^2 = f(wi, wo) / n_o^2 with the Fresnel mix at 0) and
// the smooth limit at normal incidence ((1 - F0) / ior^2 transmitted).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "gc_bsdf.h"
#include "tests/bsdf/bsdf_albedo.h"
#include "tests/bsdf/chi2.h"
#include "tests/bsdf/pbr_materials.h"

namespace gc::dev {
namespace {

using test::Uniform;
using test_albedo::Albedo;
using test_albedo::albedo_by_quadrature;
using test_albedo::base_of;
using test_albedo::directional_albedo;
using test_albedo::draw;

using test_pbr::coated;
using test_pbr::dir_deg;
using test_pbr::grey;
using test_pbr::sheened;

GcMaterial rough_glass(float3 base, float roughness, float transmission, float ior = 1.5f, float metallic = 0.0f)
{
    GcMaterial m = test_pbr::pbr(base, metallic, roughness, transmission, ior);
    m.flags = GC_MATF_ROUGH_TRANSMISSION;
    return m;
}

struct Case {
    std::string name;
    GcMaterial m;
    float3 wo;
};

// Roughness >= 0.2 for the chi-square (sharper lobes fall between its quadrature points).
std::vector<Case> transmission_cases()
{
    return {
        {"white r.3 trans 1 wo=30", rough_glass(grey(1.0f), 0.3f, 1.0f), dir_deg(30)},
        {"tinted r.5 trans .6 wo=60", rough_glass(make_float3(0.9f, 0.5f, 0.2f), 0.5f, 0.6f), dir_deg(60)},
        {"white r.4 trans 1 inside wo=150", rough_glass(grey(1.0f), 0.4f, 1.0f), dir_deg(150)},
        {"ior 1.33 r.2 inside wo=140", rough_glass(grey(0.8f), 0.2f, 1.0f, 1.33f), dir_deg(140)},
        {"coat .5 r.3 over r.4 trans .8 wo=40", coated(rough_glass(grey(0.9f), 0.4f, 0.8f), 0.5f, 0.3f), dir_deg(40)},
        {"metal .3 r.6 trans 1 wo=75", rough_glass(grey(0.7f), 0.6f, 1.0f, 1.5f, 0.3f), dir_deg(75)},
        {"sheen .8 r.5 over r.4 trans .8 wo=50", sheened(rough_glass(grey(0.9f), 0.4f, 0.8f), grey(0.8f), 0.5f),
         dir_deg(50)},
    };
}

double lost_fraction(const Case& c, int n, double* sigma)
{
    Uniform u(21);
    int failed = 0;
    for (int k = 0; k < n; ++k)
        if (draw(c.m, c.wo, u).flags == 0u) ++failed;
    const double lost = static_cast<double>(failed) / n;
    *sigma = std::sqrt(lost * (1.0 - lost) / n);
    return lost;
}

TEST(PbrTransmission, PdfIntegratesToOneLessLostSamples)
{
    for (const Case& c : transmission_cases()) {
        const double integral = test::integrate_sphere(
            [&](glm::vec3 wi) { return static_cast<double>(gc_bsdf_pdf(c.m, base_of(c.m), c.wo, wi)); }, 2048, 1024);
        double sigma = 0.0;
        const double lost = lost_fraction(c, 200000, &sigma);
        std::printf("[pdf integral] %-36s %.5f  expected %.5f (lost %.5f)\n", c.name.c_str(), integral, 1.0 - lost, lost);
        EXPECT_NEAR(integral, 1.0 - lost, 2e-3 + 5.0 * sigma) << c.name;
    }
}

TEST(PbrTransmission, SamplesFollowPdfChiSquare)
{
    for (const Case& c : transmission_cases()) {
        const test::Chi2Result r = test::chi2_sphere(
            c.name,
            [&](Uniform& u) -> std::optional<glm::vec3> {
                const GcBsdfSample s = draw(c.m, c.wo, u);
                if (s.flags == 0u) return std::nullopt;
                return s.wi;
            },
            [&](glm::vec3 wi) { return static_cast<double>(gc_bsdf_pdf(c.m, base_of(c.m), c.wo, wi)); });
        EXPECT_GT(r.p_value, r.threshold) << c.name;
    }
}

TEST(PbrTransmission, SampleAgreesWithEvalAndPdf)
{
    for (const Case& c : transmission_cases()) {
        Uniform u(31);
        int refracted = 0;
        for (int k = 0; k < 20000; ++k) {
            const GcBsdfSample s = draw(c.m, c.wo, u);
            if (s.flags == 0u) continue;
            ASSERT_TRUE(std::isfinite(s.weight.x) && std::isfinite(s.weight.y) && std::isfinite(s.weight.z)) << c.name;
            ASSERT_EQ(s.flags & GC_BSDF_SPECULAR, 0u) << c.name;
            const bool through = s.wi.z * c.wo.z < 0.0f;
            ASSERT_EQ((s.flags & GC_BSDF_TRANSMISSION) != 0u, through) << c.name;
            refracted += through ? 1 : 0;
            ASSERT_EQ(s.pdf_w, gc_bsdf_pdf(c.m, base_of(c.m), c.wo, s.wi)) << c.name;
            ASSERT_EQ(s.f, gc_bsdf_eval(c.m, base_of(c.m), c.wo, s.wi)) << c.name;
        }
        std::printf("[sample] %-36s %d of 20000 refracted\n", c.name.c_str(), refracted);
        EXPECT_GT(refracted, 0) << c.name;
    }
}

TEST(PbrTransmission, SampledAlbedoMatchesQuadrature)
{
    for (const Case& c : transmission_cases()) {
        const double q = albedo_by_quadrature(c.m, c.wo);
        const Albedo a = directional_albedo(c.m, c.wo, 400000, 9);
        const double s = gc_luminance(a.mean);
        std::printf("[albedo] %-36s quadrature %.4f sampled %.4f (+- %.4f)\n", c.name.c_str(), q, s, a.stderr_);
        EXPECT_NEAR(q, s, 3e-3 + 4.0 * a.stderr_) << c.name;
    }
}

// Reflected plus transmitted energy of a white rough dielectric, the transmitted weights
// multiplied back by eta^2 (the radiance scaling of gc_bsdf.h, which alone may exceed 1 from
// inside): single-scattering GGX with Schlick's F loses energy, never gains it.
TEST(PbrTransmission, WhiteRoughDielectricConservesEnergy)
{
    for (float r : {0.1f, 0.3f, 0.7f, 1.0f}) {
        const GcMaterial m = rough_glass(grey(1.0f), r, 1.0f);
        Uniform dirs(51);
        double hi = -1e9;
        for (int k = 0; k < 16; ++k) {
            const float3 wo = gc_sample_uniform_sphere(dirs.next(), dirs.next());
            const float eta = gc_pbr_transmission_eta(m, gc_bsdf_side(wo));
            Uniform u(100 + k);
            const int n = 20000;
            double sum = 0.0, sum2 = 0.0;
            for (int j = 0; j < n; ++j) {
                const GcBsdfSample s = draw(m, wo, u);
                if (s.flags == 0u) continue;
                const double e = gc_luminance(s.weight) * ((s.flags & GC_BSDF_TRANSMISSION) != 0u ? eta * eta : 1.0f);
                sum += e;
                sum2 += e * e;
            }
            const double mean = sum / n;
            const double se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
            hi = std::max(hi, mean);
            EXPECT_LE(mean, 1.0 + 1e-3 + 4.0 * se) << "roughness " << r << " wo.z " << wo.z;
        }
        std::printf("[energy] white rough dielectric r%.2f: max energy over 16 wo %.4f\n", r, hi);
    }
}

// Seen from inside beyond the critical angle (ior 1.5: 41.8 degrees), nothing refracts out: a
// smooth-ish white dielectric reflects all but GGX's single-scattering loss back inside.
// (Schlick's F at the incident cosine would let 90 % of it go.)
TEST(PbrTransmission, TotalInternalReflectionKeepsTheLightInside)
{
    for (float theta : {130.0f, 120.0f, 100.0f}) {
        const GcMaterial m = rough_glass(grey(1.0f), 0.1f, 1.0f);
        const Albedo a = directional_albedo(m, dir_deg(theta), 200000, 13);
        const double e = gc_luminance(a.mean);
        std::printf("[tir] white r.1 from inside at %.0f deg (%.1f from the normal): albedo %.4f (+- %.4f)\n", theta,
                    180.0f - theta, e, a.stderr_);
        EXPECT_GT(e, 0.9) << theta;
        EXPECT_LE(e, 1.0 + 4.0 * a.stderr_) << theta;
    }
}

// With the Fresnel mix switched off (KHR_materials_specular factor 0: F = 0) the btdf alone
// obeys f(wo, wi) / n(wi side)^2 = f(wi, wo) / n(wo side)^2.
TEST(PbrTransmission, BtdfGeneralisedReciprocity)
{
    GcMaterial m = rough_glass(grey(1.0f), 0.4f, 1.0f);
    m.flags |= GC_MATF_SPECULAR;
    m.coat.w = 0.0f;
    Uniform u(61);
    double worst = 0.0;
    int checked = 0;
    for (int k = 0; k < 2000; ++k) {
        float3 wo = gc_sample_uniform_sphere(u.next(), u.next());
        float3 wi = gc_sample_uniform_sphere(u.next(), u.next());
        if (wo.z * wi.z > 0.0f) wi.z = -wi.z;
        const float f_oi = gc_luminance(gc_bsdf_eval(m, base_of(m), wo, wi));
        const float f_io = gc_luminance(gc_bsdf_eval(m, base_of(m), wi, wo));
        if (!(f_oi > 1e-4f)) continue;
        const float eta = gc_pbr_transmission_eta(m, gc_bsdf_side(wo));  // n(wi side) / n(wo side)
        const double rel = std::fabs(f_io - eta * eta * f_oi) / (eta * eta * f_oi);
        worst = std::max(worst, rel);
        ++checked;
        ASSERT_LT(rel, 1e-3) << "wo.z " << wo.z << " wi.z " << wi.z;
    }
    std::printf("[reciprocity] %d pairs, worst relative error %.2e\n", checked, worst);
    EXPECT_GT(checked, 100);
}

// Near-smooth white glass at normal incidence transmits (1 - F0) / ior^2 of the radiance
// (F0 = 0.04 at ior 1.5): the thin lobe's weight, scaled as a refraction.
TEST(PbrTransmission, SmoothLimitAtNormalIncidence)
{
    const GcMaterial m = rough_glass(grey(1.0f), 0.05f, 1.0f);
    const float3 up = make_float3(0.0f, 0.0f, 1.0f);
    Uniform u(71);
    const int n = 200000;
    double t = 0.0, t2 = 0.0;
    for (int k = 0; k < n; ++k) {
        const GcBsdfSample s = draw(m, up, u);
        const double w = (s.flags & GC_BSDF_TRANSMISSION) != 0u ? gc_luminance(s.weight) : 0.0;
        t += w;
        t2 += w * w;
    }
    const double mean = t / n;
    const double se = std::sqrt(std::max(0.0, t2 / n - mean * mean) / n);
    const double expected = (1.0 - 0.04) / (1.5 * 1.5);
    std::printf("[smooth limit] transmitted %.4f (+- %.4f) expected %.4f\n", mean, se, expected);
    EXPECT_NEAR(mean, expected, 0.01 * expected + 4.0 * se);
}

// At ior 1 the facets bend no light, however rough (Khronos' TransmissionRoughnessTest, row
// "1.0 - Air"): every transmitted sample goes straight through, and none is lost to masking, so
// white glass of roughness 1 seen head-on transmits (1 - F) of what it receives, F being the
// Schlick weight at normal incidence with F0 = 0, i.e. 0.
TEST(PbrTransmission, IorOneStaysSharpAtAnyRoughness)
{
    const GcMaterial m = rough_glass(grey(1.0f), 1.0f, 1.0f, 1.0f);
    const float3 wo = dir_deg(20);
    Uniform u(5);
    const int n = 100000;
    double transmitted = 0.0, worst_cos = 1.0;
    for (int k = 0; k < n; ++k) {
        const GcBsdfSample s = draw(m, wo, u);
        if ((s.flags & GC_BSDF_TRANSMISSION) == 0u) continue;
        transmitted += gc_luminance(s.weight);
        worst_cos = std::min(worst_cos, -static_cast<double>(gc_dot(s.wi, wo)));
    }
    const double mean = transmitted / n;
    const double expected = 1.0 - std::pow(1.0 - std::cos(20.0 * 3.14159265358979 / 180.0), 5.0);
    std::printf("[ior 1] transmitted %.4f (expected %.4f); the widest transmitted direction is %.3f degrees off "
                "straight through\n",
                mean, expected, std::acos(std::min(1.0, worst_cos)) * 180.0 / 3.14159265358979);
    EXPECT_GT(worst_cos, std::cos(1.0 * 3.14159265358979 / 180.0));
    EXPECT_NEAR(mean, expected, 0.01);
}

}  // namespace
}  // namespace gc::dev
