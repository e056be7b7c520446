// How many samples per pixel the CPU path integrator traces in one pass.
//
// The megakernel (kernels/megakernel.cl) gives each work-item one pixel and runs that pass's
// samples of it one after the other. Consecutive samples of one pixel retrace nearly the same
// camera ray and first hit, so the second and later ones find that part of the BVH, the
// triangles and the shading data in the core's caches: on the 2-core VM, one PoCL thread,
// the 100k-triangle dragon at 320x240 renders 1.25-1.3x faster with 16 samples per pass than
// with one (the 36-triangle Cornell box, which lives in L1 either way, 1.03x). Mitsuba 3 lays
// its wavefront out the same way (each pixel's samples side by side).
//
// Longer passes, though, mean a coarser progress bar and a later stop for --time-limit and
// Ctrl-C. So the planner aims each pass at a fixed length, as Cycles' render scheduler does:
// it starts at one sample and, from the measured time per sample, doubles (at most) towards
// the count that fills kTargetSeconds, never above kMaxSamples. Grouping never changes the
// image (each pixel adds its samples in sample order; tests/validation/determinism_test.cpp),
// so a timing-driven plan keeps renders bit for bit reproducible.
#pragma once

#include <cstdint>

namespace gc {

class PassPlanner {
public:
    static constexpr double kTargetSeconds = 0.5;  // aimed length of one pass
    static constexpr std::uint32_t kMaxSamples = 16;

    // fixed_samples > 0 turns the planning off: every pass traces that many (tests, A/B runs).
    explicit PassPlanner(std::uint32_t fixed_samples = 0) : m_fixed(fixed_samples) {}

    // Samples for the next pass, given how many the render still needs (>= 1).
    std::uint32_t next(std::uint32_t remaining) const;

    // A pass of `samples` samples took `seconds` (including waiting for the device).
    void record(std::uint32_t samples, double seconds);

    // Whether the plan has stopped growing: the last pass asked for no more than the one
    // before, or for the cap. Never after the first pass alone, whose time may include the
    // driver's compiling the work-group function (PoCL does that at the first launch).
    bool settled() const { return m_fixed != 0 || (m_passes >= 2 && m_settled); }

private:
    std::uint32_t m_fixed = 0;
    std::uint32_t m_planned = 1;
    std::uint32_t m_passes = 0;  // passes recorded
    bool m_settled = false;
};

}  // namespace gc
