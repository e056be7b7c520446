#include "host/render/pass_planner.h"

#include <algorithm>
#include <cmath>

namespace gc {

std::uint32_t PassPlanner::next(std::uint32_t remaining) const
{
    return std::max(1u, std::min(remaining, m_fixed != 0 ? m_fixed : m_planned));
}

double PassPlanner::target_seconds() const
{
    return std::clamp(kTargetShare * m_elapsed, kMinTargetSeconds, kMaxTargetSeconds);
}

void PassPlanner::record(std::uint32_t samples, double seconds)
{
    if (samples == 0) return;
    m_seconds_per_sample = seconds / samples;
    m_elapsed += seconds;
    ++m_passes;
    if (m_fixed != 0) return;
    // The time per sample says how many fit into the target. The plan may only double, so
    // that one quick pass (a warm cache, a tiny image) cannot jump straight to a pass far
    // longer than the target. It grows from the plan, not from this pass, which may have been
    // cut short by the render's last samples.
    const double fitting = m_seconds_per_sample > 0.0 ? std::floor(target_seconds() / m_seconds_per_sample)
                                                      : double(kMaxSamples);
    const std::uint32_t limit = std::min(kMaxSamples, 2 * m_planned);
    const auto wanted = static_cast<std::uint32_t>(std::clamp(fitting, 1.0, double(limit)));
    // Settled once the plan no longer grows: it asks for no more than before, or for the cap.
    m_settled = wanted <= m_planned || wanted == kMaxSamples;
    m_planned = wanted;
}

std::uint32_t samples_before_deadline(double seconds_left, double seconds_per_sample, std::uint32_t remaining)
{
    if (!(seconds_per_sample > 0.0)) return remaining;
    const double fitting = std::ceil(std::max(seconds_left, 0.0) / seconds_per_sample);
    return static_cast<std::uint32_t>(std::clamp(fitting, 1.0, double(std::max(remaining, 1u))));
}

}  // namespace gc
