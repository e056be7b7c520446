// gc_pow.h: the kernels' own log2, exp2 and pow against double precision, over dense grids
// of the ranges the Phong lobe uses (cosines in (0, 1], exponents up to 10^4) and beyond.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "gc_pow.h"

namespace gc::dev {
namespace {

// |got - want| relative to want.
double rel(float got, double want) { return std::fabs(static_cast<double>(got) - want) / std::fabs(want); }

TEST(Pow, Log2AcrossTheFloatRange)
{
    double worst = 0.0;  // relative, or absolute below 1: log2 crosses zero at x = 1
    int points = 0;
    // Every 509th float from the smallest denormal to the largest finite value.
    for (std::uint32_t bits = 1; bits < 0x7f800000u; bits += 509u, ++points) {
        const float x = std::bit_cast<float>(bits);
        const double want = std::log2(static_cast<double>(x));
        worst = std::fmax(worst, std::fabs(static_cast<double>(gc_log2(x)) - want) / std::fmax(1.0, std::fabs(want)));
    }
    std::printf("[pow] log2 over every 509th positive float, %d points: error <= %.3g relative (or absolute below 1) (limit 3e-7)\n",
                points, worst);
    EXPECT_LE(worst, 3e-7);
    EXPECT_EQ(gc_log2(1.0f), 0.0f);
    EXPECT_EQ(gc_log2(8.0f), 3.0f);
    EXPECT_TRUE(std::isinf(gc_log2(0.0f)) && gc_log2(0.0f) < 0.0f);
}

TEST(Pow, Exp2AcrossTheFloatRange)
{
    double worst = 0.0;
    int points = 0;
    for (int i = -126 * 4096; i < 128 * 4096; ++i, ++points) {
        const float y = static_cast<float>(i) / 4096.0f;
        worst = std::fmax(worst, rel(gc_exp2(y), std::exp2(static_cast<double>(y))));
    }
    std::printf("[pow] exp2 on a grid of step 1/4096 over [-126, 128), %d points: relative error <= %.3g (limit 3e-7)\n", points, worst);
    EXPECT_LE(worst, 3e-7);
    EXPECT_EQ(gc_exp2(0.0f), 1.0f);
    EXPECT_EQ(gc_exp2(10.0f), 1024.0f);
    EXPECT_EQ(gc_exp2(-149.0f), std::ldexp(1.0f, -149));  // the smallest denormal
    EXPECT_EQ(gc_exp2(-151.0f), 0.0f);
    EXPECT_TRUE(std::isinf(gc_exp2(128.0f)));
    EXPECT_FLOAT_EQ(gc_exp2(127.75f), static_cast<float>(std::exp2(127.75)));
}

// The Phong lobe: cos^n for cosines in (0, 1] and exponents 1 .. 10^4, where the result is a
// normal float. The error grows with |n log2 c| (an absolute error of log2 becomes a relative
// one of the power), so the limit is relative to that product.
TEST(Pow, PhongLobeValues)
{
    double worst = 0.0;
    int points = 0;
    for (float n = 1.0f; n <= 1.0e4f; n *= 1.37f) {
        for (float c = 1.0f; c > 1.0e-6f; c *= 0.9993f) {
            const double want = std::pow(static_cast<double>(c), static_cast<double>(n));
            if (want < 1e-37) break;
            const double scale = std::fmax(1.0, std::fabs(static_cast<double>(n) * std::log2(static_cast<double>(c))));
            worst = std::fmax(worst, rel(gc_pow(c, n), want) / scale);
            ++points;
        }
    }
    std::printf("[pow] c^n, c in (0, 1], n in [1, 1e4], %d points: relative error <= %.3g * max(1, |n log2 c|) (limit 4e-7)\n",
                points, worst);
    EXPECT_LE(worst, 4e-7);
    EXPECT_EQ(gc_pow(0.0f, 3.0f), 0.0f);
    EXPECT_EQ(gc_pow(0.0f, 0.0f), 1.0f);
    EXPECT_EQ(gc_pow(1.0f, 1000.0f), 1.0f);
}

}  // namespace
}  // namespace gc::dev
