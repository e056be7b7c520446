// Canonical chunks: how a frame's samples are cut into pieces that devices and machines render
// independently, and how the pieces add up to the frame.
//
// A frame of samples [0, spp) is the fixed list of chunks i = 0, 1, ...: chunk i holds the
// samples [i * C, min((i + 1) * C, spp)), C = chunk_samples (an option of the render, not of
// the machine: it is part of the render-options hash). Each chunk's per-pixel sums are
// accumulated in sample order (Renderer::render over the chunk, from a cleared film), and the
// frame is the chunks' sums added in chunk order, starting from chunk 0's sums:
//
//     frame = ((c0 + c1) + c2) + ...
//
// Neither depends on how many devices or machines rendered the chunks, nor on the order they
// finished in; so a frame split over N devices of one kind has the bits of the frame on one
// of them, and a merge of partial images has the bits of the frame rendered in one process.
// A frame of at most C samples is one chunk: the bits of a plain Renderer::render(0, spp).
#pragma once

#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "host/image/film.h"
#include "host/render/renderer.h"

namespace gc {

// The default chunk size: large enough that a GPU's per-chunk costs (a cleared film, a read
// back of the sums, the host's addition) stay small against the chunk's rendering, small
// enough that a slow device's last chunk does not hold up the frame for long.
inline constexpr std::uint32_t k_default_chunk_samples = 64;

struct ChunkRange {
    std::uint32_t index = 0;  // global: first / chunk_samples
    std::uint32_t first = 0;  // first sample index
    std::uint32_t count = 0;  // samples
    std::uint32_t end() const { return first + count; }
    bool operator==(const ChunkRange&) const = default;
};

// The chunks of the sample range [first_sample, end_sample) of a frame cut in chunks of
// chunk_samples. first_sample must start a chunk; end_sample may end one early (the frame's
// last chunk is short when spp is not a multiple of chunk_samples).
struct ChunkPlan {
    std::uint32_t first_sample = 0;
    std::uint32_t end_sample = 0;
    std::uint32_t chunk_samples = k_default_chunk_samples;

    // Throws UsageError when first_sample is not a multiple of chunk_samples, the range is
    // empty or chunk_samples is 0.
    static ChunkPlan for_range(std::uint32_t first_sample, std::uint32_t end_sample, std::uint32_t chunk_samples);

    std::uint32_t first_chunk() const { return first_sample / chunk_samples; }
    std::uint32_t chunk_count() const;
    // The n-th chunk of the plan (0 <= n < chunk_count()), with its global index.
    ChunkRange chunk(std::uint32_t n) const;
};

// Per-pixel sample variance of the samples in `sums` (unbiased: n - 1 in the denominator, n
// the pixel's sample count; 0 below two samples), alpha 1. Needs the squares.
Film sample_variance(const FilmSums& sums);

// `into` += `chunk`, pixel by pixel (sums, squares and sample counts). The sizes must match
// (UsageError otherwise).
void add_sums(FilmSums& into, const FilmSums& chunk);

// The mean of the samples in `sums`: radiance sum times 1 / (its sample count), alpha 1. The
// arithmetic of Renderer::film(), so a one-chunk frame has its bits.
Film mean_film(const FilmSums& sums);

// Adds chunks into a frame in chunk order, whatever order they arrive in. Thread-safe. Chunks
// that arrive early wait (their sums kept) until the ones before them are in.
class FrameAccumulator {
public:
    explicit FrameAccumulator(const ChunkPlan& plan) : m_plan(plan), m_next(plan.first_chunk()) {}

    // A complete chunk of the plan. A second copy of a chunk already in is dropped (a backup
    // render of the same chunk: same bits on devices of one kind).
    void add(const ChunkRange& range, FilmSums sums);
    // A chunk cut short by a deadline or a cancel: [range.first, range.first + range.count)
    // are the chunk's first samples. Folded by finish() if it is the next chunk due; the
    // frame then ends with it (the frame of range.end() samples has exactly this last chunk).
    void add_truncated(const ChunkRange& range, FilmSums sums);

    // Starts the frame from its first `chunks` chunks, already added in chunk order (a
    // checkpoint's, partial_image.h); before any add.
    void start_with(FilmSums prefix, std::uint32_t chunks);
    // A copy of the frame so far (the complete chunks folded), and in `chunks` how many it holds.
    FilmSums folded(std::uint32_t* chunks) const;

    // Samples folded into the frame so far (a contiguous prefix of the plan).
    std::uint32_t samples_folded() const;
    // A copy of the frame folded so far (empty sums before the first chunk).
    FilmSums frame() const;
    // The global index of the next chunk due.
    std::uint32_t next_chunk() const;
    // Folds the best truncated chunk that continues the prefix, and returns the frame (empty
    // sums when nothing was folded) with its sample range's end.
    FilmSums finish(std::uint32_t* end_sample);

private:
    void fold_locked(FilmSums&& sums, std::uint32_t count);

    ChunkPlan m_plan;
    mutable std::mutex m_mutex;
    std::map<std::uint32_t, FilmSums> m_waiting;
    std::map<std::uint32_t, std::pair<ChunkRange, FilmSums>> m_truncated;
    FilmSums m_frame;
    bool m_started = false;
    std::uint32_t m_next;
    std::uint32_t m_folded_end = 0;
};

}  // namespace gc
