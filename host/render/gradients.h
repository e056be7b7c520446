// Gradients of a loss of the path integrator's image with respect to the scene's named
// parameters (scene_params.h), by path replay backpropagation (kernels/adjoint.cl):
//
//     Renderer renderer(context, scene, bvh, camera, settings);
//     renderer.render(0, 4);
//     std::vector<glm::vec4> d_loss = ...;   // d loss / d (each pixel's mean), row 0 at the top
//     PathAdjoint adjoint(renderer);
//     Gradients g = adjoint.backward(renderer, scene, d_loss, {"materials/red/base_color"}, 4, 1);
//
// The pass renders the renderer's scene, camera and settings with its own seed and sample
// count: give it a seed other than the image's for an unbiased gradient of a loss of that
// image (the same seed correlates the two, which finite-difference checks want). The sums
// are exact 64-bit fixed-point integers (gc_grad_slots.h), so a gradient is the same bits
// run to run on one device.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "host/cl/buffer.h"
#include "host/cl/kernel.h"
#include "host/cl/program.h"
#include "host/render/renderer.h"
#include "host/render/wavefront_path.h"

namespace gc {

// Parameter name -> its gradient, flattened in the parameter's shape.
using Gradients = std::map<std::string, std::vector<float>>;

// How the last backward pass accumulated (for reports and tests).
struct GradientStats {
    int scale_exponent = 0;         // one slot unit is 2^-scale_exponent
    float max_contribution = 0.0f;  // the largest |contribution| one vertex added
    bool rescaled = false;          // the first guess of the scale was too fine: the pass ran again
};

// How the kernel adds to the 64-bit slots: with 64-bit atomics where the device has them
// (else two 32-bit ones), or always with two 32-bit ones (to test that way on any device).
enum class SlotAtomics { Auto, Split32 };

// Where the adjoint learns each sample's radiance L before it replays the path: from a pass of
// the wavefront path integrator over the same pixels and samples (its path states, read by the
// adjoint kernel), or by tracing the path once more inside the adjoint kernel. Auto = the
// wavefront where the renderer uses it (GPUs: its passes keep the device busier than one
// long work-item per sample does) and the pass is large (small ones pay its launches for
// little), in the kernel elsewhere. The two give the same bits.
enum class PrimalPass { Auto, InKernel, Wavefront };

// How the adjoint's work is laid out and summed; every choice gives the same bits.
struct AdjointOptions {
    SlotAtomics atomics = SlotAtomics::Auto;
    // Samples of one pixel a work-item traces, one after another. 0 = the device's choice:
    // every sample of the pixel on CPUs (one long-lived item per core's turn, as the
    // megakernel), one on GPUs (pixels x spp items keep the GPU full where pixels alone would
    // not, and no item waits on another's long paths; docs/performance.md, "Gradients").
    std::uint32_t samples_per_item = 0;
    PrimalPass primal = PrimalPass::Auto;
};

class PathAdjoint {
public:
    // Builds kernels/adjoint.cl for `renderer`'s scene (again by backward if its features change).
    explicit PathAdjoint(const Renderer& renderer, AdjointOptions options = {});

    // d loss / d parameter for every name in `params` (UsageError for names that are unknown
    // or not differentiable), from `spp` samples per pixel (indices 0 .. spp - 1) with `seed`.
    // `loss_grad` has one entry per pixel (alpha ignored): d loss / d the pixel's mean radiance.
    // `scene` is the host scene the renderer's device scene was made from (it names the
    // parameters).
    Gradients backward(const Renderer& renderer, const Scene& scene,
                       std::span<const glm::vec4> loss_grad, std::span<const std::string> params,
                       std::uint32_t spp, std::uint32_t seed);

    const GradientStats& stats() const { return m_stats; }

private:
    void build(const Renderer& renderer);
    // Whether a pass of `paths` paths learns their radiance from a wavefront pass (PrimalPass).
    bool wavefront_primal(std::uint64_t paths) const;
    // The wavefront integrator for the primal pass of `spp` samples, made or remade as needed.
    WavefrontPathIntegrator& primal_integrator(const Renderer& renderer, std::uint32_t spp);
    template <class T>
    cl::Buffer<T>& sized(cl::Buffer<T>& buffer, std::size_t count, cl_mem_flags flags, const char* name);

    const cl::Context& m_context;
    AdjointOptions m_options;
    KernelFeatures m_features;
    std::unique_ptr<cl::Program> m_program;
    cl::Kernel m_kernel;
    GradientStats m_stats;
    cl::Buffer<glm::vec4> m_deltas;          // each sample's share of d loss / d pixel
    cl::Buffer<std::uint64_t> m_slots;       // the fixed-point sums (gc_grad_slots.h)
    cl::Buffer<std::uint32_t> m_max_bits;    // the largest contribution's float bits
    cl::Buffer<std::uint32_t> m_view_slots;  // per texture view, its texels' first slot
    cl::Buffer<std::uint32_t> m_wanted;      // a bit per material and environment slot asked for
    bool m_renderer_wavefront = false;       // the renderer traces paths in wavefront form
    std::unique_ptr<WavefrontPathIntegrator> m_primal;  // its paths give the adjoint each sample's L
    std::uint32_t m_primal_spp = 0;          // the sample count m_primal's path slots were sized for
    FilmBuffers m_primal_film;               // where its passes accumulate (the renderer's film stays)
    cl::Buffer<dev::GcPathState> m_no_primal;  // the kernel's argument when L is traced in it
};

}  // namespace gc
