// The OpenCL/Vulkan cross-check (DESIGN.md "Cross-checks"): the same scene, camera, seed and
// spp rendered by the OpenCL kernels and by the Vulkan path, and the figures that say how
// far apart they are.
//   - raster primitive id and depth (Vulkan mesh pass) vs the OpenCL ray-cast AOVs;
//   - the same for the Vulkan compute AOVs (same traversal code: should agree everywhere);
//   - Vulkan compute radiance vs OpenCL radiance, for each integrator that makes light: the
//     path tracer and the Whitted ray tracer; for a file that reuses meshes, also with the
//     meshes kept as instances on both sides (add_instanced).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "host/bvh/bvh.h"
#include "host/cl/context.h"
#include "host/render/render_setup.h"
#include "host/render/render_settings.h"
#include "host/render/session.h"
#include "host/scene/scene.h"
#include "host/vk/agreement.h"
#include "host/vk/context.h"

namespace gc::vk {

// Vulkan compute radiance vs OpenCL radiance with the meshes kept as instances on both sides.
struct InstancedAgreement {
    ImageDifference path;     // path.comp vs the OpenCL path tracer
    ImageDifference whitted;  // whitted.comp vs whitted.cl
};

struct CrossCheckReport {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint32_t spp = 0;
    IdDepthAgreement raster;      // Vulkan raster G-buffer vs OpenCL ray-cast AOVs
    IdDepthAgreement compute_aov; // Vulkan compute AOVs vs OpenCL ray-cast AOVs
    ImageDifference path;         // Vulkan path.comp vs the OpenCL path tracer
    ImageDifference whitted;      // Vulkan whitted.comp vs OpenCL whitted.cl
    double raster_seconds = 0.0;  // one raster frame (render + read back)
    double vk_path_seconds_per_spp = 0.0;
    double cl_path_seconds_per_spp = 0.0;
    double vk_whitted_seconds_per_spp = 0.0;
    double cl_whitted_seconds_per_spp = 0.0;
    std::optional<InstancedAgreement> instanced;  // set by add_instanced

    bool passed(const Tolerances& tol = {}) const;
    // Human-readable figures, one per line, each marked ok / FAIL against `tol`.
    std::string format(const Tolerances& tol = {}) const;
};

// Renders with both APIs. settings: width, height, spp, seed, max_depth, rr_depth,
// env_radiance and env_map_path are used; the integrator fields are set per pass.
CrossCheckReport cross_check(const cl::Context& cl_context, const Context& vk_context, const Scene& scene,
                             const FlatBvh& bvh, const Camera& camera, const RenderSettings& settings,
                             const RenderSetup& setup = {});

// The path and Whitted checks again on the scene's instanced form (the two-level BVH on both
// sides: DeviceScene::upload_instanced, kernels/vk/instances.glsl), into report.instanced.
void add_instanced(CrossCheckReport& report, const cl::Context& cl_context, const Context& vk_context,
                   const PreparedInstances& instances, const Camera& camera, const RenderSettings& settings,
                   const RenderSetup& setup = {});

}  // namespace gc::vk
