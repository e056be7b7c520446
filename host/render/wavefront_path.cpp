#include "host/render/wavefront_path.h"

#include <algorithm>
#include <optional>

#include "host/util/error.h"

namespace gc {
namespace {

// Work-items per compute unit in a GPU's launches after the first bounce, for the first batch
// (later ones are sized from the batch before: WavefrontLaunches), and the least predicted
// width, a work-group or so, so that a queue that grew since the last batch still spreads over
// the whole device (docs/decisions/wavefront-launch-sizing.md).
constexpr std::uint32_t kGpuFirstBatchItemsPerUnit = 4096;
constexpr std::uint32_t kLeastPredictedItemsPerUnit = 64;

WavefrontLaunches launches_for(const cl::DeviceInfo& device, std::uint32_t max_depth, const DeviceTuning& tuning)
{
    const std::uint32_t units = std::max<std::uint32_t>(device.compute_units, 1u);
    std::optional<std::uint32_t> fixed;
    if (tuning.wavefront_items_per_unit) fixed = *tuning.wavefront_items_per_unit * units;
    const std::uint32_t first = device.is_gpu ? kGpuFirstBatchItemsPerUnit * units : 0u;
    return WavefrontLaunches(max_depth, fixed, first, kLeastPredictedItemsPerUnit * units);
}

std::uint32_t path_capacity(const cl::DeviceInfo& device, const RenderSettings& settings, std::uint32_t batch_pixels)
{
    const std::uint32_t wavefront = settings.wavefront_size ? settings.wavefront_size : default_wavefront_size(device);
    const std::uint64_t pixels = std::uint64_t(settings.width) * std::uint64_t(settings.height);
    const std::uint64_t wanted = pixels * std::max<std::uint32_t>(settings.spp, 1u);
    return static_cast<std::uint32_t>(std::max<std::uint64_t>(batch_pixels, std::min<std::uint64_t>(wavefront, wanted)));
}

void zero_counters(const cl::Context& context, const cl::Buffer<std::uint32_t>& counters, std::uint32_t first,
                   std::uint32_t count)
{
    const std::uint32_t zero = 0;
    GC_CL_WHAT("resetting queue counters", clEnqueueFillBuffer, context.queue(), counters.mem(), &zero, sizeof zero,
               first * sizeof zero, count * sizeof zero, 0, nullptr, nullptr);
}

// Copies one queue counter into a slot of `lengths`, on the device (no host wait).
void copy_counter(const cl::Context& context, const cl::Buffer<std::uint32_t>& counters, std::uint32_t counter,
                  const cl::Buffer<std::uint32_t>& lengths, std::uint32_t slot)
{
    GC_CL_WHAT("copying a queue length", clEnqueueCopyBuffer, context.queue(), counters.mem(), lengths.mem(),
               counter * sizeof(std::uint32_t), slot * sizeof(std::uint32_t), sizeof(std::uint32_t), 0, nullptr, nullptr);
}

}  // namespace

std::uint32_t default_wavefront_size(const cl::DeviceInfo& device)
{
    if (!device.is_gpu) return kCpuWavefrontPaths;
    // Capped at an eighth of the device's memory and at its largest single buffer (the
    // shadow rays').
    std::uint64_t paths = kGpuWavefrontPaths;
    if (device.global_mem > 0) paths = std::min<std::uint64_t>(paths, device.global_mem / 8 / kWavefrontBytesPerPath);
    if (device.max_alloc > 0) paths = std::min<std::uint64_t>(paths, device.max_alloc / sizeof(dev::GcShadowRay));
    return static_cast<std::uint32_t>(std::max<std::uint64_t>(paths, kCpuWavefrontPaths));
}

WavefrontPathIntegrator::WavefrontPathIntegrator(const cl::Context& context, const DeviceScene& scene,
                                                 const RenderSettings& settings, const RenderSetup& setup,
                                                 std::uint32_t batch_pixels)
    : m_context(context),
      m_batch_pixels(batch_pixels),
      m_path_capacity(path_capacity(context.device(), settings, batch_pixels)),
      m_max_depth(settings.max_depth),
      // On CPUs (PoCL) the host reads the queue counters back after each shade launch and
      // launches the next stages over the live paths only, stopping once none is left: an
      // early-returning work-item still costs PoCL a trip through its work-group loop, and
      // reading four uints from host memory is nearly free there. GPUs keep launching without
      // a read-back (the pbrt-v4 scheme), since a blocking read per bounce would stall the
      // queue, and size the launches from the last batch instead.
      m_sync_counts(setup.tuning.wavefront_sync_counts.value_or(!context.device().is_gpu)),
      m_launches(launches_for(context.device(), settings.max_depth, setup.tuning)),
      m_last_queue_lengths(2 * std::size_t{settings.max_depth}, 0u),
      m_program(context, "wavefront.cl", scene_program_options(scene), setup.build)
{
    m_rays = cl::Buffer<dev::GcRay>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "path rays");
    // An instanced scene's hits carry their instance (GcInstanceHit, gc_scene_trace.h).
    if (scene.instanced())
        m_instance_hits = cl::Buffer<dev::GcInstanceHit>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "path hits");
    else
        m_hits = cl::Buffer<dev::GcHit>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "path hits");
    m_paths = cl::Buffer<dev::GcPathState>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "path state");
    m_queue_a = cl::Buffer<std::uint32_t>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "ray queue A");
    m_queue_b = cl::Buffer<std::uint32_t>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "ray queue B");
    m_shadow_rays = cl::Buffer<dev::GcShadowRay>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "shadow rays");
    m_counters = cl::Buffer<std::uint32_t>::create(context, GC_COUNTER_COUNT, CL_MEM_READ_WRITE, "queue counters");
    m_queue_lengths = cl::Buffer<std::uint32_t>::create(context, 2 * std::size_t{std::max(m_max_depth, 1u)},
                                                        CL_MEM_READ_WRITE, "queue lengths per depth");
    m_generate = m_program.kernel("generate");
    m_extend = m_program.kernel("extend");
    m_shade = m_program.kernel("shade");
    m_shadow = m_program.kernel("shadow");
    m_accumulate = m_program.kernel("accumulate");
}

std::uint32_t WavefrontPathIntegrator::max_samples_per_pass(std::uint32_t pixels) const
{
    // On a GPU, an image smaller than the wavefront would leave most of it idle and pay a
    // pass's launches for few paths, so the wavefront is filled with samples.
    if (pixels == 0 || pixels > m_batch_pixels) return 1;
    return std::max(1u, m_path_capacity / pixels);
}

void WavefrontPathIntegrator::render_batch(const dev::GcRenderParams& params, const DeviceScene& scene,
                                           const FilmBuffers& film)
{
    const std::uint32_t n = params.pixel_count * params.samples_in_pass;
    zero_counters(m_context, m_counters, 0, GC_COUNTER_COUNT);
    m_generate.set_args(params, m_rays, m_paths, m_queue_a, m_counters, film.pixel_list);
    m_generate.launch(m_context, n, 0, "camera rays");

    std::uint32_t live = n;
    // Each depth's queue lengths: read back on CPUs as the batch runs; on GPUs copied aside on
    // the device and read after the pass (end_pass), to size the next batch's launches.
    // Without read-backs every depth runs, so the batch leaves a length for each of them.
    m_last_queue_lengths.assign(2 * std::size_t{m_max_depth}, 0u);
    m_last_queue_paths = n;
    m_lengths_on_device = !m_sync_counts;
    const cl_mem hits = scene.instanced() ? m_instance_hits.mem() : m_hits.mem();
    set_scene_kernel_args(m_shadow, params, scene, scene.bvh_args(), m_shadow_rays, m_paths, m_counters);
    bool a_is_input = true;
    for (std::uint32_t depth = 0; depth < params.max_depth && live > 0; ++depth) {
        const std::uint32_t ray_width = m_launches.ray_width(depth, n);
        const cl::Buffer<std::uint32_t>& queue_in = a_is_input ? m_queue_a : m_queue_b;
        const cl::Buffer<std::uint32_t>& queue_out = a_is_input ? m_queue_b : m_queue_a;
        const std::uint32_t counter_in = a_is_input ? GC_COUNTER_RAYS_A : GC_COUNTER_RAYS_B;
        const std::uint32_t counter_out = a_is_input ? GC_COUNTER_RAYS_B : GC_COUNTER_RAYS_A;
        zero_counters(m_context, m_counters, counter_out, 1);
        zero_counters(m_context, m_counters, GC_COUNTER_SHADOW, 1);

        set_scene_kernel_args(m_extend, params, scene, scene.bvh_args(), m_rays, hits, queue_in, m_counters, counter_in);
        m_extend.launch(m_context, wavefront_launch_size(live, ray_width), 0, "closest-hit rays");
        set_scene_kernel_args(m_shade, params, scene, scene.shade_args(), m_rays, hits, m_paths, queue_in, queue_out,
                              m_shadow_rays, m_counters, counter_in, counter_out);
        m_shade.launch(m_context, wavefront_launch_size(live, ray_width), 0, "shading");
        std::uint32_t shadows = n;
        if (m_sync_counts) {
            std::uint32_t counts[GC_COUNTER_COUNT];
            m_counters.read(counts);
            shadows = counts[GC_COUNTER_SHADOW];
            live = counts[counter_out];
            m_last_queue_lengths[2 * depth] = live;
            m_last_queue_lengths[2 * depth + 1] = shadows;
        } else {
            copy_counter(m_context, m_counters, counter_out, m_queue_lengths, 2 * depth);
            copy_counter(m_context, m_counters, GC_COUNTER_SHADOW, m_queue_lengths, 2 * depth + 1);
        }
        m_shadow.launch(m_context, wavefront_launch_size(shadows, m_launches.shadow_width(depth, n)), 0, "shadow rays");
        a_is_input = !a_is_input;
    }
    m_accumulate.set_args(params, m_paths, film.sums, film.squares);
    m_accumulate.launch(m_context, params.pixel_count, 0, "film accumulation");
}

void WavefrontPathIntegrator::end_pass()
{
    if (!m_lengths_on_device) return;
    // The queues' lengths of the pass's last batch, copied on the device as it ran: reading
    // them once the queue is drained costs one small transfer a pass, and no stall.
    m_queue_lengths.read(std::span<std::uint32_t>(m_last_queue_lengths));
    m_launches.record(m_last_queue_lengths, m_last_queue_paths);
    m_lengths_on_device = false;
}

}  // namespace gc
