// A film and one integrator on a scene already on an OpenCL device. The caller owns the loop
// (render_loop.h runs one with a deadline and cancellation) and reads the film, as a mean or
// as per-pixel sums, whenever it wants.
//
//     auto scene = std::make_shared<DeviceScene>(DeviceScene::upload(context, host_scene, bvh, env));
//     Renderer renderer(context, scene, camera, settings);
//     renderer.render(0, 32);
//     renderer.render(32, 32);   // the same bits as render(0, 64)
//     Film image = renderer.film();
//
// Several renderers may share one device scene (the cross-check renders it with four
// integrators). The camera can change between renders, and the scene's materials
// (DeviceScene::update_materials): either restarts the film, without a new upload of the
// geometry and, unless the kernel features changed, without a new program.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gc_types.h"
#include "host/bvh/bvh.h"
#include "host/cl/context.h"
#include "host/image/film.h"
#include "host/render/device_scene.h"
#include "host/render/integrator.h"
#include "host/render/pass_planner.h"
#include "host/render/render_settings.h"
#include "host/render/render_setup.h"
#include "host/scene/scene.h"

namespace gc {

// A film's raw content: per pixel, row 0 at the top, the sums over its samples of the
// radiance (alpha: the number of samples, counted in float) and of its squares, and how many
// samples it holds.
struct FilmSums {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<glm::vec4> sums;
    std::vector<glm::vec4> squares;
    std::vector<std::uint32_t> sample_counts;
};

class Renderer {
public:
    // `scene` must have been uploaded to `context`'s device with the environment map that
    // settings.env_map_path names (UsageError otherwise). `setup` changes the speed and where
    // the kernels come from, never the image.
    Renderer(const cl::Context& context, std::shared_ptr<const DeviceScene> scene, const Camera& camera,
             const RenderSettings& settings, const RenderSetup& setup = {});
    // Uploads `scene`, and the environment map settings.env_map_path names, for this renderer
    // alone: for one-off renders and tests.
    Renderer(const cl::Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
             const RenderSettings& settings, const RenderSetup& setup = {});
    ~Renderer();

    // Adds samples [first_sample, first_sample + count) to every pixel, in as many passes as
    // the integrator plans. Ranges rendered one after the other give the same bits as one.
    void render(std::uint32_t first_sample, std::uint32_t count);

    // Adds between 1 and max_samples samples, from next_sample() on, to every pixel in one pass
    // (several kernel batches if the image is larger than the wavefront) and returns how many.
    // The path integrator traces several samples per pixel in one pass where that pays
    // (Integrator::max_samples_per_pass, PassPlanner). The image after n samples is the same
    // bits however they were grouped. Enqueues work and waits for it.
    std::uint32_t render_samples(std::uint32_t max_samples);
    void render_sample() { render_samples(1); }

    // Points the camera elsewhere; the film restarts.
    void set_camera(const Camera& camera);
    // Sets the constant environment's radiance (or the environment map's scale); the film restarts.
    void set_env_radiance(const glm::vec3& radiance);
    // The passes that follow render only `pixels` (indices y * width + x, strictly ascending;
    // UsageError otherwise, or for an integrator other than path); the others get no samples
    // and count none (sums()). Each listed pixel gets the bits it gets in a render of every
    // pixel. The film restarts at next_sample(). Adaptive sampling's rounds (adaptive.h).
    void select_pixels(std::vector<std::uint32_t> pixels);
    // Every pixel again (the default); the film restarts at next_sample().
    void select_all_pixels();
    // Empties the film; the next render_samples starts at sample `next_sample`.
    void clear(std::uint32_t next_sample = 0);

    // Samples each pixel of the film holds (each selected pixel: select_pixels), and the index
    // the next render_samples starts at. After a scene update, 0: the next render restarts the
    // film.
    std::uint32_t samples_done() const { return m_scene->revision == m_scene_revision ? m_sample_count : 0; }
    std::uint32_t next_sample() const { return m_next_sample; }
    // Whether the passes have reached their steady size (benchmarks time from there on).
    bool passes_settled() const { return !m_integrator->plans_passes_by_time() || m_planner.settled(); }
    // The last pass's seconds per sample (0 before the first): for a caller with a deadline.
    double seconds_per_sample() const { return m_planner.seconds_per_sample(); }
    // Estimates the seconds a pass takes per sample of the current pixels (all, or those
    // selected) from about `probe_pixels` of them, in runs spread evenly: one untimed sample
    // (a driver's first launch compiles), then kProbeSamples timed. Path integrator only
    // (UsageError otherwise). Leaves the pick of pixels, the pass plan and next_sample() as
    // they were and the film empty. For a device that must learn its rate without taking a
    // share of the frame's work first (multi_device.cpp).
    static constexpr std::uint32_t kProbeSamples = 4;
    double estimate_seconds_per_sample(std::uint32_t probe_pixels);
    // Pixels one work-item rendered in the last pass (gc_packet_lanes.h; 1 but for the BVH8
    // megakernel's camera packets).
    std::uint32_t pixels_per_item() const { return m_params.pixels_per_item; }
    // Pixels per kernel batch: the wavefront's size, or the image if it is smaller.
    std::uint32_t batch_pixels() const { return m_batch_pixels; }

    const Integrator& integrator() const { return *m_integrator; }
    const cl::Program& program() const { return m_integrator->program(); }
    const DeviceScene& device_scene() const { return *m_scene; }
    const RenderSettings& settings() const { return m_settings; }
    const Camera& camera() const { return m_camera; }
    const RenderSetup& setup() const { return m_setup; }
    const cl::Context& context() const { return m_context; }
    // The device scene, for another renderer of it (denoise_guides.h).
    std::shared_ptr<const DeviceScene> shared_scene() const { return m_scene; }

    // The mean of the samples so far, linear RGB, alpha 1.
    Film film() const;
    // Per-pixel sample variance of the samples so far (unbiased, n - 1 in the denominator):
    // what a Z-test against a reference needs. Path integrator only; zero elsewhere.
    Film variance() const;
    // The film's sums and sample counts, which add up across renders of disjoint ranges.
    // Without `with_squares`, `squares` stays empty (half the read-back: the multi-device
    // scheduler's chunks).
    FilmSums sums(bool with_squares = true) const;
    // Enqueues copies of the film's sums (and, where `squares` is given, of its squares) into
    // these device buffers of the film's size, after the work enqueued so far and before any
    // that follows, and returns the event of the last copy (the caller releases it) and, in
    // `header`, what sums() would return but the radiance arrays: width, height, sample
    // counts. The renderer can go on at once: the copies are the film as it is now.
    cl_event copy_sums(const cl::Buffer<glm::vec4>& sums, const cl::Buffer<glm::vec4>* squares,
                       FilmSums& header) const;

private:
    // Restarts the film and rebuilds what a scene update made stale.
    void follow_scene_updates();
    // The kernels' parameters from the scene, the camera and the settings (the per-pass
    // fields are set by render_samples).
    void update_params();
    // Per pixel, the samples the film holds: samples_done(), or 0 for a pixel not selected.
    std::vector<std::uint32_t> pixel_sample_counts() const;

    const cl::Context& m_context;
    std::shared_ptr<const DeviceScene> m_scene;
    std::uint64_t m_scene_revision;
    KernelFeatures m_program_features;  // the features m_integrator's program was built for
    RenderSettings m_settings;
    RenderSetup m_setup;
    Camera m_camera;
    dev::GcRenderParams m_params{};
    std::uint32_t m_batch_pixels = 0;
    std::unique_ptr<Integrator> m_integrator;
    PassPlanner m_planner;  // samples per pass where planned by time; pass times of any integrator
    FilmBuffers m_film;
    bool m_pixels_listed = false;              // select_pixels: only m_pixel_list renders
    std::vector<std::uint32_t> m_pixel_list;  // ascending; its copy is m_film.pixel_list
    std::uint32_t m_sample_count = 0;
    std::uint32_t m_next_sample = 0;
};

}  // namespace gc
