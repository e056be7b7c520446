// The path integrator as wavefront stages (kernels/wavefront.cl), the form GPUs use: each pass
// generates camera rays for its path slots, then for each bounce launches extend (closest
// hits), shade (one vertex: emission, light sample, next direction) and shadow (the light
// samples' visibility) over queues of live paths, and finally accumulates the paths into the
// film in sample order. Every slot gets the same work whatever the launch widths, so the image
// is the megakernel's bits.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "gc_instance.h"
#include "host/cl/kernel.h"
#include "host/render/integrator.h"
#include "host/render/wavefront_launches.h"

namespace gc {

class WavefrontPathIntegrator : public Integrator {
public:
    // `batch_pixels`: pixels per batch. The path slots hold a whole wavefront when the image
    // is smaller than it and several samples are asked for, so a pass can trace them at once.
    WavefrontPathIntegrator(const cl::Context& context, const DeviceScene& scene, const RenderSettings& settings,
                            const RenderSetup& setup, std::uint32_t batch_pixels);

    const cl::Program& program() const override { return m_program; }
    std::uint32_t max_samples_per_pass(std::uint32_t pixels) const override;
    void render_batch(const dev::GcRenderParams& params, const DeviceScene& scene, const FilmBuffers& film) override;
    void end_pass() override;

    // The queue lengths of the last pass's last batch: for each depth the rays it queued for
    // the next one and its shadow rays (2 x max_depth values; zeros before the first pass and
    // past the depth where every path ended).
    std::span<const std::uint32_t> last_queue_lengths() const { return m_last_queue_lengths; }
    // The path states of the last batch: slot p * samples_in_pass + s holds sample s of the
    // batch's pixel p (generate.cl), its radiance final once the batch has run. The adjoint
    // reads each sample's radiance there (gradients.h, PrimalPass).
    const cl::Buffer<dev::GcPathState>& paths() const { return m_paths; }

private:
    const cl::Context& m_context;
    std::uint32_t m_batch_pixels;
    std::uint32_t m_path_capacity;  // >= m_batch_pixels
    std::uint32_t m_max_depth;
    bool m_sync_counts;             // the host reads each bounce's queue lengths back (CPUs)
    WavefrontLaunches m_launches;   // each launch's width (from the last batch on GPUs)
    std::vector<std::uint32_t> m_last_queue_lengths;
    std::uint32_t m_last_queue_paths = 0;
    bool m_lengths_on_device = false;  // m_queue_lengths holds lengths not yet read

    cl::Program m_program;
    cl::Buffer<dev::GcRay> m_rays;
    cl::Buffer<dev::GcHit> m_hits;                   // a flat scene's
    cl::Buffer<dev::GcInstanceHit> m_instance_hits;  // an instanced scene's
    cl::Buffer<dev::GcPathState> m_paths;
    cl::Buffer<std::uint32_t> m_queue_a;
    cl::Buffer<std::uint32_t> m_queue_b;
    cl::Buffer<dev::GcShadowRay> m_shadow_rays;
    cl::Buffer<std::uint32_t> m_counters;
    cl::Buffer<std::uint32_t> m_queue_lengths;  // per depth: rays queued for the next, shadow rays
    cl::Kernel m_generate;
    cl::Kernel m_extend;
    cl::Kernel m_shade;
    cl::Kernel m_shadow;
    cl::Kernel m_accumulate;
};

// Default paths in flight per pass: as many as a GPU's memory allows up to 2^24 (its passes'
// fixed costs shrink with each path added: docs/decisions/wavefront-paths-per-pass.md), 2^16 on
// CPUs (small enough for their caches).
inline constexpr std::uint32_t kGpuWavefrontPaths = 1u << 24;
inline constexpr std::uint32_t kCpuWavefrontPaths = 1u << 16;
// Device bytes a wavefront path slot takes: ray, hit, path state, two queue entries, shadow ray.
inline constexpr std::uint64_t kWavefrontBytesPerPath = sizeof(dev::GcRay) + sizeof(dev::GcHit) +
                                                        sizeof(dev::GcPathState) + 2 * sizeof(std::uint32_t) +
                                                        sizeof(dev::GcShadowRay);
std::uint32_t default_wavefront_size(const cl::DeviceInfo& device);

}  // namespace gc
