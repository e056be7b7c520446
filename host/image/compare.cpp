#include "host/image/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "host/util/error.h"

namespace gc {
namespace {

void require_same_size(const Film& a, const Film& b, const char* what)
{
    if (a.width() != b.width() || a.height() != b.height())
        throw InputError(std::string(what) + ": images differ in size (" + std::to_string(a.width()) + "x" +
                         std::to_string(a.height()) + " vs " + std::to_string(b.width()) + "x" +
                         std::to_string(b.height()) + ")");
    if (a.empty()) throw InputError(std::string(what) + ": the images are empty");
}

bool finite_rgb(const float* p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

bool within(double test, double ref, const PixelTolerance& tol)
{
    const double diff = std::fabs(test - ref);
    if (tol.rule == PixelTolerance::Rule::reference) return diff <= tol.rel * std::fabs(ref) + tol.abs;
    return diff <= tol.rel * std::max(std::fabs(test), std::fabs(ref)) || diff <= tol.abs;
}

std::string format(const char* fmt, double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, fmt, value);
    return buffer;
}

std::string percent(double fraction) { return format("%.3f %%", 100.0 * fraction); }

}  // namespace

ImageDifference compare_images(const Film& test, const Film& ref, const PixelTolerance& tol)
{
    require_same_size(test, ref, "image comparison");
    ImageDifference d;
    double sq = 0, rel = 0, total_test = 0, total_ref = 0;
    double sum_test[3] = {0, 0, 0}, sum_ref[3] = {0, 0, 0};
    size_t within_count = 0, identical_count = 0;
    for (size_t i = 0; i < test.pixel_count(); ++i) {
        const float* a = test.data().data() + i * 4;
        const float* b = ref.data().data() + i * 4;
        if (!finite_rgb(a) || !finite_rgb(b)) {
            ++d.nonfinite;
            continue;
        }
        bool ok = true;
        for (int c = 0; c < 3; ++c) {
            const double diff = double(a[c]) - double(b[c]);
            const double ad = std::fabs(diff);
            sq += diff * diff;
            rel += diff * diff / (double(b[c]) * b[c] + 1e-2);
            d.max_abs = std::max(d.max_abs, ad);
            const double scale = std::max(std::fabs(double(a[c])), std::fabs(double(b[c])));
            if (scale > 0) d.max_rel = std::max(d.max_rel, ad / scale);
            ok = ok && within(a[c], b[c], tol);
            sum_test[c] += a[c];
            sum_ref[c] += b[c];
            total_test += a[c];
            total_ref += b[c];
        }
        within_count += ok;
        identical_count += std::memcmp(a, b, 3 * sizeof(float)) == 0;
        ++d.pixels;
    }
    const double all = double(test.pixel_count());
    d.within_tolerance = double(within_count) / all;
    d.identical = double(identical_count) / all;
    if (d.pixels > 0) {
        const double n = 3.0 * double(d.pixels);
        d.rmse = std::sqrt(sq / n);
        d.rel_mse = rel / n;
        d.mean_test = total_test / n;
        d.mean_ref = total_ref / n;
        for (int c = 0; c < 3; ++c) {
            const double bias = std::fabs(sum_test[c] - sum_ref[c]);
            if (bias > 0) d.mean_rel_diff = std::max(d.mean_rel_diff, bias / std::fabs(sum_ref[c]));
        }
    }
    return d;
}

AgreementVerdict judge_agreement(const ImageDifference& d, const AgreementLimits& limits)
{
    AgreementVerdict v;
    v.finite = d.nonfinite == 0;
    const bool test_black = d.mean_test == 0.0, ref_black = d.mean_ref == 0.0;
    v.lit = !test_black && !ref_black;
    v.rel_mse_ok = d.rel_mse <= limits.max_rel_mse;
    v.within_ok = d.within_tolerance >= limits.min_within;
    if (!v.finite) v.why = std::to_string(d.nonfinite) + " pixels with NaN/Inf";
    else if (test_black && ref_black) v.why = "both images are black (the comparison proves nothing)";
    else if (!v.lit) v.why = "one image is black (the comparison proves nothing)";
    else if (!v.rel_mse_ok)
        v.why = "rel MSE " + format("%.3g", d.rel_mse) + " > " + format("%.3g", limits.max_rel_mse);
    else if (!v.within_ok)
        v.why = "only " + percent(d.within_tolerance) + " of pixels within tolerance (< " +
                percent(limits.min_within) + ")";
    return v;
}

ZTestResult z_test(const Film& mean, uint32_t spp, const Film& ref, const Film& ref_variance, double alpha,
                   double variance_floor)
{
    require_same_size(mean, ref, "Z-test (mean vs reference)");
    require_same_size(mean, ref_variance, "Z-test (mean vs variance)");
    if (spp == 0) throw InputError("Z-test: the sample count is 0");
    if (!(alpha > 0 && alpha < 1)) throw InputError("Z-test: alpha must be in (0, 1), got " + std::to_string(alpha));

    ZTestResult r;
    for (size_t i = 0; i < mean.pixel_count(); ++i)
        r.tested += finite_rgb(ref.data().data() + i * 4) && finite_rgb(ref_variance.data().data() + i * 4);
    if (r.tested == 0) {
        r.pass_fraction = 1;
        return r;
    }
    // 1 - (1 - alpha)^(1/N), written with log1p/expm1 so that it stays accurate for large N.
    r.alpha_sidak = -std::expm1(std::log1p(-alpha) / (3.0 * double(r.tested)));

    for (size_t i = 0; i < mean.pixel_count(); ++i) {
        const float* m = mean.data().data() + i * 4;
        const float* f = ref.data().data() + i * 4;
        const float* v = ref_variance.data().data() + i * 4;
        if (!finite_rgb(f) || !finite_rgb(v)) continue;
        bool pass = finite_rgb(m);
        for (int c = 0; c < 3 && pass; ++c) {
            const double z = std::fabs(double(m[c]) - f[c]) * std::sqrt(double(spp) / std::max(double(v[c]), variance_floor));
            const double p = std::erfc(z / std::sqrt(2.0));
            r.max_z = std::max(r.max_z, z);
            r.min_p_value = std::min(r.min_p_value, p);
            pass = p > r.alpha_sidak;
        }
        if (!finite_rgb(m)) r.min_p_value = 0;
        r.passed += pass;
    }
    r.pass_fraction = double(r.passed) / double(r.tested);
    return r;
}

Film difference_heatmap(const Film& a, const Film& b, float scale)
{
    require_same_size(a, b, "difference heat map");
    Film out(a.width(), a.height());
    std::vector<float> e(a.pixel_count(), -1.0f);  // -1 marks non-finite
    float emax = 0;
    for (size_t i = 0; i < a.pixel_count(); ++i) {
        const float* p = a.data().data() + i * 4;
        const float* q = b.data().data() + i * 4;
        if (!finite_rgb(p) || !finite_rgb(q)) continue;
        e[i] = (std::fabs(p[0] - q[0]) + std::fabs(p[1] - q[1]) + std::fabs(p[2] - q[2])) / 3.0f;
        emax = std::max(emax, e[i]);
    }
    const float s = scale > 0 ? scale : (emax > 0 ? 1.0f / emax : 1.0f);
    auto clamp01 = [](float x) { return std::clamp(x, 0.0f, 1.0f); };
    for (size_t i = 0; i < a.pixel_count(); ++i) {
        float* o = out.data().data() + i * 4;
        if (e[i] < 0) {
            o[0] = 1, o[1] = 0, o[2] = 1;
            continue;
        }
        const float t = clamp01(e[i] * s);
        o[0] = clamp01(3 * t);
        o[1] = clamp01(3 * t - 1);
        o[2] = clamp01(3 * t - 2);
    }
    return out;
}

}  // namespace gc
