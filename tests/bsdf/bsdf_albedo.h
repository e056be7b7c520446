// Directional albedo of a GcMaterial two ways, for the PBR tests: as the mean sample weight
// (all lobes, delta ones included) and by quadrature of f |cos| (the non-delta part, whatever
// the sampler does).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "gc_bsdf.h"
#include "tests/bsdf/chi2.h"

namespace gc::dev::test_albedo {

inline float3 base_of(const GcMaterial& m) { return GC_XYZ(m.albedo); }

inline GcBsdfSample draw(const GcMaterial& m, float3 wo, test::Uniform& u)
{
    const float u0 = u.next();
    const float u1 = u.next();
    const float u2 = u.next();
    return gc_bsdf_sample(m, base_of(m), wo, u0, u1, u2);
}

struct Albedo {
    float3 mean;    // per channel
    double stderr_; // of the luminance
};

inline Albedo directional_albedo(const GcMaterial& m, float3 wo, int n, std::uint32_t seed)
{
    test::Uniform u(seed);
    double sum[3] = {0, 0, 0};
    double lum = 0.0;
    double lum2 = 0.0;
    for (int k = 0; k < n; ++k) {
        const GcBsdfSample s = draw(m, wo, u);
        if (s.flags == 0u) continue;
        for (int c = 0; c < 3; ++c) sum[c] += s.weight[c];
        const double l = gc_luminance(s.weight);
        lum += l;
        lum2 += l * l;
    }
    const double mean = lum / n;
    return {make_float3(static_cast<float>(sum[0] / n), static_cast<float>(sum[1] / n), static_cast<float>(sum[2] / n)),
            std::sqrt(std::max(0.0, lum2 / n - mean * mean) / n)};
}

inline double albedo_by_quadrature(const GcMaterial& m, float3 wo)
{
    return test::integrate_sphere(
        [&](glm::vec3 wi) {
            return static_cast<double>(gc_luminance(gc_bsdf_eval(m, base_of(m), wo, wi))) * std::fabs(wi.z);
        },
        2048, 512);
}

}  // namespace gc::dev::test_albedo
