#include "host/render/pass_planner.h"

#include <algorithm>
#include <cmath>

namespace gc {

std::uint32_t PassPlanner::next(std::uint32_t remaining) const
{
    return std::max(1u, std::min(remaining, m_fixed != 0 ? m_fixed : m_planned));
}

void PassPlanner::record(std::uint32_t samples, double seconds)
{
    if (m_fixed != 0 || samples == 0) return;
    // The time per sample says how many fit into the target. The plan may only double, so
    // that one quick pass (a warm cache, a tiny image) cannot jump straight to a pass far
    // longer than the target. It grows from the plan, not from this pass, which may have been
    // cut short by the render's last samples.
    const double per_sample = seconds / samples;
    const double fitting = per_sample > 0.0 ? std::floor(kTargetSeconds / per_sample) : double(kMaxSamples);
    const std::uint32_t limit = std::min(kMaxSamples, 2 * m_planned);
    const auto wanted = static_cast<std::uint32_t>(std::clamp(fitting, 1.0, double(limit)));
    // Settled once the plan no longer grows: it asks for no more than before, or for the cap.
    m_settled = wanted <= m_planned || wanted == kMaxSamples;
    ++m_passes;
    m_planned = wanted;
}

}  // namespace gc
