#include "host/render/megakernel_path.h"

#include "gc_packet_lanes.h"

namespace gc {
namespace {

// The work-group size. On CPUs, 1: PoCL gives every work-item of a group its own copy of the
// private arrays (traversal stack, path state), so a large group spreads them beyond L1 while
// one long-running item per group keeps them there (docs/decisions/cpu-pass-length.md).
// GPUs keep the context's size.
std::size_t local_size(const cl::Context& context) { return context.device().is_gpu ? 0 : 1; }

}  // namespace

MegakernelPathIntegrator::MegakernelPathIntegrator(const cl::Context& context, const DeviceScene& scene,
                                                   const RenderSetup& setup)
    : m_context(context),
      m_camera_packets(scene.bvh.layout() == BvhLayout::Wide8 && !scene.instanced()),
      m_program(context, "megakernel.cl", scene_program_options(scene), setup.build),
      m_kernel(m_program.kernel("path_megakernel"))
{
}

void MegakernelPathIntegrator::begin_pass(dev::GcRenderParams& params)
{
    // Where a pass has too few samples to fill a camera-ray packet, a work-item takes
    // neighbouring pixels too.
    params.pixels_per_item = m_camera_packets ? dev::gc_megakernel_pixels_per_item(params.samples_in_pass) : 1u;
}

void MegakernelPathIntegrator::render_batch(const dev::GcRenderParams& params, const DeviceScene& scene,
                                            const FilmBuffers& film)
{
    set_scene_kernel_args(m_kernel, params, scene, scene.scene_args(), film.sums, film.squares, film.pixel_list);
    const std::uint32_t items = (params.pixel_count + params.pixels_per_item - 1) / params.pixels_per_item;
    m_kernel.launch(m_context, items, local_size(m_context), "paths (megakernel)");
}

}  // namespace gc
