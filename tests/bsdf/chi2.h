// Test helpers for tests/bsdf: a deterministic uniform generator, quadrature over the sphere
// and Pearson's chi-square goodness-of-fit test of a direction sampler against its pdf, as
// pbrt-v3's and Mitsuba's BSDF tests do it (bins in (theta, phi), expected counts from the
// pdf integrated per bin, sparse bins pooled).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gc::test {

inline constexpr double kPi = std::numbers::pi;

// Significance of the whole binary's chi-square tests. Each test is run at the Šidák level
// 1 - (1 - alpha)^(1/m) so that, with all samplers correct, the chance of any false alarm is
// alpha. kChi2TestCount = m, the number of chi2 tests the binary runs: 7 in
// sampling_test.cpp (disk, cosine, sphere, triangle, 3 Phong lobes) + 9 in bsdf_test.cpp
// (one per non_delta_cases() entry) + 8 in pbr_test.cpp (one per pbr_cases() entry) + 7 in
// pbr_layers_test.cpp + 6 in pbr_transmission_test.cpp (one per case each).
// Update it when adding tests.
inline constexpr double kChi2Alpha = 0.01;
inline constexpr int kChi2TestCount = 37;

// Uniform floats in [0,1) with 24 random bits (never 1.0f, unlike some
// uniform_real_distribution<float> implementations).
class Uniform {
public:
    explicit Uniform(std::uint32_t seed) : m_rng(seed) {}
    float next() { return static_cast<float>(m_rng() >> 8) * (1.0f / 16777216.0f); }

private:
    std::mt19937 m_rng;
};

inline glm::vec3 spherical(double theta, double phi)
{
    return {static_cast<float>(std::sin(theta) * std::cos(phi)),
            static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta))};
}

// Midpoint rule over the sphere in (theta, phi) with the sin(theta) Jacobian: fine enough in
// theta for Phong lobes up to exponent ~1000.
inline double integrate_sphere(const std::function<double(glm::vec3)>& pdf, int n_theta = 1024, int n_phi = 1024)
{
    const double dt = kPi / n_theta;
    const double dp = 2.0 * kPi / n_phi;
    double sum = 0.0;
    for (int i = 0; i < n_theta; ++i) {
        const double theta = (i + 0.5) * dt;
        double ring = 0.0;
        for (int j = 0; j < n_phi; ++j) ring += pdf(spherical(theta, (j + 0.5) * dp));
        sum += ring * std::sin(theta);
    }
    return sum * dt * dp;
}

// Regularised upper incomplete gamma Q(a, x): power series below a + 1, modified Lentz
// continued fraction above (the standard split; see e.g. Press et al., Numerical Recipes,
// sec. 6.2).
inline double gamma_q(double a, double x)
{
    if (x <= 0.0) return 1.0;
    const double log_prefix = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a;
        double sum = term;
        for (int n = 1; n < 100000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
        }
        return 1.0 - sum * std::exp(log_prefix);
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a;
    double c = 1.0 / tiny;
    double d = 1.0 / b;
    double h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::fabs(delta - 1.0) < 1e-15) break;
    }
    return std::exp(log_prefix) * h;
}

struct Chi2Result {
    double statistic = 0.0;
    int dof = 0;
    double p_value = 0.0;
    double threshold = 0.0; // Šidák-corrected per-test significance level
};

// Pearson's chi-square statistic of observed against expected bin counts and its p-value.
// Bins expecting < 5 are pooled into one bin; if the pool still expects < 5 it is dropped,
// unless it received clearly more samples than it should (then the test fails outright:
// the sampler produces what the density says it cannot).
inline Chi2Result chi2_test(const std::string& name, const std::vector<double>& observed,
                            const std::vector<double>& expected)
{
    Chi2Result r;
    double pooled_obs = 0.0;
    double pooled_exp = 0.0;
    int bins = 0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooled_obs += observed[i];
            pooled_exp += expected[i];
            continue;
        }
        const double d = observed[i] - expected[i];
        r.statistic += d * d / expected[i];
        ++bins;
    }
    if (pooled_exp >= 5.0) {
        const double d = pooled_obs - pooled_exp;
        r.statistic += d * d / pooled_exp;
        ++bins;
    } else if (pooled_obs > 20.0) {
        r.statistic = std::numeric_limits<double>::infinity();
    }
    r.dof = bins - 1;
    r.p_value = r.dof > 0 ? gamma_q(0.5 * r.dof, 0.5 * r.statistic) : 1.0;
    r.threshold = 1.0 - std::pow(1.0 - kChi2Alpha, 1.0 / kChi2TestCount);
    std::printf("[chi2] %-44s chi2 = %10.2f  dof = %4d  p = %.4f  (reject below %.2e)\n", name.c_str(), r.statistic,
                r.dof, r.p_value, r.threshold);
    return r;
}

// Chi-square test of `sample` (nullopt = no sample, e.g. a delta lobe or a lost
// Phong sample) against `pdf` over the sphere. Bins: n_theta x n_phi cells uniform in
// (theta, phi), plus one "elsewhere" bin whose expected count is what the pdf leaves out
// (N (1 - integral)); pooling as in chi2_test.
inline Chi2Result chi2_sphere(const std::string& name, const std::function<std::optional<glm::vec3>(Uniform&)>& sample,
                           const std::function<double(glm::vec3)>& pdf, int n_samples = 1000000, int n_theta = 20,
                           int n_phi = 40, std::uint32_t seed = 7)
{
    const int cells = n_theta * n_phi;
    std::vector<double> observed(cells + 1, 0.0);
    Uniform u(seed);
    for (int k = 0; k < n_samples; ++k) {
        const std::optional<glm::vec3> w = sample(u);
        if (!w) {
            observed[cells] += 1.0;
            continue;
        }
        const double theta = std::acos(std::clamp(static_cast<double>(w->z), -1.0, 1.0));
        double phi = std::atan2(static_cast<double>(w->y), static_cast<double>(w->x));
        if (phi < 0.0) phi += 2.0 * kPi;
        const int it = std::min(n_theta - 1, static_cast<int>(theta / kPi * n_theta));
        const int ip = std::min(n_phi - 1, static_cast<int>(phi / (2.0 * kPi) * n_phi));
        observed[it * n_phi + ip] += 1.0;
    }

    // Expected counts: midpoint rule with sub x sub points per cell.
    const int sub = 32;
    std::vector<double> expected(cells + 1, 0.0);
    const double dt = kPi / (n_theta * sub);
    const double dp = 2.0 * kPi / (n_phi * sub);
    double total = 0.0;
    for (int it = 0; it < n_theta; ++it)
        for (int ip = 0; ip < n_phi; ++ip) {
            double integral = 0.0;
            for (int a = 0; a < sub; ++a) {
                const double theta = (it * sub + a + 0.5) * dt;
                double ring = 0.0;
                for (int b = 0; b < sub; ++b) ring += pdf(spherical(theta, (ip * sub + b + 0.5) * dp));
                integral += ring * std::sin(theta);
            }
            expected[it * n_phi + ip] = integral * dt * dp * n_samples;
            total += expected[it * n_phi + ip];
        }
    expected[cells] = std::max(0.0, n_samples - total);

    return chi2_test(name, observed, expected);
}

}  // namespace gc::test
