#include "host/render/wavefront_launches.h"

#include <algorithm>

namespace gc {

std::uint32_t wavefront_launch_size(std::uint32_t entries, std::uint32_t width)
{
    return width == 0 ? entries : std::min(entries, width);
}

WavefrontLaunches::WavefrontLaunches(std::uint32_t max_depth, std::optional<std::uint32_t> fixed_width,
                                     std::uint32_t first_width, std::uint32_t min_width)
    : m_max_depth(max_depth), m_fixed_width(fixed_width), m_first_width(first_width), m_min_width(std::max(min_width, 1u))
{
}

// The first bounce's launches are one work-item per entry: its queue is full, and a full queue
// looped over by fewer work-items balances no better (docs/decisions/wavefront-launch-sizing.md).
std::uint32_t WavefrontLaunches::ray_width(std::uint32_t depth, std::uint32_t paths) const
{
    if (depth == 0) return 0;
    if (m_fixed_width) return *m_fixed_width;
    if (!has_history()) return m_first_width;
    return predicted(m_history[2 * (depth - 1)], paths);
}

std::uint32_t WavefrontLaunches::shadow_width(std::uint32_t depth, std::uint32_t paths) const
{
    if (m_fixed_width) return depth == 0 ? 0u : *m_fixed_width;
    if (!has_history()) return depth == 0 ? 0u : m_first_width;
    return predicted(m_history[2 * depth + 1], paths);
}

void WavefrontLaunches::record(std::span<const std::uint32_t> lengths, std::uint32_t paths)
{
    if (lengths.size() != 2 * std::size_t{m_max_depth} || paths == 0) return;
    m_history.assign(lengths.begin(), lengths.end());
    m_history_paths = paths;
}

// The last length scaled to this batch, a sixteenth more, and the least width on top: a batch
// of other pixels (the last of a pass is often smaller) or later samples may bounce a little
// more. Never wider than the batch, never 0 (which would mean one work-item per entry).
std::uint32_t WavefrontLaunches::predicted(std::uint32_t last_length, std::uint32_t paths) const
{
    const std::uint64_t scaled = std::uint64_t{last_length} * paths / m_history_paths;
    const std::uint64_t width = scaled + scaled / 16 + m_min_width;
    return static_cast<std::uint32_t>(std::max<std::uint64_t>(1, std::min<std::uint64_t>(width, paths)));
}

}  // namespace gc
