// The low-discrepancy sampler of kernels/shared/gc_rng.h (gc_sobol4, gc_sobol_rand4) on the
// host: the properties that make it worth having (stratification in 1D and of each block's 2D
// point, in every aligned window of sample indices, as chunks and adaptive rounds take them)
// and the ones that keep estimates unbiased (uniform, and decorrelated between pixels, blocks
// and seeds). The devices' bits are checked against these functions in device_kernels_test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <set>
#include <utility>
#include <vector>

#include "gc_rng.h"

namespace gc {
namespace {

constexpr std::uint32_t kLog2Points = 8;
constexpr std::uint32_t kPoints = 1u << kLog2Points;

float component(const dev::float4& v, int c) { return c == 0 ? v.x : c == 1 ? v.y : c == 2 ? v.z : v.w; }

// Whether the points' (a, b) projection has exactly one point in every elementary interval
// [i / 2^k, (i + 1) / 2^k) x [j / 2^(m-k), (j + 1) / 2^(m-k)), k = 0..m: a (0, m, 2)-net.
bool is_02_net(const std::vector<dev::float4>& points, int a, int b)
{
    for (std::uint32_t k = 0; k <= kLog2Points; ++k) {
        std::set<std::pair<std::uint32_t, std::uint32_t>> cells;
        for (const dev::float4& p : points)
            cells.insert({std::uint32_t(component(p, a) * float(1u << k)),
                          std::uint32_t(component(p, b) * float(1u << (kLog2Points - k)))});
        if (cells.size() != points.size()) return false;
    }
    return true;
}

// Whether dimension c of the points puts one point in each of the intervals [i / n, (i + 1) / n).
bool is_stratified(const std::vector<dev::float4>& points, int c)
{
    std::set<std::uint32_t> cells;
    for (const dev::float4& p : points) cells.insert(std::uint32_t(component(p, c) * float(points.size())));
    return cells.size() == points.size();
}

std::vector<dev::float4> window(std::uint32_t pixel, std::uint32_t first_sample, std::uint32_t block, std::uint32_t seed)
{
    std::vector<dev::float4> points;
    for (std::uint32_t s = first_sample; s < first_sample + kPoints; ++s)
        points.push_back(dev::gc_sobol_rand4(pixel, s, block, seed));
    return points;
}

// Sobol's dimensions 0-3 by the recurrence of the direction numbers (Bratley & Fox): v_k =
// a_1 v_{k-1} ^ ... ^ a_{s-1} v_{k-s+1} ^ v_{k-s} ^ (v_{k-s} >> s), v_k = m_k / 2^(k+1) for
// the first s. What gc_sobol4_reversed's constants must give.
dev::uint4 sobol_by_recurrence(std::uint32_t index)
{
    struct Polynomial {
        int s;
        std::vector<int> a;  // a_1 .. a_{s-1}
        std::vector<std::uint32_t> m;
    };
    const Polynomial polys[3] = {{1, {}, {1}}, {2, {1}, {1, 3}}, {3, {0, 1}, {1, 3, 1}}};
    std::uint32_t out[4] = {0, 0, 0, 0};
    for (int k = 0; k < 32; ++k)
        if ((index >> k) & 1u) out[0] ^= 0x80000000u >> k;
    for (int d = 0; d < 3; ++d) {
        const Polynomial& p = polys[d];
        std::vector<std::uint32_t> v;
        for (int k = 0; k < 32; ++k) {
            if (k < p.s) {
                v.push_back(p.m[k] << (31 - k));
                continue;
            }
            std::uint32_t x = v[k - p.s] ^ (v[k - p.s] >> p.s);
            for (int j = 1; j < p.s; ++j)
                if (p.a[j - 1]) x ^= v[k - j];
            v.push_back(x);
        }
        for (int k = 0; k < 32; ++k)
            if ((index >> k) & 1u) out[d + 1] ^= v[k];
    }
    return dev::make_uint4(out[0], out[1], out[2], out[3]);
}

TEST(SobolSampler, DirectionNumbersAreSobols)
{
    for (std::uint32_t i = 0; i < (1u << 16); ++i) {
        const dev::uint4 got = dev::gc_sobol4_reversed(i);
        const dev::uint4 want = sobol_by_recurrence(i);
        ASSERT_EQ(dev::gc_reverse_bits(got.x), want.x) << "index " << i;
        ASSERT_EQ(dev::gc_reverse_bits(got.y), want.y) << "index " << i;
        ASSERT_EQ(dev::gc_reverse_bits(got.z), want.z) << "index " << i;
        ASSERT_EQ(dev::gc_reverse_bits(got.w), want.w) << "index " << i;
    }
    // Known points: index 1 is 1/2 in every dimension, 2 is (1/4, 3/4, 3/4, 3/4), 4 reads each
    // dimension's third direction number: 1/8, 5/8, 3/8, 1/8.
    const dev::uint4 four = sobol_by_recurrence(4);
    EXPECT_EQ(four.x, 0x20000000u);
    EXPECT_EQ(four.y, 0xA0000000u);
    EXPECT_EQ(four.z, 0x60000000u);
    EXPECT_EQ(four.w, 0x20000000u);
    EXPECT_EQ(sobol_by_recurrence(2).w, 0xC0000000u);
    EXPECT_EQ(sobol_by_recurrence(1).y, 0x80000000u);
    // The first 256 points: every dimension stratified, dimensions 0 and 1 a (0, 8, 2)-net.
    std::vector<dev::float4> points;
    for (std::uint32_t i = 0; i < kPoints; ++i) {
        const dev::uint4 p = sobol_by_recurrence(i);
        points.push_back(dev::make_float4(float(p.x >> 8) / 16777216.0f, float(p.y >> 8) / 16777216.0f,
                                          float(p.z >> 8) / 16777216.0f, float(p.w >> 8) / 16777216.0f));
    }
    for (int c = 0; c < 4; ++c) EXPECT_TRUE(is_stratified(points, c)) << "dimension " << c;
    EXPECT_TRUE(is_02_net(points, 0, 1));
}

TEST(SobolSampler, EveryAlignedWindowIsStratified)
{
    // Chunks are aligned ranges of sample indices: 256 samples from any multiple of 256 are
    // stratified in each dimension, and each block's 2D point, (x, y) for the camera and
    // (y, z) for the others, is a (0, 8, 2)-net; past 2^16 samples too (new keys there).
    std::size_t windows = 0;
    for (const std::uint32_t pixel : {0u, 7u, 123457u})
        for (const std::uint32_t first : {0u, kPoints, 37u * kPoints, (1u << 16) + 5u * kPoints})
            for (const std::uint32_t block : {dev::gc_rng_block(0, 0), std::uint32_t(GC_RNG_BLOCK_CAMERA), dev::gc_rng_block(3, 1)})
                for (const std::uint32_t seed : {0u, 99u}) {
                    const std::vector<dev::float4> points = window(pixel, first, block, seed);
                    for (int c = 0; c < 4; ++c)
                        EXPECT_TRUE(is_stratified(points, c)) << "pixel " << pixel << " first " << first << " block "
                                                              << block << " dimension " << c;
                    const bool camera = block == GC_RNG_BLOCK_CAMERA;
                    EXPECT_TRUE(is_02_net(points, camera ? 0 : 1, camera ? 1 : 2)) << "block " << block;
                    ++windows;
                }
    std::printf("[sobol] %zu windows of %u samples: each dimension stratified, each 2D point a (0,8,2)-net\n", windows,
                kPoints);
}

TEST(SobolSampler, ANonAlignedWindowIsNotStratified)
{
    // The test above can fail: 256 samples that straddle two aligned windows are not a net.
    EXPECT_FALSE(is_02_net(window(5, kPoints / 2, GC_RNG_BLOCK_CAMERA, 0), 0, 1));
}

TEST(SobolSampler, PixelsBlocksAndSeedsAreDecorrelated)
{
    // The first sample of 2^16 pixels: uniform in each dimension (mean 1/2, variance 1/12 to
    // a few standard errors) and uncorrelated between the dimensions and with the next block
    // and the next seed. Without the per-pixel scrambles every pixel would draw one point.
    constexpr std::uint32_t kPixels = 1u << 16;
    double sum[4] = {0, 0, 0, 0}, sum_sq[4] = {0, 0, 0, 0}, cross_dim = 0, cross_block = 0, cross_seed = 0;
    for (std::uint32_t p = 0; p < kPixels; ++p) {
        const dev::float4 u = dev::gc_sobol_rand4(p, 0, dev::gc_rng_block(0, 0), 3);
        const dev::float4 next_block = dev::gc_sobol_rand4(p, 0, dev::gc_rng_block(0, 1), 3);
        const dev::float4 next_seed = dev::gc_sobol_rand4(p, 0, dev::gc_rng_block(0, 0), 4);
        for (int c = 0; c < 4; ++c) {
            sum[c] += component(u, c);
            sum_sq[c] += double(component(u, c)) * component(u, c);
        }
        cross_dim += (u.y - 0.5) * (u.z - 0.5);
        cross_block += (u.y - 0.5) * (next_block.y - 0.5);
        cross_seed += (u.y - 0.5) * (next_seed.y - 0.5);
    }
    const double n = kPixels;
    const double mean_se = std::sqrt(1.0 / 12.0 / n);  // standard error of a uniform mean
    const double corr_se = 1.0 / std::sqrt(n);         // of a correlation coefficient near 0
    for (int c = 0; c < 4; ++c) {
        const double mean = sum[c] / n;
        const double var = sum_sq[c] / n - mean * mean;
        std::printf("[sobol] dimension %d over %u pixels: mean %.5f, variance %.5f\n", c, kPixels, mean, var);
        EXPECT_LT(std::fabs(mean - 0.5), 5.0 * mean_se) << "dimension " << c;
        EXPECT_NEAR(var, 1.0 / 12.0, 0.003) << "dimension " << c;
    }
    const double to_corr = 12.0 / n;
    std::printf("[sobol] correlations: dimensions %.4f, blocks %.4f, seeds %.4f (standard error %.4f)\n",
                cross_dim * to_corr, cross_block * to_corr, cross_seed * to_corr, corr_se);
    EXPECT_LT(std::fabs(cross_dim * to_corr), 5.0 * corr_se);
    EXPECT_LT(std::fabs(cross_block * to_corr), 5.0 * corr_se);
    EXPECT_LT(std::fabs(cross_seed * to_corr), 5.0 * corr_se);
}

TEST(SobolSampler, IntegratesASmoothFunctionFasterThanIndependentSamples)
{
    // f(x, y) = x y on the unit square (integral 1/4), 256 samples, averaged over 256 pixels:
    // the Sobol estimate's squared error is far below the independent one's (O(n^-3) against
    // O(n^-1) for Owen-scrambled nets on smooth integrands; 1/(144 n) for independent ones).
    double sobol_sq = 0, independent_sq = 0;
    constexpr std::uint32_t kPixels = 256;
    const std::uint32_t block = dev::gc_rng_block(1, 0);
    for (std::uint32_t p = 0; p < kPixels; ++p) {
        double s = 0, i = 0;
        for (std::uint32_t k = 0; k < kPoints; ++k) {
            const dev::float4 a = dev::gc_sobol_rand4(p, k, block, 0);
            const dev::float4 b = dev::gc_rand4(p, k, block, 0);
            s += double(a.y) * a.z;
            i += double(b.y) * b.z;
        }
        sobol_sq += std::pow(s / kPoints - 0.25, 2);
        independent_sq += std::pow(i / kPoints - 0.25, 2);
    }
    const double sobol_mse = sobol_sq / kPixels, independent_mse = independent_sq / kPixels;
    std::printf("[sobol] MSE of 256-sample estimates of the mean of x y: sobol %.3g, independent %.3g (%.0fx)\n",
                sobol_mse, independent_mse, independent_mse / sobol_mse);
    EXPECT_LT(sobol_mse * 100.0, independent_mse);
}

}  // namespace
}  // namespace gc
