// The integrators that give each pixel one work-item per pass and one sample per pass: the
// first-hit AOVs and the Whitted ray trees.
#pragma once

#include "host/cl/kernel.h"
#include "host/render/integrator.h"

namespace gc {

// One kernel, one work-item per pixel of the batch.
class PixelKernelIntegrator : public Integrator {
public:
    const cl::Program& program() const override { return m_program; }
    void render_batch(const dev::GcRenderParams& params, const DeviceScene& scene, const FilmBuffers& film) override;

protected:
    // `what` names the launch in errors.
    PixelKernelIntegrator(const cl::Context& context, const DeviceScene& scene, const RenderSetup& setup,
                          const char* file, const char* kernel, const char* what);

private:
    const cl::Context& m_context;
    cl::Program m_program;
    cl::Kernel m_kernel;
    const char* m_what;
};

// aov.cl: albedo, normals, depth, primitive ids or a preview shading of the first hit.
class AovIntegrator : public PixelKernelIntegrator {
public:
    AovIntegrator(const cl::Context& context, const DeviceScene& scene, const RenderSetup& setup)
        : PixelKernelIntegrator(context, scene, setup, "aov.cl", "aov_render", "first-hit AOVs")
    {
    }
};

// whitted.cl: mirror and glass recursion with direct light at every diffuse hit.
class WhittedIntegrator : public PixelKernelIntegrator {
public:
    WhittedIntegrator(const cl::Context& context, const DeviceScene& scene, const RenderSetup& setup)
        : PixelKernelIntegrator(context, scene, setup, "whitted.cl", "whitted_render", "Whitted ray trees")
    {
    }
};

}  // namespace gc
