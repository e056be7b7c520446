#include "host/render/integrator.h"

#include "host/render/megakernel_path.h"
#include "host/render/pixel_integrators.h"
#include "host/render/wavefront_path.h"

namespace gc {

bool path_megakernel_for(const cl::DeviceInfo& device, PathKernelForm form)
{
    switch (form) {
    case PathKernelForm::Wavefront: return false;
    case PathKernelForm::Megakernel: return true;
    case PathKernelForm::Auto: break;
    }
    return !device.is_gpu;
}

std::string scene_program_options(const DeviceScene& scene)
{
    return program_options(scene.bvh.layout()) + " " + program_options(scene.features) +
           (scene.instanced() ? " -D GC_SCENE_INSTANCED" : "");
}

std::unique_ptr<Integrator> make_integrator(const cl::Context& context, const DeviceScene& scene,
                                            const RenderSettings& settings, const RenderSetup& setup,
                                            std::uint32_t batch_pixels)
{
    switch (settings.integrator) {
    case IntegratorKind::Aov: return std::make_unique<AovIntegrator>(context, scene, setup);
    case IntegratorKind::Whitted: return std::make_unique<WhittedIntegrator>(context, scene, setup);
    case IntegratorKind::Path: break;
    }
    if (path_megakernel_for(context.device(), setup.tuning.path_kernel))
        return std::make_unique<MegakernelPathIntegrator>(context, scene, setup);
    return std::make_unique<WavefrontPathIntegrator>(context, scene, settings, setup, batch_pixels);
}

}  // namespace gc
