// Adaptive sampling's decisions (host/render/adaptive.h), on the host: the check points, the
// error estimate and which tiles go on; and that the options hash sees the threshold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "gc_sampling.h"
#include "host/render/adaptive.h"
#include "host/render/frame_hash.h"
#include "host/util/error.h"

namespace gc {
namespace {

using Points = std::vector<std::uint32_t>;

TEST(AdaptiveCheckPoints, StartAtTheFirstChunkPastTheMinimumsAndDouble)
{
    EXPECT_EQ(adaptive_check_points(256, 64), (Points{64, 128}));
    EXPECT_EQ(adaptive_check_points(256, 8), (Points{16, 32, 64, 128}));
    EXPECT_EQ(adaptive_check_points(200, 5), (Points{20, 40, 80, 160}));
    EXPECT_EQ(adaptive_check_points(129, 16), (Points{16, 32, 64, 128}));
    EXPECT_EQ(adaptive_check_points(1024, 16), (Points{64, 128, 256, 512}));  // a sixteenth of the cap
    EXPECT_EQ(adaptive_check_points(1000, 48), (Points{96, 192, 384, 768}));
    EXPECT_EQ(adaptive_check_points(16, 16), Points{});  // nothing to decide: one round
    EXPECT_EQ(adaptive_check_points(64, 64), Points{});
    EXPECT_THROW(adaptive_check_points(64, 0), UsageError);
}

// The sums of `values` as a grey pixel (R = G = B), and of their squares.
void grey_pixel(const std::vector<float>& values, glm::vec4& sum, glm::vec4& squares)
{
    sum = squares = glm::vec4(0.0f);
    for (float v : values) {
        sum += glm::vec4(v, v, v, 1.0f);
        squares += glm::vec4(v * v, v * v, v * v, 0.0f);
    }
}

TEST(AdaptiveError, IsTheStandardErrorOverTheMean)
{
    glm::vec4 sum, squares;
    // 0 and 2 alternating: mean 1, unbiased variance n / (n - 1), standard error 1 / sqrt(n - 1).
    std::vector<float> values;
    for (int i = 0; i < 16; ++i) values.push_back(i % 2 ? 2.0f : 0.0f);
    grey_pixel(values, sum, squares);
    const double got = relative_standard_error(sum, squares, 16);
    std::printf("  0/2 alternating, 16 samples: %.6f (expected %.6f)\n", got, 1.0 / std::sqrt(15.0));
    EXPECT_NEAR(got, 1.0 / std::sqrt(15.0), 1e-6);

    // Scale-free: ten times brighter, same relative error.
    for (float& v : values) v *= 10.0f;
    grey_pixel(values, sum, squares);
    EXPECT_NEAR(relative_standard_error(sum, squares, 16), 1.0 / std::sqrt(15.0), 1e-6);

    // A constant pixel has converged, a black one too (no division by its zero mean).
    grey_pixel(std::vector<float>(16, 0.25f), sum, squares);
    EXPECT_NEAR(relative_standard_error(sum, squares, 16), 0.0, 1e-6);
    grey_pixel(std::vector<float>(16, 0.0f), sum, squares);
    EXPECT_EQ(relative_standard_error(sum, squares, 16), 0.0);
    // One sample says nothing about the error.
    grey_pixel({0.5f}, sum, squares);
    EXPECT_EQ(relative_standard_error(sum, squares, 1), std::numeric_limits<double>::infinity());
}

TEST(AdaptiveError, BoundsTheLuminanceOfCorrelatedChannels)
{
    // Red and green move together: the bound adds their deviations (weights of gc_luminance).
    glm::vec4 sum(0.0f), squares(0.0f);
    for (int i = 0; i < 8; ++i) {
        const float v = i % 2 ? 1.0f : 0.0f;
        sum += glm::vec4(v, v, 0.0f, 1.0f);
        squares += glm::vec4(v * v, v * v, 0.0f, 0.0f);
    }
    const double luminance = dev::gc_luminance(dev::make_float3(1.0f, 1.0f, 0.0f));
    const double deviation = std::sqrt(8.0 / 7.0 * 0.25);  // of each channel
    const double expected = luminance * deviation / std::sqrt(8.0) / (0.5 * luminance);
    EXPECT_NEAR(relative_standard_error(sum, squares, 8), expected, 1e-6);
}

// A width x height frame of `samples` samples per pixel, every pixel constant (converged).
FilmSums quiet_frame(std::uint32_t width, std::uint32_t height, std::uint32_t samples)
{
    FilmSums f;
    f.width = width;
    f.height = height;
    const std::size_t n = std::size_t(width) * height;
    f.sums.assign(n, glm::vec4(0.5f * samples, 0.5f * samples, 0.5f * samples, float(samples)));
    f.squares.assign(n, glm::vec4(0.25f * samples, 0.25f * samples, 0.25f * samples, 0.0f));
    f.sample_counts.assign(n, samples);
    return f;
}

// Makes pixel (x, y) noisy: half its samples 0, half 1.
void make_noisy(FilmSums& f, std::uint32_t x, std::uint32_t y)
{
    const std::size_t i = std::size_t(y) * f.width + x;
    const float half = 0.5f * float(f.sample_counts[i]);
    f.sums[i] = glm::vec4(half, half, half, float(f.sample_counts[i]));
    f.squares[i] = glm::vec4(half, half, half, 0.0f);
}

Points tile_pixels(std::uint32_t width, std::uint32_t x0, std::uint32_t y0, std::uint32_t x1, std::uint32_t y1)
{
    Points out;
    for (std::uint32_t y = y0; y < y1; ++y)
        for (std::uint32_t x = x0; x < x1; ++x) out.push_back(y * width + x);
    return out;
}

TEST(AdaptiveTiles, ANoisyPixelKeepsItsWholeTile)
{
    FilmSums f = quiet_frame(20, 10, 32);
    EXPECT_EQ(noisy_pixels(f, 32, 0.01), Points{});
    make_noisy(f, 17, 3);  // in the tile x 16..19 (cut by the edge), y 0..7
    EXPECT_EQ(noisy_pixels(f, 32, 0.01), tile_pixels(20, 16, 0, 20, 8));
    make_noisy(f, 2, 9);  // the bottom row of tiles, cut to y 8..9
    Points both = tile_pixels(20, 16, 0, 20, 8);
    for (std::uint32_t p : tile_pixels(20, 0, 8, 8, 10)) both.push_back(p);
    std::sort(both.begin(), both.end());
    EXPECT_EQ(noisy_pixels(f, 32, 0.01), both);
    // A tile's error is the root mean square of its pixels': one pixel of error e gives
    // e / sqrt(32) in the 4 x 8 tile and e / 4 in the 8 x 2 tile, so a threshold just above
    // e / sqrt(32) stops the first tile only.
    glm::vec4 sum, squares;
    std::vector<float> alternating;
    for (int i = 0; i < 32; ++i) alternating.push_back(float(i % 2));
    grey_pixel(alternating, sum, squares);
    const double tile_error = relative_standard_error(sum, squares, 32) / std::sqrt(32.0);
    EXPECT_EQ(noisy_pixels(f, 32, tile_error * 1.01), tile_pixels(20, 0, 8, 8, 10));
    EXPECT_EQ(noisy_pixels(f, 32, tile_error * 0.99), both);
    EXPECT_EQ(noisy_pixels(f, 32, 0.5), Points{});
}

TEST(AdaptiveTiles, AStoppedTileStaysStopped)
{
    FilmSums f = quiet_frame(16, 8, 32);
    make_noisy(f, 3, 3);
    make_noisy(f, 12, 3);
    // The right tile stopped at 16 samples: noisy or not, it is not sampled again.
    for (std::uint32_t p : tile_pixels(16, 8, 0, 16, 8)) f.sample_counts[p] = 16;
    EXPECT_EQ(noisy_pixels(f, 32, 0.01), tile_pixels(16, 0, 0, 8, 8));
}

TEST(AdaptiveTiles, RefusesAFrameWithoutSquares)
{
    FilmSums f = quiet_frame(8, 8, 16);
    f.squares.clear();
    EXPECT_THROW(noisy_pixels(f, 16, 0.01), UsageError);
    EXPECT_THROW(adaptive_rounds(0.0, 64, 16), UsageError);
}

TEST(AdaptiveOptionsHash, SeesTheThreshold)
{
    RenderSettings settings;
    const Camera camera;
    const std::uint64_t uniform = render_options_hash(settings, camera, 64);
    settings.noise_threshold = 0.02;
    const std::uint64_t adaptive = render_options_hash(settings, camera, 64);
    settings.noise_threshold = 0.05;
    EXPECT_NE(adaptive, uniform);
    EXPECT_NE(render_options_hash(settings, camera, 64), adaptive);
    settings.noise_threshold = 0.0;
    EXPECT_EQ(render_options_hash(settings, camera, 64), uniform);
}

}  // namespace
}  // namespace gc
