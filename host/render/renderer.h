// Renders a scene on one OpenCL device, one sample per pixel at a time. The caller owns the
// loop (progress, time limit, Ctrl-C) and asks for the film whenever it wants an image.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gc_types.h"
#include "host/bvh/bvh.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/kernel.h"
#include "host/cl/program.h"
#include "host/image/film.h"
#include "host/render/device_scene.h"
#include "host/render/device_tuning.h"
#include "host/render/render_setup.h"
#include "host/render/pass_planner.h"
#include "host/render/render_settings.h"
#include "host/render/wavefront_launches.h"
#include "host/scene/scene.h"

namespace gc {

class Renderer {
public:
    // `setup` changes the speed and where the kernels come from, never the image.
    Renderer(const cl::Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
             const RenderSettings& settings, const RenderSetup& setup = {});

    // Adds one sample to every pixel (several kernel passes if the image is larger than the
    // wavefront). Enqueues work and waits for it.
    void render_sample() { render_samples(1); }

    // Adds between 1 and max_samples samples to every pixel and returns how many: the path
    // integrator traces several samples per pixel in one pass, on GPUs when the image is
    // smaller than the wavefront, on CPUs as many as fill the planner's pass length (PassPlanner).
    // The image after n samples is the same bits however they were grouped.
    std::uint32_t render_samples(std::uint32_t max_samples);

    // Whether the passes have reached their steady size (benchmarks time from there on).
    bool passes_settled() const { return !m_megakernel || m_planner.settled(); }
    // The last pass's seconds per sample (0 before the first): for a caller with a deadline.
    double seconds_per_sample() const { return m_planner.seconds_per_sample(); }

    std::uint32_t samples_done() const { return m_samples; }
    std::uint32_t wavefront_size() const { return m_batch; }
    bool uses_megakernel() const { return m_megakernel; }
    // Pixels one megakernel work-item rendered in the last pass (gc_packet_lanes.h); 1 elsewhere.
    std::uint32_t pixels_per_item() const { return m_params.pixels_per_item; }
    // Wavefront path integrator: the queue lengths of the last pass's last batch, for each depth
    // the rays it queued for the next one and its shadow rays (2 x max_depth values; zeros
    // before the first pass and past the depth where every path ended).
    std::span<const std::uint32_t> last_queue_lengths() const { return m_last_queue_lengths; }
    const cl::Program& program() const { return m_program; }
    const DeviceScene& device_scene() const { return m_scene; }

    // The mean of the samples so far, linear RGB, alpha 1.
    Film film() const;
    // Per-pixel sample variance of the samples so far (unbiased, n - 1 in the denominator):
    // what a Z-test against a reference needs. Path integrator only; zero elsewhere.
    Film variance() const;

private:
    void run_aov_batch();
    void run_path_batch();
    void run_megakernel_batch();
    void run_whitted_batch(); // [whitted hook]

    const cl::Context& m_context;
    RenderSettings m_settings;
    DeviceScene m_scene;
    dev::GcRenderParams m_params{};
    bool m_megakernel = false;  // path integrator as megakernel.cl (before m_program: it picks the file)
    cl::Program m_program;
    std::uint32_t m_batch = 0;          // pixels per pass
    std::uint32_t m_path_capacity = 0;  // path slots (>= m_batch; samples * pixels per pass)
    std::uint32_t m_samples = 0;
    PassPlanner m_planner;              // samples per pass of the megakernel; pass times of any form
    bool m_sync_counts = false;         // wavefront: the host reads each bounce's queue lengths back (CPUs)
    WavefrontLaunches m_launches;       // wavefront: each launch's width (from the last batch on GPUs)
    std::vector<std::uint32_t> m_last_queue_lengths;  // wavefront: see last_queue_lengths()
    std::uint32_t m_last_queue_paths = 0;
    bool m_lengths_on_device = false;   // m_queue_lengths holds lengths not yet read

    cl::Buffer<glm::vec4> m_film;
    cl::Buffer<glm::vec4> m_film_squares;
    // Path integrator state (empty for the aov integrator).
    cl::Buffer<dev::GcRay> m_rays;
    cl::Buffer<dev::GcHit> m_hits;
    cl::Buffer<dev::GcPathState> m_paths;
    cl::Buffer<std::uint32_t> m_queue_a;
    cl::Buffer<std::uint32_t> m_queue_b;
    cl::Buffer<dev::GcShadowRay> m_shadow_rays;
    cl::Buffer<std::uint32_t> m_counters;
    cl::Buffer<std::uint32_t> m_queue_lengths;  // per depth: rays queued for the next, shadow rays

    cl::Kernel m_aov;
    cl::Kernel m_generate;
    cl::Kernel m_extend;
    cl::Kernel m_shade;
    cl::Kernel m_shadow;
    cl::Kernel m_accumulate;
    cl::Kernel m_whitted; // [whitted hook]
    cl::Kernel m_path_megakernel;
};

// The program file each integrator is built from.
// The path integrator's form on `device`: one kernel per path (megakernel.cl) on CPUs, the
// wavefront stages (wavefront.cl) on GPUs, unless `form` names one; both give the same bits
// on one device.
bool path_megakernel_for(const cl::DeviceInfo& device, PathKernelForm form = PathKernelForm::Auto);
const char* integrator_program(IntegratorKind kind, bool megakernel);

// Default paths in flight per pass: as many as a GPU's memory allows up to 2^24 (its passes'
// fixed costs shrink with each path added), 2^16 on CPUs (small enough for their caches).
inline constexpr std::uint32_t kGpuWavefrontPaths = 1u << 24;
inline constexpr std::uint32_t kCpuWavefrontPaths = 1u << 16;
// Device bytes a wavefront path slot takes: ray, hit, path state, two queue entries, shadow ray.
inline constexpr std::uint64_t kWavefrontBytesPerPath = sizeof(dev::GcRay) + sizeof(dev::GcHit) +
                                                        sizeof(dev::GcPathState) + 2 * sizeof(std::uint32_t) +
                                                        sizeof(dev::GcShadowRay);
std::uint32_t default_wavefront_size(const cl::DeviceInfo& device);

}  // namespace gc
