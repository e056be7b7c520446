#include "host/render/adaptive.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gc_sampling.h"
#include "host/util/error.h"

namespace gc {

std::vector<std::uint32_t> adaptive_check_points(std::uint32_t spp, std::uint32_t chunk_samples)
{
    if (chunk_samples == 0) throw UsageError("the chunk size must be at least 1 sample");
    std::vector<std::uint32_t> points;
    const std::uint64_t least = std::max<std::uint64_t>(
        k_adaptive_min_samples, (std::uint64_t(spp) + k_adaptive_min_fraction - 1) / k_adaptive_min_fraction);
    std::uint64_t point = (least + chunk_samples - 1) / chunk_samples * chunk_samples;
    for (; point < spp; point *= 2) points.push_back(static_cast<std::uint32_t>(point));
    return points;
}

double relative_standard_error(const glm::vec4& sum, const glm::vec4& squares, std::uint32_t n)
{
    if (n < 2) return std::numeric_limits<double>::infinity();
    const double count = n;
    double mean[3];
    double deviation[3];
    for (int c = 0; c < 3; ++c) {
        mean[c] = sum[c] / count;
        const double variance = (squares[c] - count * mean[c] * mean[c]) / (count - 1.0);
        deviation[c] = std::sqrt(std::max(variance, 0.0));
    }
    const auto luminance = [](const double* rgb) {
        return double(dev::gc_luminance(dev::make_float3(float(rgb[0]), float(rgb[1]), float(rgb[2]))));
    };
    return luminance(deviation) / std::sqrt(count) / std::max(luminance(mean), k_adaptive_mean_floor);
}

std::vector<std::uint32_t> noisy_pixels(const FilmSums& frame, std::uint32_t samples, double threshold)
{
    const std::size_t pixels = std::size_t(frame.width) * frame.height;
    if (frame.sums.size() != pixels || frame.squares.size() != pixels || frame.sample_counts.size() != pixels)
        throw UsageError("adaptive sampling needs the frame's sums, squares and sample counts of every pixel");
    std::vector<std::uint8_t> noisy(pixels, 0);
    for (std::uint32_t ty = 0; ty < frame.height; ty += k_adaptive_tile)
        for (std::uint32_t tx = 0; tx < frame.width; tx += k_adaptive_tile) {
            const std::uint32_t x_end = std::min(tx + k_adaptive_tile, frame.width);
            const std::uint32_t y_end = std::min(ty + k_adaptive_tile, frame.height);
            // A tile stops as a whole, so its first pixel says whether it is still sampled.
            if (frame.sample_counts[std::size_t(ty) * frame.width + tx] != samples) continue;
            double squared = 0.0;
            for (std::uint32_t y = ty; y < y_end; ++y)
                for (std::uint32_t x = tx; x < x_end; ++x) {
                    const std::size_t i = std::size_t(y) * frame.width + x;
                    const double e = relative_standard_error(frame.sums[i], frame.squares[i], samples);
                    squared += e * e;
                }
            const double tile_error = std::sqrt(squared / double((x_end - tx) * (y_end - ty)));
            if (!(tile_error < threshold))
                for (std::uint32_t y = ty; y < y_end; ++y)
                    std::fill_n(noisy.begin() + std::ptrdiff_t(std::size_t(y) * frame.width + tx), x_end - tx, 1);
        }
    std::vector<std::uint32_t> out;
    for (std::size_t i = 0; i < pixels; ++i)
        if (noisy[i]) out.push_back(static_cast<std::uint32_t>(i));
    return out;
}

FrameRounds adaptive_rounds(double threshold, std::uint32_t spp, std::uint32_t chunk_samples)
{
    if (!(threshold > 0.0)) throw UsageError("the noise threshold must be a relative error > 0");
    FrameRounds rounds;
    rounds.check_points = adaptive_check_points(spp, chunk_samples);
    rounds.pixels_after = [threshold](const FilmSums& frame, std::uint32_t check_point) {
        return noisy_pixels(frame, check_point, threshold);
    };
    return rounds;
}

std::uint64_t total_samples(const FilmSums& frame)
{
    std::uint64_t total = 0;
    for (std::uint32_t n : frame.sample_counts) total += n;
    return total;
}

}  // namespace gc
