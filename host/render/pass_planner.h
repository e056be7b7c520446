// How many samples per pixel the CPU path integrator traces in one pass.
//
// The megakernel (kernels/megakernel.cl) gives each work-item one pixel and runs that pass's
// samples of it one after the other. Consecutive samples of one pixel retrace nearly the same
// camera ray and first hit, so the second and later ones find that part of the BVH, the
// triangles and the shading data in the core's caches. That pays most where the scene does
// not fit in L1 (docs/decisions/cpu-pass-length.md). Mitsuba 3 lays its wavefront out the
// same way (each pixel's samples side by side).
//
// Longer passes, though, mean a coarser progress bar and a later stop for --time-limit and
// Ctrl-C. So the planner aims each pass at a length, as Cycles' render scheduler does: half a
// second at first, then a tenth of the time rendered so far, up to two seconds, so that a
// long render updates less often (and runs faster) than a short one. It starts at one sample
// and, from the measured time per sample, doubles (at most) towards the count that fills the
// target, never above kMaxSamples. Grouping never changes the image (each pixel adds its
// samples in sample order; tests/validation/determinism_test.cpp), so a timing-driven plan
// keeps renders bit for bit reproducible.
//
// The cap is there only so that one pass cannot run away; the time target is what sizes a
// pass. It is high because on many cores a low cap cuts passes far below the target, and
// each short pass pays its launches, the wait for the last work-groups and the host's round
// trip (docs/decisions/cpu-pass-length.md).
#pragma once

#include <cstdint>

namespace gc {

class PassPlanner {
public:
    static constexpr double kMinTargetSeconds = 0.5;  // aimed length of the first passes
    static constexpr double kMaxTargetSeconds = 2.0;  // ... and of a long render's
    static constexpr double kTargetShare = 0.1;       // of the time rendered so far, between the two
    static constexpr std::uint32_t kMaxSamples = 256;

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

    // The last pass's seconds per sample; 0 before the first. What a caller with a deadline
    // (--time-limit) needs to keep a pass from running far past it.
    double seconds_per_sample() const { return m_seconds_per_sample; }

    // The length the next pass aims at.
    double target_seconds() const;

private:
    std::uint32_t m_fixed = 0;
    std::uint32_t m_planned = 1;
    std::uint32_t m_passes = 0;  // passes recorded
    double m_elapsed = 0.0;      // their seconds
    double m_seconds_per_sample = 0.0;
    bool m_settled = false;
};

// How many of `remaining` samples a render with `seconds_left` before its deadline should ask
// for next, passes taking `seconds_per_sample` (0: unknown): enough to reach the deadline,
// rounded up, so the pass that crosses it ends at most about one sample's time past it; at
// least 1, so that a render past its deadline still finishes the pass it is asked for.
std::uint32_t samples_before_deadline(double seconds_left, double seconds_per_sample, std::uint32_t remaining);

}  // namespace gc
