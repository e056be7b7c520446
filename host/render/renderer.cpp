#include "host/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "gc_packet_lanes.h"
#include "host/render/environment.h"
#include "host/render/scene_convert.h"
#include "host/util/error.h"

namespace gc {
namespace {

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

// The megakernel's work-group size. On CPUs, 1: PoCL gives every work-item of a group its own
// copy of the private arrays (traversal stack, path state), so a group of 128 spreads them
// over ~200 KB; one long-running item per group keeps them in L1. H200 box, PoCL 5 on 16
// cores, Cornell 512^2 path, medians of 3 x 5: local 128 5.55, 16 6.04, 4 6.54, 1 6.76
// Msamples/s; the dragon 320x240 is flat (26.6 / 26.7 / 27.0 / 26.3). GPUs keep the
// context's size.
std::size_t megakernel_local_size(const cl::Context& context)
{
    if (context.device().is_gpu) return 0;  // 0: the context's default
    return 1;
}

// Work-items per compute unit in a GPU's wavefront launches after the first bounce, for the
// first batch (later ones are sized from the batch before: WavefrontLaunches). H200, path
// samples/s against one work-item per queue entry, 2^20 paths, 2 rounds (Cornell box / dragon /
// 5.2M triangles): 4096 per unit 1.01x / 1.06x / 1.01x; 2048 1.00x / 1.07x / 0.99x; 8192 1.00x /
// 0.99x / 1.01x.
constexpr std::uint32_t kGpuFirstBatchItemsPerUnit = 4096;
// The least predicted width per compute unit: a work-group or so, so that a queue that grew
// since the last batch still spreads over the whole device.
constexpr std::uint32_t kLeastPredictedItemsPerUnit = 64;

// GPUs size each launch after the first bounce from the last batch's queue lengths. H200, 2^24
// paths per pass, path samples/s, 3 interleaved rounds (Cornell box / dragon / 5.2M triangles):
// against 4096 work-items per unit on every batch 1.024x / 1.018x / 1.114x, against one per
// queue entry 1.061x / 1.201x / 1.026x. DeviceTuning::wavefront_items_per_unit fixes the width
// instead, on any device. CPUs read the lengths back (run_path_batch), so one per entry is exact.
WavefrontLaunches wavefront_launches(const cl::DeviceInfo& device, std::uint32_t max_depth,
                                     const DeviceTuning& tuning)
{
    const std::uint32_t units = std::max<std::uint32_t>(device.compute_units, 1u);
    std::optional<std::uint32_t> fixed;
    if (tuning.wavefront_items_per_unit) fixed = *tuning.wavefront_items_per_unit * units;
    const std::uint32_t first = device.is_gpu ? kGpuFirstBatchItemsPerUnit * units : 0u;
    return WavefrontLaunches(max_depth, fixed, first, kLeastPredictedItemsPerUnit * units);
}

}  // namespace

bool path_megakernel_for(const cl::DeviceInfo& device, PathKernelForm form)
{
    switch (form) {
    case PathKernelForm::Wavefront: return false;
    case PathKernelForm::Megakernel: return true;
    case PathKernelForm::Auto: break;
    }
    return !device.is_gpu;
}

const char* integrator_program(IntegratorKind kind, bool megakernel)
{
    switch (kind) {
    case IntegratorKind::Aov: return "aov.cl";
    case IntegratorKind::Path: return megakernel ? "megakernel.cl" : "wavefront.cl";
    case IntegratorKind::Whitted: return "whitted.cl";
    }
    return "aov.cl";
}

std::uint32_t default_wavefront_size(const cl::DeviceInfo& device)
{
    if (!device.is_gpu) return kCpuWavefrontPaths;
    // A GPU pass pays, most likely, for its launches' tails, where a few long paths hold the
    // device while the rest of it waits, and for the round trip at its end: the more paths
    // share them, the less each pays. H200, path samples/s against 2^20 paths (2 rounds, Cornell box 512x512 /
    // dragon 320x240 / 5.2M triangles 512x512): 2^22 1.16x / 2.22x / 1.68x, 2^23 1.20x /
    // 2.38x / 1.89x, 2^24 1.22x / 2.37x / 1.99x (the dragon's 64 samples fit one pass from
    // 2^23). At 168 bytes a path, 2^24 take 2.8 GB: capped at an eighth of the device's memory
    // and at its largest single buffer (the shadow rays').
    std::uint64_t paths = kGpuWavefrontPaths;
    if (device.global_mem > 0) paths = std::min<std::uint64_t>(paths, device.global_mem / 8 / kWavefrontBytesPerPath);
    if (device.max_alloc > 0) paths = std::min<std::uint64_t>(paths, device.max_alloc / sizeof(dev::GcShadowRay));
    return static_cast<std::uint32_t>(std::max<std::uint64_t>(paths, kCpuWavefrontPaths));
}

Renderer::Renderer(const cl::Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
                   const RenderSettings& settings, const RenderSetup& setup)
    : m_context(context),
      m_settings(settings),
      m_scene(DeviceScene::upload(context, scene, bvh, load_environment_map(settings), setup.tuning)),
      m_megakernel(settings.integrator == IntegratorKind::Path &&
                   path_megakernel_for(context.device(), setup.tuning.path_kernel)),
      m_program(context, integrator_program(settings.integrator, m_megakernel),
                program_options(m_scene.bvh.layout()) + " " + program_options(m_scene.features), setup.build),
      m_planner(settings.samples_per_pass),
      m_launches(wavefront_launches(context.device(), settings.max_depth, setup.tuning))
{
    // On CPUs (PoCL) the host reads the queue counters back after each shade pass and launches
    // the next stages over the live paths only, stopping once none is left: an early-returning
    // work-item still costs PoCL a trip through its work-group loop, and reading four uints
    // from host memory is nearly free there. GPUs keep launching without a read-back (the
    // pbrt-v4 scheme), since a blocking read per bounce would stall the queue (0.93x on an
    // H200), and size the launches from the last batch instead (m_launches). Either way every
    // slot gets the same work, so the image is the same bits. DeviceTuning can fix the choice.
    m_sync_counts = setup.tuning.wavefront_sync_counts.value_or(!context.device().is_gpu);

    const std::uint32_t pixels = static_cast<std::uint32_t>(settings.width) * static_cast<std::uint32_t>(settings.height);
    const std::uint32_t wavefront = settings.wavefront_size ? settings.wavefront_size : default_wavefront_size(context.device());
    m_batch = std::min(pixels, wavefront);
    // Path slots: a whole wavefront when the image is smaller than it and several samples are
    // asked for, so render_samples can trace them in one pass.
    const std::uint64_t wanted = std::uint64_t{pixels} * std::max<std::uint32_t>(settings.spp, 1u);
    m_path_capacity = static_cast<std::uint32_t>(std::max<std::uint64_t>(m_batch, std::min<std::uint64_t>(wavefront, wanted)));

    m_params = make_render_params(scene, camera, settings);
    set_environment_map(m_params, settings, m_scene.env_width, m_scene.env_height);

    m_film = cl::Buffer<glm::vec4>::create(context, pixels, CL_MEM_READ_WRITE, "film");
    const glm::vec4 zero(0.0f);
    m_film_squares = cl::Buffer<glm::vec4>::create(context, pixels, CL_MEM_READ_WRITE, "film squares");
    for (const cl::Buffer<glm::vec4>* film : {&m_film, &m_film_squares})
        GC_CL_WHAT("clearing the film", clEnqueueFillBuffer, context.queue(), film->mem(), &zero, sizeof zero, 0,
                   film->bytes(), 0, nullptr, nullptr);

    if (settings.integrator == IntegratorKind::Aov) {
        m_aov = m_program.kernel("aov_render");
    } else if (settings.integrator == IntegratorKind::Path && m_megakernel) {
        m_path_megakernel = m_program.kernel("path_megakernel");
    } else if (settings.integrator == IntegratorKind::Path) {
        m_rays = cl::Buffer<dev::GcRay>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "path rays");
        m_hits = cl::Buffer<dev::GcHit>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "path hits");
        m_paths = cl::Buffer<dev::GcPathState>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "path state");
        m_queue_a = cl::Buffer<std::uint32_t>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "ray queue A");
        m_queue_b = cl::Buffer<std::uint32_t>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "ray queue B");
        m_shadow_rays = cl::Buffer<dev::GcShadowRay>::create(context, m_path_capacity, CL_MEM_READ_WRITE, "shadow rays");
        m_counters = cl::Buffer<std::uint32_t>::create(context, GC_COUNTER_COUNT, CL_MEM_READ_WRITE, "queue counters");
        m_queue_lengths = cl::Buffer<std::uint32_t>::create(context, 2 * std::size_t{std::max(m_params.max_depth, 1u)},
                                                            CL_MEM_READ_WRITE, "queue lengths per depth");
        m_last_queue_lengths.assign(2 * std::size_t{m_params.max_depth}, 0u);
        m_generate = m_program.kernel("generate");
        m_extend = m_program.kernel("extend");
        m_shade = m_program.kernel("shade");
        m_shadow = m_program.kernel("shadow");
        m_accumulate = m_program.kernel("accumulate");
    } else if (settings.integrator == IntegratorKind::Whitted) {
        m_whitted = m_program.kernel("whitted_render"); // [whitted hook]
    } else {
        throw UsageError(std::string("the ") + integrator_name(settings.integrator) + " integrator is not available yet");
    }
}

std::uint32_t Renderer::render_samples(std::uint32_t max_samples)
{
    const std::uint32_t pixels = m_params.width * m_params.height;
    // The path integrator traces several samples of every pixel in one pass where that pays.
    // On a GPU, an image smaller than the wavefront would leave most of it idle and pay the ~30
    // launches of a pass for few paths, so the wavefront is filled with samples. On a CPU, a
    // megakernel work-item runs its pixel's samples back to back, which keeps that pixel's part
    // of the scene in the core's caches; the planner sizes the pass (pass_planner.h). Every
    // form's pass time is recorded, for callers with a deadline (seconds_per_sample).
    // accumulate.cl and the megakernel add each pixel's samples in sample order, so the image
    // is the same bits as one sample per pass.
    std::uint32_t samples = 1;
    if (m_megakernel) {
        samples = m_planner.next(max_samples);
    } else if (m_settings.integrator == IntegratorKind::Path && pixels <= m_batch) {
        samples = std::max(1u, std::min(max_samples, m_path_capacity / pixels));
        if (m_settings.samples_per_pass != 0) samples = std::min(samples, m_settings.samples_per_pass);
    }
    const auto start = std::chrono::steady_clock::now();
    m_params.sample_index = m_samples;
    m_params.samples_in_pass = samples;
    // The megakernel's camera-ray packets exist on the BVH8 only (gc_packet8.h); where a pass
    // has too few samples to fill them, a work-item takes neighbouring pixels too.
    const bool camera_packets = m_megakernel && m_scene.bvh.layout() == BvhLayout::Wide8;
    m_params.pixels_per_item = camera_packets ? dev::gc_megakernel_pixels_per_item(samples) : 1u;
    for (std::uint32_t offset = 0; offset < pixels; offset += m_batch) {
        m_params.pixel_offset = offset;
        m_params.pixel_count = std::min(m_batch, pixels - offset);
        if (m_settings.integrator == IntegratorKind::Aov) run_aov_batch();
        else if (m_settings.integrator == IntegratorKind::Whitted) run_whitted_batch(); // [whitted hook]
        else if (m_megakernel) run_megakernel_batch();
        else run_path_batch();
    }
    m_context.finish();
    if (m_lengths_on_device) {
        // The queues' lengths of the pass's last batch, copied on the device as it ran: reading
        // them once the queue is drained costs one small transfer a pass, and no stall.
        m_queue_lengths.read(std::span<std::uint32_t>(m_last_queue_lengths));
        m_launches.record(m_last_queue_lengths, m_last_queue_paths);
        m_lengths_on_device = false;
    }
    m_planner.record(samples, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    m_samples += samples;
    return samples;
}

void Renderer::run_aov_batch()
{
    m_aov.set_args(m_params, m_scene.scene_args(), m_film);
    m_aov.launch(m_context, m_params.pixel_count, 0, "first-hit AOVs");
}

// [whitted hook] One work-item per pixel of the batch, like run_aov_batch.
void Renderer::run_whitted_batch()
{
    m_whitted.set_args(m_params, m_scene.scene_args(), m_film);
    m_whitted.launch(m_context, m_params.pixel_count, 0, "Whitted ray trees");
}

// One work-item per pixel of the batch (or per few neighbours: gc_packet_lanes.h) runs its
// samples of the pass from camera to end.
void Renderer::run_megakernel_batch()
{
    m_path_megakernel.set_args(m_params, m_scene.scene_args(), m_film, m_film_squares);
    const std::uint32_t items = (m_params.pixel_count + m_params.pixels_per_item - 1) / m_params.pixels_per_item;
    m_path_megakernel.launch(m_context, items, megakernel_local_size(m_context), "paths (megakernel)");
}

void Renderer::run_path_batch()
{
    const std::uint32_t n = m_params.pixel_count * m_params.samples_in_pass;
    zero_counters(m_context, m_counters, 0, GC_COUNTER_COUNT);
    m_generate.set_args(m_params, m_rays, m_paths, m_queue_a, m_counters);
    m_generate.launch(m_context, n, 0, "camera rays");

    std::uint32_t live = n;
    // Each depth's queue lengths: read back on CPUs as the batch runs; on GPUs copied aside on
    // the device and read after the pass (render_samples), to size the next batch's launches.
    // Without read-backs every depth runs, so the batch leaves a length for each of them.
    m_last_queue_lengths.assign(2 * std::size_t{m_params.max_depth}, 0u);
    m_last_queue_paths = n;
    m_lengths_on_device = !m_sync_counts;
    m_shadow.set_args(m_params, m_scene.bvh_args(), m_shadow_rays, m_paths, m_counters);
    bool a_is_input = true;
    for (std::uint32_t depth = 0; depth < m_params.max_depth && live > 0; ++depth) {
        const std::uint32_t ray_width = m_launches.ray_width(depth, n);
        const cl::Buffer<std::uint32_t>& queue_in = a_is_input ? m_queue_a : m_queue_b;
        const cl::Buffer<std::uint32_t>& queue_out = a_is_input ? m_queue_b : m_queue_a;
        const std::uint32_t counter_in = a_is_input ? GC_COUNTER_RAYS_A : GC_COUNTER_RAYS_B;
        const std::uint32_t counter_out = a_is_input ? GC_COUNTER_RAYS_B : GC_COUNTER_RAYS_A;
        zero_counters(m_context, m_counters, counter_out, 1);
        zero_counters(m_context, m_counters, GC_COUNTER_SHADOW, 1);

        m_extend.set_args(m_params, m_scene.bvh_args(), m_rays, m_hits, queue_in, m_counters, counter_in);
        m_extend.launch(m_context, wavefront_launch_size(live, ray_width), 0, "closest-hit rays");
        m_shade.set_args(m_params, m_scene.shade_args(), m_rays, m_hits, m_paths, queue_in, queue_out, m_shadow_rays,
                         m_counters, counter_in, counter_out);
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
    m_accumulate.set_args(m_params, m_paths, m_film, m_film_squares);
    m_accumulate.launch(m_context, m_params.pixel_count, 0, "film accumulation");
}

Film Renderer::film() const
{
    const std::size_t pixels = m_film.count();
    std::vector<glm::vec4> sums(pixels);
    m_film.read(sums);
    Film film(m_params.width, m_params.height);
    const float inv = m_samples > 0 ? 1.0f / static_cast<float>(m_samples) : 0.0f;
    for (std::size_t i = 0; i < pixels; ++i) {
        const std::uint32_t x = static_cast<std::uint32_t>(i % m_params.width);
        const std::uint32_t y = static_cast<std::uint32_t>(i / m_params.width);
        film.set(x, y, Rgba{sums[i].x * inv, sums[i].y * inv, sums[i].z * inv, 1.0f});
    }
    return film;
}

Film Renderer::variance() const
{
    const std::size_t pixels = m_film.count();
    std::vector<glm::vec4> sums(pixels), squares(pixels);
    m_film.read(sums);
    m_film_squares.read(squares);
    Film film(m_params.width, m_params.height);
    const double n = m_samples;
    for (std::size_t i = 0; i < pixels; ++i) {
        float v[3] = {0, 0, 0};
        if (n > 1) {
            for (int c = 0; c < 3; ++c) {
                const double mean = sums[i][c] / n;
                v[c] = static_cast<float>(std::max(0.0, (squares[i][c] / n - mean * mean) * n / (n - 1)));
            }
        }
        film.set(static_cast<std::uint32_t>(i % m_params.width), static_cast<std::uint32_t>(i / m_params.width),
                 Rgba{v[0], v[1], v[2], 1.0f});
    }
    return film;
}

}  // namespace gc
