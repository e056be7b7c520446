// Adaptive sampling (--noise-threshold T): a frame spends its samples where the image is still
// noisy. Its canonical chunks (chunks.h) are rendered in rounds that end at fixed check points;
// at each one, every tile whose pixels' relative standard errors of the mean have a root mean
// square below T stops, and the next round renders only the other tiles' pixels
// (Renderer::select_pixels), up to the sample cap (--spp).
//
//     const FrameResult frame = render_frame(devices, prepared, settings, setup, plan, control,
//                                            adaptive_rounds(0.02, settings.spp, plan.chunk_samples));
//
// The image stays a pure function of (scene, seed, options): the check points depend only on
// the cap and the chunk size, and each decision only on the frame so far, the chunks added in
// chunk order, which has the same bits on any number of devices of one kind. A pixel's sample
// s keeps the random numbers it has in a uniform render, so a tile that never stops has the
// uniform render's bits, and a tile that stops has its bits up to the check point.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "host/render/multi_device.h"
#include "host/render/renderer.h"

namespace gc {

// No pixel stops before this many samples, nor before a sixteenth of the cap: below that the
// error estimate is itself too noisy. Light that arrives by rare paths (caustics seen on a
// diffuse wall) makes the noise heavy-tailed, and a pixel that has not yet seen such a path
// looks converged; the later the first check, the fewer such pixels stop too early.
inline constexpr std::uint32_t k_adaptive_min_samples = 16;
inline constexpr std::uint32_t k_adaptive_min_fraction = 16;
// Pixels stop by square tiles of this side. A tile's error is the root mean square of its
// pixels' relative errors, its share of the image's relative MSE: one noisy pixel holds the tile
// in proportion to its noise (a thin caustic, the start of a firefly) instead of being dropped
// with its quiet neighbours. (The tile's worst pixel holds nearly every tile of a scene with
// caustics: a pixel whose one bright sample carries its mean has a relative error near 1 at any
// sample count, and most tiles hold one.)
inline constexpr std::uint32_t k_adaptive_tile = 8;
// The relative error divides by the mean luminance, but by no less than this: dark pixels with
// a little noise stop instead of sampling forever for an error no display shows.
inline constexpr double k_adaptive_mean_floor = 1e-3;

// The sample counts after which the pixels still sampled are decided: the first multiple of
// chunk_samples at or above k_adaptive_min_samples and spp / k_adaptive_min_fraction, then each
// doubling of it, while below spp.
// Doubling keeps the rounds few (each is a barrier for the devices) and the work between two
// decisions proportional to the work before them.
std::vector<std::uint32_t> adaptive_check_points(std::uint32_t spp, std::uint32_t chunk_samples);

// The relative standard error of a pixel's mean luminance after n samples, from the sums of
// its RGB samples and of their squares, bounded above: the luminance's standard deviation is
// at most the weighted sum of the channels' (whatever their correlation), divided by
// max(mean luminance, k_adaptive_mean_floor). Infinite below 2 samples.
double relative_standard_error(const glm::vec4& sum, const glm::vec4& squares, std::uint32_t n);

// The pixels that go on sampling after `samples` samples of `frame` (sums and squares): those of
// the k_adaptive_tile tiles that got all `samples` and whose root mean square relative standard
// error is at least `threshold`. Ascending indices y * width + x.
std::vector<std::uint32_t> noisy_pixels(const FilmSums& frame, std::uint32_t samples, double threshold);

// The rounds of an adaptive frame of at most `spp` samples per pixel.
FrameRounds adaptive_rounds(double threshold, std::uint32_t spp, std::uint32_t chunk_samples);

// The samples a frame holds, over all its pixels.
std::uint64_t total_samples(const FilmSums& frame);

}  // namespace gc
