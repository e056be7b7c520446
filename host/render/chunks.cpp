#include "host/render/chunks.h"

#include <algorithm>
#include <utility>

#include "host/util/error.h"

namespace gc {

ChunkPlan ChunkPlan::for_range(std::uint32_t first_sample, std::uint32_t end_sample, std::uint32_t chunk_samples)
{
    if (chunk_samples == 0) throw UsageError("the chunk size must be at least 1 sample");
    if (end_sample <= first_sample)
        throw UsageError("the sample range " + std::to_string(first_sample) + ":" + std::to_string(end_sample) +
                         " is empty");
    if (first_sample % chunk_samples != 0)
        throw UsageError("the sample range " + std::to_string(first_sample) + ":" + std::to_string(end_sample) +
                         " does not start a chunk: its start must be a multiple of the chunk size (" +
                         std::to_string(chunk_samples) + " samples)");
    return ChunkPlan{first_sample, end_sample, chunk_samples};
}

std::uint32_t ChunkPlan::chunk_count() const
{
    if (end_sample <= first_sample || chunk_samples == 0) return 0;
    const std::uint64_t span = std::uint64_t(end_sample) - first_sample;
    return static_cast<std::uint32_t>((span + chunk_samples - 1) / chunk_samples);
}

ChunkRange ChunkPlan::chunk(std::uint32_t n) const
{
    ChunkRange c;
    c.index = first_chunk() + n;
    c.first = first_sample + n * chunk_samples;
    c.count = std::min(chunk_samples, end_sample - c.first);
    return c;
}

void add_sums(FilmSums& into, const FilmSums& chunk)
{
    if (into.width != chunk.width || into.height != chunk.height || into.sums.size() != chunk.sums.size() ||
        into.sample_counts.size() != chunk.sample_counts.size() || into.squares.size() != chunk.squares.size())
        throw UsageError("cannot add film sums of different sizes (" + std::to_string(into.width) + "x" +
                         std::to_string(into.height) + " and " + std::to_string(chunk.width) + "x" +
                         std::to_string(chunk.height) + ")");
    for (std::size_t i = 0; i < into.sums.size(); ++i) into.sums[i] += chunk.sums[i];
    for (std::size_t i = 0; i < into.squares.size(); ++i) into.squares[i] += chunk.squares[i];
    for (std::size_t i = 0; i < into.sample_counts.size(); ++i) into.sample_counts[i] += chunk.sample_counts[i];
}

Film mean_film(const FilmSums& sums)
{
    Film film(sums.width, sums.height);
    for (std::size_t i = 0; i < sums.sums.size(); ++i) {
        const std::uint32_t n = i < sums.sample_counts.size() ? sums.sample_counts[i] : 0;
        const float inv = n > 0 ? 1.0f / static_cast<float>(n) : 0.0f;
        const std::uint32_t x = static_cast<std::uint32_t>(i % sums.width);
        const std::uint32_t y = static_cast<std::uint32_t>(i / sums.width);
        film.set(x, y, Rgba{sums.sums[i].x * inv, sums.sums[i].y * inv, sums.sums[i].z * inv, 1.0f});
    }
    return film;
}

Film sample_variance(const FilmSums& s)
{
    if (s.squares.size() != s.sums.size())
        throw UsageError("the sample variance needs the squared sums, which these film sums do not hold");
    Film film(s.width, s.height);
    for (std::size_t i = 0; i < s.sums.size(); ++i) {
        const double n = i < s.sample_counts.size() ? s.sample_counts[i] : 0;
        float v[3] = {0, 0, 0};
        if (n > 1) {
            for (int c = 0; c < 3; ++c) {
                const double mean = s.sums[i][c] / n;
                v[c] = static_cast<float>(std::max(0.0, (s.squares[i][c] / n - mean * mean) * n / (n - 1)));
            }
        }
        film.set(static_cast<std::uint32_t>(i % s.width), static_cast<std::uint32_t>(i / s.width),
                 Rgba{v[0], v[1], v[2], 1.0f});
    }
    return film;
}

void FrameAccumulator::start_with(FilmSums prefix, std::uint32_t chunks)
{
    std::lock_guard lock(m_mutex);
    if (m_started || chunks == 0) throw UsageError("a frame starts from its first chunks once, before any other");
    m_frame = std::move(prefix);
    m_started = true;
    m_next = m_plan.first_chunk() + chunks;
    m_folded_end = m_plan.first_sample + chunks * m_plan.chunk_samples;
}

FilmSums FrameAccumulator::folded(std::uint32_t* chunks) const
{
    std::lock_guard lock(m_mutex);
    if (chunks) *chunks = m_started ? m_next - m_plan.first_chunk() : 0;
    return m_started ? m_frame : FilmSums{};
}

void FrameAccumulator::fold_locked(FilmSums&& sums, std::uint32_t count)
{
    if (!m_started) {
        m_frame = std::move(sums);
        m_started = true;
    } else {
        add_sums(m_frame, sums);
    }
    m_folded_end = m_plan.first_sample + (m_next - m_plan.first_chunk()) * m_plan.chunk_samples + count;
    ++m_next;
}

void FrameAccumulator::add(const ChunkRange& range, FilmSums sums)
{
    std::lock_guard lock(m_mutex);
    if (range.index < m_next || m_waiting.count(range.index)) return;  // a backup's second copy
    m_truncated.erase(range.index);
    m_waiting.emplace(range.index, std::move(sums));
    for (auto it = m_waiting.find(m_next); it != m_waiting.end(); it = m_waiting.find(m_next)) {
        FilmSums next = std::move(it->second);
        m_waiting.erase(it);
        fold_locked(std::move(next), m_plan.chunk(m_next - m_plan.first_chunk()).count);
    }
}

void FrameAccumulator::add_truncated(const ChunkRange& range, FilmSums sums)
{
    std::lock_guard lock(m_mutex);
    if (range.index < m_next || m_waiting.count(range.index) || range.count == 0) return;
    auto it = m_truncated.find(range.index);
    // Of two cut copies of one chunk (a backup), keep the one with more samples.
    if (it != m_truncated.end() && it->second.first.count >= range.count) return;
    m_truncated[range.index] = {range, std::move(sums)};
}

std::uint32_t FrameAccumulator::samples_folded() const
{
    std::lock_guard lock(m_mutex);
    return m_started ? m_folded_end - m_plan.first_sample : 0;
}

FilmSums FrameAccumulator::frame() const
{
    std::lock_guard lock(m_mutex);
    return m_started ? m_frame : FilmSums{};
}

std::uint32_t FrameAccumulator::next_chunk() const
{
    std::lock_guard lock(m_mutex);
    return m_next;
}

FilmSums FrameAccumulator::finish(std::uint32_t* end_sample)
{
    std::lock_guard lock(m_mutex);
    if (auto it = m_truncated.find(m_next); it != m_truncated.end()) {
        const std::uint32_t count = it->second.first.count;
        FilmSums sums = std::move(it->second.second);
        m_truncated.erase(it);
        fold_locked(std::move(sums), count);
    }
    m_waiting.clear();
    m_truncated.clear();
    if (end_sample) *end_sample = m_started ? m_folded_end : m_plan.first_sample;
    return m_started ? std::move(m_frame) : FilmSums{};
}

}  // namespace gc
