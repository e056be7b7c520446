// The OpenCL half of the benchmark: ray throughput through kernels/trace.cl, path-traced
// samples per second through the Renderer, time to first image in a fresh process, and the
// device's copy bandwidth (the memory roofline's denominator).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "gc_types.h"
#include "host/bvh/flatten.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/kernel.h"
#include "host/cl/program.h"
#include "host/render/device_bvh.h"
#include "host/render/render_settings.h"
#include "host/render/render_setup.h"
#include "host/scene/scene.h"

namespace gc::bench {

// trace_closest / trace_any over device-resident ray buffers. Times are wall seconds of
// launch + clFinish (rays and BVH uploaded beforehand, results not read back), per pass over
// the ray set.
class OclTracer {
public:
    OclTracer(const cl::Context& context, const FlatBvh& bvh, const RenderSetup& setup = {});

    double compile_seconds() const { return m_program.build_seconds(); }
    const char* layout() const { return layout_name(m_bvh.layout()); }
    // Uploads the rays, runs one untimed launch, then `repeats` timed ones; returns every
    // timed duration. prims: the hit primitive (or the occlusion flag) of the last launch.
    std::vector<double> closest(const std::vector<dev::GcRay>& rays, int repeats, std::vector<std::uint32_t>& prims);
    std::vector<double> occluded(const std::vector<dev::GcRay>& rays, int repeats, std::vector<std::uint32_t>& flags);

    // Launches of at least `rays` rays: a smaller set is uploaded that many times over, back
    // to back, and one launch traces every copy (0: the set as it is). A GPU launch of a few
    // hundred thousand rays is about one wave of its resident threads, so its figure is held by
    // the wave's tail and the launch's fixed cost; the renderer's launches hold up to 2^24 paths.
    void set_min_launch_rays(std::size_t rays) { m_min_launch_rays = rays; }
    // Copies of the set that the last closest() or occluded() traced per launch (packets of
    // eight always trace one).
    std::uint32_t copies() const { return m_copies; }

    // Whether closest hits can also be traced eight neighbouring rays at a time as one packet
    // (trace.cl's trace_closest8, gc_packet8.h): on the BVH8, where the CPU path megakernel
    // traces its camera rays that way. Embree's counterpart is rtcIntersect16.
    bool has_packets() const { return m_bvh.layout() == BvhLayout::Wide8; }
    // As closest(), rays 8 i .. 8 i + 7 in packet i (the last one padded with idle lanes).
    std::vector<double> closest_packets(const std::vector<dev::GcRay>& rays, int repeats,
                                        std::vector<std::uint32_t>& prims);

private:
    // Uploads `rays` (copied as set_min_launch_rays asks where `replicate`) and sizes the
    // result buffers; returns the work-items of a launch over them.
    std::uint32_t upload(const std::vector<dev::GcRay>& rays, bool replicate = true);
    // Seconds per pass over the set: a launch's time over the `copies` of it that it traced.
    std::vector<double> timed_launches(cl::Kernel& kernel, std::uint32_t count, std::uint32_t copies, int repeats,
                                       const char* what);
    // The first prims.size() hits' primitives, after checking that each of the `copies` of the
    // set found the same (throws where one did not).
    void read_prims(std::vector<std::uint32_t>& prims, std::uint32_t copies) const;

    const cl::Context& m_context;
    DeviceBvh m_bvh;  // before m_program: its layout picks the traversal compiled
    cl::Program m_program;
    cl::Kernel m_closest;
    cl::Kernel m_any;
    cl::Kernel m_closest8;  // has_packets() only
    cl::Buffer<dev::GcRay> m_rays;
    cl::Buffer<int> m_active;  // trace_closest8's lane mask
    cl::Buffer<dev::GcHit> m_hits;
    cl::Buffer<std::uint32_t> m_flags;
    std::size_t m_min_launch_rays = 0;
    std::uint32_t m_copies = 1;
};

struct PathFigures {
    std::vector<double> sample_seconds; // one entry per timed sample (all pixels once)
    double pixels = 0.0;
    double scene_bytes = 0.0;           // DeviceScene::bytes()
    std::uint32_t wavefront = 0;  // pixels per pass
    std::uint32_t samples_per_pass = 0; // of the largest timed pass (the last may be cut short)
    bool megakernel = false;      // the path integrator ran as megakernel.cl (CPUs), else wavefront.cl
};
// Path-traces `settings`: one warm-up sample, warm-up passes until the renderer's passes have
// their steady size (a CPU's PassPlanner grows them over the first few), then up to
// max_samples timed samples, stopping early once budget_seconds have passed.
PathFigures path_samples(const cl::Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
                         const RenderSettings& settings, int max_samples, double budget_seconds,
                         const RenderSetup& setup = {});

// Device-to-device copy bandwidth in bytes per second (read + write counted), over a buffer
// of `bytes` (capped at a quarter of the largest allocation).
double copy_bandwidth(const cl::Context& context, std::size_t bytes, int repeats);

}  // namespace gc::bench
