// Metrics on constructed images whose values are known by hand.
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

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
    EXPECT_EQ(d.within_tolerance, 1.0);
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
    EXPECT_DOUBLE_EQ(d.within_tolerance, 0.75);
}

TEST(Compare, RelativeMseWeighsDarkPixelsMore)
{
    // The same absolute error of 0.1 counts 0.01/(0^2+0.01) = 1 on black, 0.01/1.01 on white.
    EXPECT_NEAR(compare_images(solid(1, 1, 0.1f), solid(1, 1, 0.0f)).rel_mse, 1.0, 1e-6);
    EXPECT_NEAR(compare_images(solid(1, 1, 1.1f), solid(1, 1, 1.0f)).rel_mse, 0.01 / 1.01, 1e-6);
}

TEST(Compare, ToleranceIsRelativePlusAbsolute)
{
    // |t - r| <= 0.01 |r| + 1e-3: at r = 10, 0.1009 passes and 0.102 fails; at r = 0, 9e-4 passes.
    EXPECT_EQ(compare_images(solid(1, 1, 10.1009f), solid(1, 1, 10.0f)).within_tolerance, 1.0);
    EXPECT_EQ(compare_images(solid(1, 1, 10.102f), solid(1, 1, 10.0f)).within_tolerance, 0.0);
    EXPECT_EQ(compare_images(solid(1, 1, 9e-4f), solid(1, 1, 0.0f)).within_tolerance, 1.0);
    EXPECT_EQ(compare_images(solid(1, 1, 2e-3f), solid(1, 1, 0.0f)).within_tolerance, 0.0);
}

TEST(Compare, NonFinitePixelsAreCountedNotAveraged)
{
    Film test = solid(2, 1, 1.0f);
    test.set(0, 0, {std::numeric_limits<float>::quiet_NaN(), 1, 1, 1});
    const ImageDifference d = compare_images(test, solid(2, 1, 1.0f));
    EXPECT_EQ(d.nonfinite, 1u);
    EXPECT_EQ(d.pixels, 1u);
    EXPECT_EQ(d.rmse, 0.0);
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
