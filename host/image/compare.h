// Differences between two renders, for tests, tools/imgdiff and cross-device checks.
// All metrics use R, G and B only (alpha is ignored) and need equal sizes (else InputError).
// `test` is the image under test, `ref` the reference; the relative metrics divide by ref.
#pragma once

#include <cstddef>
#include <cstdint>

#include "host/image/film.h"

namespace gc {

struct ImageDifference {
    size_t pixels = 0;     // pixels compared: finite RGB in both images
    size_t nonfinite = 0;  // pixels skipped because either image has a NaN/Inf in RGB
    double rmse = 0;       // sqrt(mean over compared channels of (test - ref)^2)
    double rel_mse = 0;    // mean over compared channels of (test - ref)^2 / (ref^2 + 1e-2)
                           // (the formula of the reference images' README)
    double max_abs = 0;    // largest |test - ref| over compared channels
    // Fraction of compared pixels whose R, G and B all satisfy
    //   |test - ref| <= rel_tol * |ref| + abs_tol
    // (numpy.isclose's form: relative where the reference is bright, absolute near black).
    double within_tolerance = 0;
    // Largest over R, G, B of |mean(test) - mean(ref)| / |mean(ref)| (a global bias, which
    // per-pixel metrics at a modest spp cannot see); 0 where both means are 0.
    double mean_rel_diff = 0;
};

ImageDifference compare_images(const Film& test, const Film& ref, double rel_tol = 0.01, double abs_tol = 1e-3);

// Per-pixel Z-test after Mitsuba 3's render tests: is `mean`, an average of `spp` samples,
// consistent with `ref`, given the per-sample variance `ref_variance` of the estimator?
// For each pixel and channel c in RGB:
//   z = |mean - ref| * sqrt(spp / max(var, variance_floor))
//   p = erfc(z / sqrt 2)                         (two-sided, standard normal)
// With N = 3 x (pixels tested), the per-test level is Šidák-corrected so that the whole image
// has false-alarm probability `alpha`:  alpha_sidak = 1 - (1 - alpha)^(1/N).
// A pixel passes when p > alpha_sidak in all three channels. A non-finite `mean` pixel fails;
// a pixel whose ref or variance is non-finite is not tested.
struct ZTestResult {
    size_t tested = 0;
    size_t passed = 0;
    double pass_fraction = 0;  // passed / tested (1 when nothing was tested)
    double alpha_sidak = 0;
    double min_p_value = 1;
    double max_z = 0;
};

ZTestResult z_test(const Film& mean, uint32_t spp, const Film& ref, const Film& ref_variance, double alpha = 0.01,
                   double variance_floor = 1e-4);

// A picture of where two images differ: e = mean over RGB of |a - b|, t = clamp(e * scale),
// mapped black -> red -> yellow -> white. scale <= 0 picks 1 / max(e) (the largest difference
// is white). Pixels with a NaN/Inf in either image are magenta.
Film difference_heatmap(const Film& a, const Film& b, float scale = 0.0f);

}  // namespace gc
