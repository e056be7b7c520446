// How many work-items each launch of the wavefront path integrator gets. The first bounce's
// queues hold every camera ray; later ones shrink by an amount that, on GPUs, only the device
// knows while it runs (the host does not wait to read the counters back: run_path_batch). The
// extend, shade and shadow kernels loop over their queue in steps of the launch's width, so any
// width gives the same image; the width only decides how many work-items find nothing to do
// (too wide) and how long the rest loop (too narrow).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace gc {

// Work-items for a launch over `entries` queue entries when a launch may hold at most `width`
// of them (0: one per entry).
std::uint32_t wavefront_launch_size(std::uint32_t entries, std::uint32_t width);

// Each depth's launch widths for one wavefront batch. Sized from the queue lengths the last
// batch left at the same depth (record), scaled to this batch's paths, with some slack: a pass's
// paths bounce alike from one pass to the next, so the last one is a close estimate, and one
// that falls short costs only a few more loop steps. Before any batch is recorded, and always
// with a fixed width, every launch after the first bounce holds at most that width.
class WavefrontLaunches {
public:
    // fixed_width: no prediction, this width after the first bounce
    // (DeviceTuning::wavefront_items_per_unit).
    // first_width: the width until a batch is recorded. min_width: the least predicted width
    // (a few work-groups per compute unit, so a queue that grew since still spreads out).
    WavefrontLaunches(std::uint32_t max_depth, std::optional<std::uint32_t> fixed_width, std::uint32_t first_width,
                      std::uint32_t min_width);

    // Width of the extend and shade launches at `depth` in a batch of `paths` paths.
    std::uint32_t ray_width(std::uint32_t depth, std::uint32_t paths) const;
    // Width of the shadow-ray launch at `depth`.
    std::uint32_t shadow_width(std::uint32_t depth, std::uint32_t paths) const;

    // The queue lengths a batch of `paths` paths left: for each depth, the rays it queued for
    // the next depth, then its shadow rays (2 x max_depth values). Later batches are sized
    // from them; a span of another length is ignored.
    void record(std::span<const std::uint32_t> lengths, std::uint32_t paths);
    bool has_history() const { return m_history_paths > 0; }

private:
    std::uint32_t predicted(std::uint32_t last_length, std::uint32_t paths) const;

    std::uint32_t m_max_depth;
    std::optional<std::uint32_t> m_fixed_width;
    std::uint32_t m_first_width;
    std::uint32_t m_min_width;
    std::vector<std::uint32_t> m_history;  // the recorded lengths, as record takes them
    std::uint32_t m_history_paths = 0;     // paths of the recorded batch (0: none yet)
};

}  // namespace gc
