#include "tools/bench/ocl_bench.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <stdexcept>
#include <string>

#include "host/render/pass_planner.h"
#include "host/render/megakernel_path.h"
#include "host/render/renderer.h"
#include "tools/bench/timing.h"

namespace gc::bench {

OclTracer::OclTracer(const cl::Context& context, const FlatBvh& bvh, const RenderSetup& setup)
    : m_context(context),
      m_bvh(DeviceBvh::upload(context, bvh, bvh_layout_for(context.device(), setup.tuning.bvh_layout))),
      m_program(context, "trace.cl", program_options(m_bvh.layout()), setup.build),
      m_closest(m_program.kernel("trace_closest")),
      m_any(m_program.kernel("trace_any"))
{
    if (has_packets()) m_closest8 = m_program.kernel("trace_closest8");
}

std::uint32_t OclTracer::upload(const std::vector<dev::GcRay>& rays, bool replicate)
{
    std::uint32_t copies = 1;
    if (replicate && !rays.empty() && rays.size() < m_min_launch_rays)
        copies = static_cast<std::uint32_t>((m_min_launch_rays + rays.size() - 1) / rays.size());
    if (replicate) m_copies = copies;
    const std::size_t total = rays.size() * copies;
    if (m_rays.count() < total) {
        m_rays = cl::Buffer<dev::GcRay>::create(m_context, total, CL_MEM_READ_ONLY, "bench rays");
        m_hits = cl::Buffer<dev::GcHit>::create(m_context, total, CL_MEM_WRITE_ONLY, "bench hits");
        m_flags = cl::Buffer<std::uint32_t>::create(m_context, total, CL_MEM_WRITE_ONLY, "bench occlusion");
    }
    // Each copy has its own hit slots, so every traversal's result is stored (none is dead
    // code) and no two work-items write one slot; the first copy's are read back.
    for (std::uint32_t c = 0; c < copies; ++c) m_rays.write(rays, c * rays.size());
    return static_cast<std::uint32_t>(total);
}

// One untimed launch of `kernel` (its arguments set) over `count` work-items, then `repeats`
// timed ones, each to the end of the device's work.
std::vector<double> OclTracer::timed_launches(cl::Kernel& kernel, std::uint32_t count, std::uint32_t copies,
                                              int repeats, const char* what)
{
    kernel.launch(m_context, count, 0, what);
    m_context.finish();
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
        const auto start = Clock::now();
        kernel.launch(m_context, count, 0, what);
        m_context.finish();
        times.push_back(seconds_since(start) / copies);
    }
    return times;
}

namespace {

// Checks that every copy of the set found the first copy's answers (the same rays through the
// same BVH: any other answer means a copy was not the set).
void expect_copies_agree(const std::vector<std::uint32_t>& all, std::size_t set_size, const char* what)
{
    for (std::size_t i = set_size; i < all.size(); ++i)
        if (all[i] != all[i % set_size])
            throw std::runtime_error(std::string("benchmark ") + what + ": copy " + std::to_string(i / set_size) +
                                     " of the ray set found another answer than the set for ray " +
                                     std::to_string(i % set_size));
}

}  // namespace

void OclTracer::read_prims(std::vector<std::uint32_t>& prims, std::uint32_t copies) const
{
    std::vector<dev::GcHit> hits(prims.size() * copies);
    m_hits.read(hits, 0);
    std::vector<std::uint32_t> all(hits.size());
    for (std::size_t i = 0; i < hits.size(); ++i) all[i] = hits[i].prim;
    expect_copies_agree(all, prims.size(), "closest hits");
    std::copy_n(all.begin(), prims.size(), prims.begin());
}

std::vector<double> OclTracer::closest(const std::vector<dev::GcRay>& rays, int repeats,
                                       std::vector<std::uint32_t>& prims)
{
    prims.assign(rays.size(), GC_INVALID);
    if (rays.empty()) return {};
    const std::uint32_t count = upload(rays);
    m_closest.set_args(m_bvh.nodes(), m_bvh.triangles(), m_rays, m_hits, count);
    const std::vector<double> times = timed_launches(m_closest, count, m_copies, repeats, "benchmark closest hits");
    read_prims(prims, m_copies);
    return times;
}

std::vector<double> OclTracer::closest_packets(const std::vector<dev::GcRay>& rays, int repeats,
                                               std::vector<std::uint32_t>& prims)
{
    prims.assign(rays.size(), GC_INVALID);
    if (rays.empty() || !has_packets()) return {};
    const std::size_t packets = (rays.size() + 7) / 8;
    std::vector<dev::GcRay> lanes(rays);
    lanes.resize(packets * 8, rays.back());  // idle lanes: copies, never traced
    std::vector<int> active(lanes.size(), 0);
    std::fill_n(active.begin(), rays.size(), 1);
    upload(lanes, false);
    if (m_active.count() < active.size())
        m_active = cl::Buffer<int>::create(m_context, active.size(), CL_MEM_READ_ONLY, "bench packet lanes");
    m_active.write(active);
    const auto count = static_cast<std::uint32_t>(packets);
    m_closest8.set_args(m_bvh.nodes(), m_bvh.triangles(), m_rays, m_active, m_hits, count);
    const std::vector<double> times =
        timed_launches(m_closest8, count, 1, repeats, "benchmark closest hits, packets of eight");
    read_prims(prims, 1);
    return times;
}

std::vector<double> OclTracer::occluded(const std::vector<dev::GcRay>& rays, int repeats,
                                        std::vector<std::uint32_t>& flags)
{
    flags.assign(rays.size(), 0u);
    if (rays.empty()) return {};
    const std::uint32_t count = upload(rays);
    m_any.set_args(m_bvh.nodes(), m_bvh.triangles(), m_rays, m_flags, count);
    const std::vector<double> times = timed_launches(m_any, count, m_copies, repeats, "benchmark any hits");
    std::vector<std::uint32_t> all(rays.size() * m_copies);
    m_flags.read(all, 0);
    expect_copies_agree(all, rays.size(), "any hits");
    std::copy_n(all.begin(), rays.size(), flags.begin());
    return times;
}

PathFigures path_samples(const cl::Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
                         const RenderSettings& settings, int max_samples, double budget_seconds,
                         const RenderSetup& setup)
{
    PathFigures figures;
    Renderer renderer(context, scene, bvh, camera, settings, setup);
    figures.pixels = double(settings.width) * double(settings.height);
    figures.scene_bytes = double(renderer.device_scene().bytes());
    figures.wavefront = renderer.batch_pixels();
    figures.megakernel = dynamic_cast<const MegakernelPathIntegrator*>(&renderer.integrator()) != nullptr;
    renderer.render_sample(); // warm-up: PoCL builds its work-group functions on first launch
    // A long render spends nearly all its time in passes of the planner's steady size, so
    // that is what is timed. The planner at most doubles per pass, from 1 to
    // PassPlanner::kMaxSamples (bit_width(kMaxSamples) passes), and the first pass never
    // settles it: a few passes of slack on top.
    constexpr int kWarmUpPasses = std::bit_width(PassPlanner::kMaxSamples) + 3;
    for (int pass = 0; pass < kWarmUpPasses && budget_seconds > 0.0 && !renderer.passes_settled(); ++pass)
        renderer.render_samples(static_cast<std::uint32_t>(max_samples));
    const auto begin = Clock::now();
    // Small images trace several samples per pass (Renderer::render_samples); each sample
    // is credited the pass's time divided by its samples.
    for (int s = 0; s < max_samples;) {
        const auto start = Clock::now();
        const std::uint32_t done = renderer.render_samples(static_cast<std::uint32_t>(max_samples - s));
        const double seconds = seconds_since(start);
        for (std::uint32_t k = 0; k < done; ++k) figures.sample_seconds.push_back(seconds / done);
        figures.samples_per_pass = std::max(figures.samples_per_pass, done);
        s += static_cast<int>(done);
        if (seconds_since(begin) > budget_seconds) break;
    }
    return figures;
}

double copy_bandwidth(const cl::Context& context, std::size_t bytes, int repeats)
{
    bytes = std::min<std::size_t>(bytes, context.device().max_alloc / 4);
    bytes &= ~std::size_t{255};
    auto src = cl::Buffer<std::uint8_t>::create(context, bytes, CL_MEM_READ_WRITE, "bandwidth source");
    auto dst = cl::Buffer<std::uint8_t>::create(context, bytes, CL_MEM_READ_WRITE, "bandwidth destination");
    const std::uint8_t zero = 0;
    GC_CL_WHAT("filling the bandwidth buffer", clEnqueueFillBuffer, context.queue(), src.mem(), &zero, 1, 0, bytes, 0,
               nullptr, nullptr);
    context.finish();
    double best = 1e30;
    for (int r = 0; r < repeats + 1; ++r) {
        const auto start = Clock::now();
        GC_CL_WHAT("copying for the bandwidth figure", clEnqueueCopyBuffer, context.queue(), src.mem(), dst.mem(), 0, 0,
                   bytes, 0, nullptr, nullptr);
        context.finish();
        if (r > 0) best = std::min(best, seconds_since(start));
    }
    return 2.0 * double(bytes) / best;
}

}  // namespace gc::bench
