// How far two renders are apart, and whether they agree: the one home of the image metrics
// used by tests, tools/imgdiff, the consistency check (host/app) and the OpenCL/Vulkan
// cross-check (host/vk).
// All metrics use R, G and B only (alpha is ignored) and need equal sizes (else InputError).
// `test` is the image under test, `ref` the reference; the relative metrics divide by ref.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "host/image/film.h"

namespace gc {

// When a pixel is within tolerance: each of its R, G and B passes `rule`.
struct PixelTolerance {
    enum class Rule {
        // |test - ref| <= rel * |ref| + abs (numpy.isclose's form): relative where the
        // reference is bright, absolute near black. For renders against a converged reference.
        reference,
        // |test - ref| <= rel * max(|test|, |ref|)  or  |test - ref| <= abs: symmetric, for two
        // devices where neither is the reference; abs only matters for (near-)black pixels.
        symmetric,
    };
    Rule rule = Rule::reference;
    double rel = 0.01;
    double abs = 1e-3;
};

struct ImageDifference {
    size_t pixels = 0;     // pixels compared: finite RGB in both images
    size_t nonfinite = 0;  // pixels skipped because either image has a NaN/Inf in RGB
    double rmse = 0;       // sqrt(mean over compared channels of (test - ref)^2)
    // Mean over compared channels of (test - ref)^2 / (ref^2 + 1e-2): relative MSE as in the
    // denoising literature (Rousselle et al. 2011) and the reference images' README, the 1e-2
    // keeping black pixels from dominating.
    double rel_mse = 0;
    double max_abs = 0;    // largest |test - ref| over compared channels
    double max_rel = 0;    // largest |test - ref| / max(|test|, |ref|) over compared channels
    // Fractions of all pixels (a non-finite pixel is never within, nor identical):
    double within_tolerance = 0;  // pixels within the PixelTolerance
    double identical = 0;         // pixels whose RGB are the same bits in both images
    double mean_test = 0;  // mean RGB value over compared pixels
    double mean_ref = 0;
    // Largest over R, G, B of |mean(test) - mean(ref)| / |mean(ref)| (a global bias, which
    // per-pixel metrics at a modest spp cannot see); 0 where both means are 0.
    double mean_rel_diff = 0;
};

ImageDifference compare_images(const Film& test, const Film& ref, const PixelTolerance& tol = {});

// The limits two renders of the same scene on different devices or APIs must meet.
//
// Why two figures and no limit on max_abs: devices differ in the last ulps of sin, cos, pow
// and exp (OpenCL C allows 4 to 16 ulp). Most paths only move by those ulps, but now and then
// a perturbed path takes another branch (Russian roulette's threshold, the other side of an
// edge, another lobe) and from then on is an unrelated sample. Such a pixel's mean moves by
// (sample difference) / spp, far beyond 1e-3 relative, while the image's relative MSE stays
// tiny. So `min_within` bounds how many such pixels there are and `max_rel_mse` their weight.
struct AgreementLimits {
    double max_rel_mse = 1e-5;   // issue 5: NVIDIA vs PoCL, Cornell box, 64 spp
    double min_within = 0.999;   // fraction of pixels within `pixel`
    PixelTolerance pixel{PixelTolerance::Rule::symmetric, 1e-3, 1e-6};
};

// The verdict on an ImageDifference made with limits.pixel. Images agree when they have no
// NaN/Inf, neither is black (a black comparison proves nothing), rel_mse <= max_rel_mse and
// within_tolerance >= min_within.
struct AgreementVerdict {
    bool finite = false;   // no pixel with a NaN/Inf
    bool lit = false;      // neither image is black
    bool rel_mse_ok = false;
    bool within_ok = false;
    std::string why;  // empty when the images agree; else the first rule broken, in the order above
    bool passed() const { return why.empty(); }
};

AgreementVerdict judge_agreement(const ImageDifference& d, const AgreementLimits& limits);

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
