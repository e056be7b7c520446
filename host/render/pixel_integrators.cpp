#include "host/render/pixel_integrators.h"

namespace gc {

PixelKernelIntegrator::PixelKernelIntegrator(const cl::Context& context, const DeviceScene& scene,
                                             const RenderSetup& setup, const char* file, const char* kernel,
                                             const char* what)
    : m_context(context),
      m_program(context, file, scene_program_options(scene), setup.build),
      m_kernel(m_program.kernel(kernel)),
      m_what(what)
{
}

void PixelKernelIntegrator::render_batch(const dev::GcRenderParams& params, const DeviceScene& scene,
                                         const FilmBuffers& film)
{
    set_scene_kernel_args(m_kernel, params, scene, scene.scene_args(), film.sums);
    m_kernel.launch(m_context, params.pixel_count, 0, m_what);
}

}  // namespace gc
