// Metrics on constructed images whose values are known by hand.
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "host/image/compare.h"
#include "host/util/error.h"

namespace gc {
namespace {

Film solid(uint32_t w, uint32_t h, float v)
{
    Film f(w, h);
    f.fill({v, v, v, 1});
    return f;
}

TEST(Compare, IdenticalImagesAreZero)
{
    const Film a = solid(8, 8, 0.3f);
    const ImageDifference d = compare_images(a, a);
    EXPECT_EQ(d.pixels, 64u);
    EXPECT_EQ(d.rmse, 0.0);
    EXPECT_EQ(d.rel_mse, 0.0);
    EXPECT_EQ(d.max_abs, 0.0);
    EXPECT_EQ(d.max_rel, 0.0);
    EXPECT_EQ(d.within_tolerance, 1.0);
    EXPECT_EQ(d.identical, 1.0);
    EXPECT_EQ(d.mean_rel_diff, 0.0);
    EXPECT_NEAR(d.mean_test, 0.3, 1e-7);
    EXPECT_EQ(d.mean_test, d.mean_ref);
}

TEST(Compare, KnownValues)
{
    // Reference all 1. Test: one pixel of four is 1.5 in R only, the others equal.
    const Film ref = solid(2, 2, 1.0f);
    Film test = ref;
    test.set(1, 0, {1.5f, 1.0f, 1.0f, 0.0f});  // alpha differs too: ignored
    const ImageDifference d = compare_images(test, ref);
    // 12 channels, one with diff 0.5: MSE = 0.25/12, relMSE = 0.25/(1.01)/12.
    std::printf("rmse %.9f (want %.9f)  rel_mse %.9f (want %.9f)\n", d.rmse, std::sqrt(0.25 / 12), d.rel_mse,
                0.25 / 1.01 / 12);
    EXPECT_NEAR(d.rmse, std::sqrt(0.25 / 12), 1e-12);
    EXPECT_NEAR(d.rel_mse, 0.25 / 1.01 / 12, 1e-12);
    EXPECT_DOUBLE_EQ(d.max_abs, 0.5);
    EXPECT_DOUBLE_EQ(d.max_rel, 0.5 / 1.5);
    EXPECT_DOUBLE_EQ(d.within_tolerance, 0.75);
    EXPECT_DOUBLE_EQ(d.identical, 0.75);
    EXPECT_DOUBLE_EQ(d.mean_test, 12.5 / 12);
    EXPECT_DOUBLE_EQ(d.mean_ref, 1.0);
    EXPECT_DOUBLE_EQ(d.mean_rel_diff, 0.5 / 4);  // red: sums 4.5 vs 4
}

TEST(Compare, RelativeMseWeighsDarkPixelsMore)
{
    // The same absolute error of 0.1 counts 0.01/(0^2+0.01) = 1 on black, 0.01/1.01 on white.
    EXPECT_NEAR(compare_images(solid(1, 1, 0.1f), solid(1, 1, 0.0f)).rel_mse, 1.0, 1e-6);
    EXPECT_NEAR(compare_images(solid(1, 1, 1.1f), solid(1, 1, 1.0f)).rel_mse, 0.01 / 1.01, 1e-6);
}

TEST(Compare, ReferenceToleranceIsRelativePlusAbsolute)
{
    // |t - r| <= 0.01 |r| + 1e-3: at r = 10, 0.1009 passes and 0.102 fails; at r = 0, 9e-4 passes.
    EXPECT_EQ(compare_images(solid(1, 1, 10.1009f), solid(1, 1, 10.0f)).within_tolerance, 1.0);
    EXPECT_EQ(compare_images(solid(1, 1, 10.102f), solid(1, 1, 10.0f)).within_tolerance, 0.0);
    EXPECT_EQ(compare_images(solid(1, 1, 9e-4f), solid(1, 1, 0.0f)).within_tolerance, 1.0);
    EXPECT_EQ(compare_images(solid(1, 1, 2e-3f), solid(1, 1, 0.0f)).within_tolerance, 0.0);
}

TEST(Compare, SymmetricToleranceIsRelativeToTheLargerValue)
{
    const PixelTolerance tol = AgreementLimits{}.pixel;  // 1e-3 relative, 1e-6 absolute
    Film a(2, 1), b(2, 1);
    // Pixel 0: off by 0.9e-3 relative to the larger value: within. Pixel 1: 1.1e-3: outside.
    a.set(0, 0, Rgba{1.0f, 1.0f, 1.0f, 1.0f});
    b.set(0, 0, Rgba{1.0f, 1.0f, 0.9991f, 1.0f});
    a.set(1, 0, Rgba{1.0f, 1.0f, 1.0f, 1.0f});
    b.set(1, 0, Rgba{1.0f, 0.9989f, 1.0f, 1.0f});
    EXPECT_EQ(compare_images(a, b, tol).within_tolerance, 0.5);
    EXPECT_EQ(compare_images(b, a, tol).within_tolerance, 0.5);
}

TEST(Compare, SymmetricToleranceHasAnAbsoluteFloorForBlack)
{
    const PixelTolerance tol = AgreementLimits{}.pixel;
    Film test = solid(2, 2, 0.0f);
    test.set(0, 0, Rgba{5e-7f, 0.0f, 0.0f, 1.0f});  // below the 1e-6 floor
    test.set(1, 0, Rgba{2e-6f, 0.0f, 0.0f, 1.0f});  // above it
    const ImageDifference d = compare_images(test, solid(2, 2, 0.0f), tol);
    EXPECT_EQ(d.within_tolerance, 0.75);
    EXPECT_EQ(d.identical, 0.5);  // within is not the same bits
}

TEST(Compare, NonFinitePixelsAreCountedNotAveraged)
{
    Film test = solid(2, 1, 1.0f);
    test.set(0, 0, {std::numeric_limits<float>::quiet_NaN(), 1, 1, 1});
    const ImageDifference d = compare_images(test, solid(2, 1, 1.0f));
    EXPECT_EQ(d.nonfinite, 1u);
    EXPECT_EQ(d.pixels, 1u);
    EXPECT_EQ(d.rmse, 0.0);
    EXPECT_EQ(d.rel_mse, 0.0);
    EXPECT_EQ(d.mean_test, 1.0);
    // ... but a NaN pixel is neither within tolerance nor identical.
    EXPECT_EQ(d.within_tolerance, 0.5);
    EXPECT_EQ(d.identical, 0.5);
}

// A smooth, non-black image.
Film gradient(uint32_t w, uint32_t h)
{
    Film f(w, h);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            f.set(x, y, Rgba{0.1f + 0.8f * float(x) / float(w), 0.5f, 0.2f + 0.3f * float(y) / float(h), 1.0f});
    return f;
}

AgreementVerdict judge(const Film& test, const Film& ref, const AgreementLimits& limits = {})
{
    return judge_agreement(compare_images(test, ref, limits.pixel), limits);
}

TEST(Agreement, IdenticalImagesPass)
{
    const AgreementVerdict v = judge(gradient(32, 32), gradient(32, 32));
    EXPECT_TRUE(v.passed()) << v.why;
    EXPECT_TRUE(v.finite && v.lit && v.rel_mse_ok && v.within_ok);
}

// One decorrelated path in a 64-spp pixel: the pixel moves by sample / 64, far outside 1e-3
// relative, but the image's relative MSE stays small. The two limits judge the two effects.
TEST(Agreement, RareOutlierPixelsAreJudgedByFractionAndRelMse)
{
    const Film a = gradient(100, 100);
    Film b = a;
    Rgba c = b.at(7, 7);
    c.g += 1.0f / 64.0f;
    b.set(7, 7, c);
    const ImageDifference one = compare_images(b, a, AgreementLimits{}.pixel);
    std::printf("one outlier of 10000: within %.4f%% rel_mse %.3g max_abs %.3g\n", 100 * one.within_tolerance,
                one.rel_mse, one.max_abs);
    EXPECT_DOUBLE_EQ(one.within_tolerance, 0.9999);
    EXPECT_LT(one.rel_mse, 1e-5);
    EXPECT_TRUE(judge_agreement(one, {}).passed()) << judge_agreement(one, {}).why;

    // 20 such pixels more (0.2 %): the fraction limit (99.9 %) fails.
    for (uint32_t i = 0; i < 20; ++i) {
        Rgba d = b.at(i, 50);
        d.r += 1.0f / 64.0f;
        b.set(i, 50, d);
    }
    const AgreementVerdict many = judge(b, a);
    std::printf("21 outliers -> %s\n", many.why.c_str());
    EXPECT_FALSE(many.within_ok);
    EXPECT_EQ(many.why, "only 99.790 % of pixels within tolerance (< 99.900 %)");
}

TEST(Agreement, LargeRelMseFails)
{
    const Film a = gradient(16, 16);
    Film b = a;
    for (float& v : b.data()) v *= 1.01f;  // 1 % everywhere: rel MSE about 2e-5 .. 1e-4
    const AgreementVerdict v = judge(b, a, AgreementLimits{1e-5, 0.0});
    std::printf("1%% brighter -> %s\n", v.why.c_str());
    EXPECT_FALSE(v.rel_mse_ok);
    EXPECT_EQ(v.why.rfind("rel MSE ", 0), 0u);
    EXPECT_NE(v.why.find(" > 1e-05"), std::string::npos);
}

TEST(Agreement, BlackImagesProveNothing)
{
    const Film black(8, 8);
    const AgreementVerdict both = judge(black, black);
    EXPECT_FALSE(both.lit);
    EXPECT_EQ(both.why, "both images are black (the comparison proves nothing)");
    // One black image fails too, even where the other is too dark to leave the tolerance.
    const AgreementVerdict one = judge(solid(8, 8, 5e-7f), black);
    EXPECT_TRUE(one.within_ok);
    EXPECT_FALSE(one.passed());
    EXPECT_EQ(one.why, "one image is black (the comparison proves nothing)");
}

TEST(Agreement, NonFinitePixelsFailFirst)
{
    const Film a = gradient(8, 8);
    Film b = a;
    b.set(3, 3, Rgba{std::numeric_limits<float>::quiet_NaN(), 0, 0, 1});
    const AgreementVerdict v = judge(b, a);
    EXPECT_FALSE(v.finite);
    EXPECT_TRUE(v.rel_mse_ok);  // over the other pixels, which agree
    EXPECT_EQ(v.why, "1 pixels with NaN/Inf");
}

TEST(Compare, SizeMismatchIsInputError)
{
    EXPECT_THROW(compare_images(solid(2, 2, 0), solid(2, 3, 0)), InputError);
    EXPECT_THROW(z_test(solid(2, 2, 0), 4, solid(2, 2, 0), solid(3, 2, 0)), InputError);
    EXPECT_THROW(difference_heatmap(solid(1, 2, 0), solid(2, 2, 0)), InputError);
}

// A Monte Carlo "render": each pixel the mean of spp samples of N(mu, sigma^2) (per channel).
Film noisy_mean(uint32_t w, uint32_t h, float mu, float sigma, uint32_t spp, uint32_t seed)
{
    std::mt19937 rng(seed);
    std::normal_distribution<float> n(mu, sigma / std::sqrt(float(spp)));
    Film f(w, h);
    for (size_t i = 0; i < f.pixel_count(); ++i)
        for (int c = 0; c < 3; ++c) f.data()[i * 4 + c] = n(rng);
    return f;
}

TEST(ZTest, IdenticalPasses)
{
    const Film ref = solid(16, 16, 0.5f);
    const Film var = solid(16, 16, 0.04f);
    const ZTestResult r = z_test(ref, 64, ref, var);
    EXPECT_EQ(r.tested, 256u);
    EXPECT_EQ(r.pass_fraction, 1.0);
    EXPECT_EQ(r.min_p_value, 1.0);
    // Sidak over 768 tests at alpha 0.01: 1 - 0.99^(1/768).
    EXPECT_NEAR(r.alpha_sidak, 1 - std::pow(0.99, 1.0 / 768), 1e-15);
}

TEST(ZTest, UnbiasedNoisePassesShiftedFails)
{
    const uint32_t spp = 64;
    const float sigma = 0.2f;  // per-sample standard deviation
    const Film ref = solid(64, 64, 0.5f);
    const Film var = solid(64, 64, sigma * sigma);
    const ZTestResult good = z_test(noisy_mean(64, 64, 0.5f, sigma, spp, 1), spp, ref, var);
    // A bias of 6 standard errors: each channel's z is ~N(6, 1), past the corrected
    // threshold (~4.9 for 3 x 4096 tests) in most channels.
    const float se = sigma / std::sqrt(float(spp));
    const ZTestResult bad = z_test(noisy_mean(64, 64, 0.5f + 6 * se, sigma, spp, 2), spp, ref, var);
    std::printf("unbiased: %.4f pass (min p %.3g, alpha_sidak %.3g); biased by 6 s.e.: %.4f pass\n",
                good.pass_fraction, good.min_p_value, good.alpha_sidak, bad.pass_fraction);
    EXPECT_GE(good.pass_fraction, 0.9975);  // Mitsuba's acceptance level
    EXPECT_LT(bad.pass_fraction, 0.9);
}

TEST(ZTest, NonFiniteMeanFails)
{
    Film mean = solid(2, 2, 0.5f);
    mean.set(0, 0, {INFINITY, 0.5f, 0.5f, 1});
    const ZTestResult r = z_test(mean, 16, solid(2, 2, 0.5f), solid(2, 2, 0.01f));
    EXPECT_EQ(r.passed, 3u);
    EXPECT_EQ(r.tested, 4u);
}

TEST(Heatmap, LargestDifferenceIsWhiteEqualIsBlack)
{
    const Film a = solid(3, 1, 0.0f);
    Film b = a;
    b.set(1, 0, {0.5f, 0.5f, 0.5f, 1});  // half the largest: t = 0.5 -> (1, 0.5, 0)
    b.set(2, 0, {1.0f, 1.0f, 1.0f, 1});
    const Film h = difference_heatmap(a, b);
    EXPECT_EQ(h.at(0, 0), (Rgba{0, 0, 0, 1}));
    EXPECT_EQ(h.at(1, 0), (Rgba{1, 0.5f, 0, 1}));
    EXPECT_EQ(h.at(2, 0), (Rgba{1, 1, 1, 1}));
    // A fixed scale saturates.
    EXPECT_EQ(difference_heatmap(a, b, 10.0f).at(1, 0), (Rgba{1, 1, 1, 1}));
    b.set(0, 0, {NAN, 0, 0, 1});
    EXPECT_EQ(difference_heatmap(a, b).at(0, 0), (Rgba{1, 0, 1, 1}));
}

}  // namespace
}  // namespace gc
