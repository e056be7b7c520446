// One integrator's kernels on one device, as a Renderer drives them: the Renderer owns the
// film, the camera and the sample count, and asks its integrator, pass by pass, to add samples
// to a batch of pixels. One class per integrator:
//
//     AovIntegrator             aov.cl, first-hit AOVs (pixel_integrators.h)
//     WhittedIntegrator         whitted.cl, Whitted ray trees (pixel_integrators.h)
//     MegakernelPathIntegrator  megakernel.cl, one work-item per path (megakernel_path.h)
//     WavefrontPathIntegrator   wavefront.cl, one launch per stage and bounce (wavefront_path.h)
//
// The two path integrators run the same shared code (kernels/shared/gc_shade_vertex.h) and
// give the same bits on one device; make_integrator picks the form for the device.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "gc_types.h"
#include "host/cl/buffer.h"
#include "host/cl/context.h"
#include "host/cl/kernel.h"
#include "host/cl/program.h"
#include "host/render/device_scene.h"
#include "host/render/render_settings.h"
#include "host/render/render_setup.h"

namespace gc {

// The film's device buffers, one entry per pixel: the sums of the samples' radiance and of
// its squares (for the variance). Integrators add to them, in sample order per pixel.
// `pixel_list` names the pixels a pass renders when params.flags has GC_RENDER_PIXEL_LIST
// (the path integrator's; Renderer::select_pixels); kernels take it either way.
struct FilmBuffers {
    cl::Buffer<glm::vec4> sums;
    cl::Buffer<glm::vec4> squares;
    cl::Buffer<std::uint32_t> pixel_list;
};

class Integrator {
public:
    virtual ~Integrator() = default;

    virtual const cl::Program& program() const = 0;

    // Whether a pass's sample count follows measured pass times (PassPlanner) rather than
    // max_samples_per_pass.
    virtual bool plans_passes_by_time() const { return false; }
    // The most samples of each pixel one pass may trace for an image of `pixels` pixels.
    virtual std::uint32_t max_samples_per_pass(std::uint32_t /*pixels*/) const { return 1; }

    // Sets the pass-wide parameters the integrator decides (params.samples_in_pass is set).
    virtual void begin_pass(dev::GcRenderParams& /*params*/) {}
    // Enqueues the work that adds params.samples_in_pass samples, from params.sample_index on,
    // to the pixels [params.pixel_offset, + params.pixel_count), or to those entries of
    // film.pixel_list (GC_RENDER_PIXEL_LIST).
    virtual void render_batch(const dev::GcRenderParams& params, const DeviceScene& scene,
                              const FilmBuffers& film) = 0;
    // Called once the device has finished the pass's batches.
    virtual void end_pass() {}
};

// The integrator `settings` names, for `scene` on `context`'s device. `batch_pixels` is the
// most pixels one batch covers (Renderer: the wavefront's size, capped by the image).
std::unique_ptr<Integrator> make_integrator(const cl::Context& context, const DeviceScene& scene,
                                            const RenderSettings& settings, const RenderSetup& setup,
                                            std::uint32_t batch_pixels);

// The path integrator's form on `device`: one kernel per path (megakernel.cl) on CPUs, the
// wavefront stages (wavefront.cl) on GPUs, unless `form` names one; both give the same bits
// on one device.
bool path_megakernel_for(const cl::DeviceInfo& device, PathKernelForm form = PathKernelForm::Auto);

// Sets a scene kernel's arguments: `params`, then an instanced scene's instance buffers
// (GC_INSTANCES_FIRST_PARAMS, gc_scene_trace.h), then `args`.
template <class... Args>
void set_scene_kernel_args(cl::Kernel& kernel, const dev::GcRenderParams& params, const DeviceScene& scene,
                           const Args&... args)
{
    if (scene.instanced()) kernel.set_args(params, scene.instance_args(), args...);
    else kernel.set_args(params, args...);
}

// The compile options every program of `scene` is built with: its BVH layout and features.
std::string scene_program_options(const DeviceScene& scene);

}  // namespace gc
