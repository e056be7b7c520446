// The path integrator as one kernel (kernels/megakernel.cl): a work-item runs its pixel's
// samples of the pass from the camera to the end of each path, back to back, which keeps that
// pixel's part of the scene in the core's caches. The form CPUs use.
#pragma once

#include "host/cl/kernel.h"
#include "host/render/integrator.h"

namespace gc {

class MegakernelPathIntegrator : public Integrator {
public:
    MegakernelPathIntegrator(const cl::Context& context, const DeviceScene& scene, const RenderSetup& setup);

    const cl::Program& program() const override { return m_program; }
    // A pass is sized by time (PassPlanner): long enough to pay its launch and round trip,
    // short enough for progress, --time-limit and Ctrl-C.
    bool plans_passes_by_time() const override { return true; }
    void begin_pass(dev::GcRenderParams& params) override;
    void render_batch(const dev::GcRenderParams& params, const DeviceScene& scene, const FilmBuffers& film) override;

private:
    const cl::Context& m_context;
    bool m_camera_packets;  // the BVH8's camera-ray packets (gc_packet8.h)
    cl::Program m_program;
    cl::Kernel m_kernel;
};

}  // namespace gc
