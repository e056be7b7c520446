#include "host/vk/cross_check.h"

#include <chrono>
#include <cstdio>
#include <memory>

#include "host/render/environment.h"
#include "host/render/render_loop.h"
#include "host/render/renderer.h"
#include "host/render/scene_convert.h"
#include "host/vk/compute_reference.h"
#include "host/vk/raster_pass.h"

namespace gc::vk {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

RenderSettings aov_settings(RenderSettings s, AovKind kind)
{
    s.integrator = IntegratorKind::Aov;
    s.aov = kind;
    return s;
}

// Both render_* time only the sample loop (not program builds or uploads) into *seconds.
Film render_cl(const cl::Context& context, const RenderSetup& setup, const std::shared_ptr<const DeviceScene>& scene,
               const Camera& camera, const RenderSettings& settings, std::uint32_t spp, double* seconds = nullptr)
{
    Renderer renderer(context, scene, camera, settings, setup);
    const auto t0 = Clock::now();
    render_to(renderer, spp);
    if (seconds) *seconds = seconds_since(t0);
    return renderer.film();
}

Film render_vk(ComputeReference& reference, std::uint32_t spp, double* seconds = nullptr)
{
    const auto t0 = Clock::now();
    while (reference.samples_done() < spp) reference.render_sample();
    if (seconds) *seconds = seconds_since(t0);
    return reference.film();
}

Film render_vk(const Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
               const RenderSettings& settings, std::uint32_t spp, double* seconds = nullptr)
{
    ComputeReference reference(context, scene, bvh, camera, settings);
    return render_vk(reference, spp, seconds);
}

std::string line(const char* label, const std::string& value, bool ok)
{
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "  %-52s %-24s %s\n", label, value.c_str(), ok ? "ok" : "FAIL");
    return buffer;
}

std::string num(const char* format, double value)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, format, value);
    return buffer;
}

std::string radiance_lines(const std::string& integrator, const ImageDifference& r, const Tolerances& tol)
{
    const AgreementVerdict v = judge_agreement(r, tol.radiance);
    std::string s;
    if (!v.finite) s += line((integrator + " radiance pixels with NaN/Inf").c_str(), std::to_string(r.nonfinite), false);
    s += line((integrator + " radiance rel MSE").c_str(), num("%.3g", r.rel_mse), v.rel_mse_ok);
    s += line((integrator + " radiance pixels within 1e-3 relative").c_str(), num("%.3f %%", 100.0 * r.within_tolerance),
              v.within_ok);
    s += line("  bit-identical pixels", num("%.3f %%", 100.0 * r.identical), true);
    s += line("  max rel error", num("%.3g", r.max_rel), true);
    s += line("  mean OpenCL radiance (must not be black)", num("%.4g", r.mean_ref), v.lit);
    return s;
}

// Renders `integrator` with both APIs at settings.spp and compares the radiance.
ImageDifference compare_integrator(const cl::Context& cl_context, const RenderSetup& setup,
                                   const std::shared_ptr<const DeviceScene>& cl_scene, const Context& vk_context, const Scene& scene, const FlatBvh& bvh,
                                   const Camera& camera, const RenderSettings& settings,
                                   IntegratorKind integrator, double& cl_seconds_per_spp, double& vk_seconds_per_spp)
{
    RenderSettings s = settings;
    s.integrator = integrator;
    double cl_seconds = 0.0, vk_seconds = 0.0;
    const Film cl_film = render_cl(cl_context, setup, cl_scene, camera, s, settings.spp, &cl_seconds);
    const Film vk_film = render_vk(vk_context, scene, bvh, camera, s, settings.spp, &vk_seconds);
    cl_seconds_per_spp = cl_seconds / settings.spp;
    vk_seconds_per_spp = vk_seconds / settings.spp;
    return compare_images(vk_film, cl_film, Tolerances{}.radiance.pixel);
}

}  // namespace

bool CrossCheckReport::passed(const Tolerances& tol) const
{
    return raster.id_agreement >= tol.min_id_agreement && raster.max_depth_rel_error <= tol.max_depth_rel_error &&
           compute_aov.id_agreement >= tol.min_id_agreement &&
           compute_aov.max_depth_rel_error <= tol.max_depth_rel_error &&
           judge_agreement(path, tol.radiance).passed() && judge_agreement(whitted, tol.radiance).passed() &&
           (!instanced || (judge_agreement(instanced->path, tol.radiance).passed() &&
                           judge_agreement(instanced->whitted, tol.radiance).passed()));
}

std::string CrossCheckReport::format(const Tolerances& tol) const
{
    std::string s;
    s += "cross-check " + std::to_string(width) + "x" + std::to_string(height) + ", " + std::to_string(spp) +
         " spp (OpenCL vs Vulkan)\n";
    s += line("raster primid agreement (non-edge covered px)",
              num("%.3f %%", 100.0 * raster.id_agreement) + " of " + std::to_string(raster.compared),
              raster.id_agreement >= tol.min_id_agreement);
    s += line("  edge pixels excluded", std::to_string(raster.edge_excluded) + " of " + std::to_string(raster.covered),
              true);
    s += line("raster depth max rel error (equal ids)", num("%.3g", raster.max_depth_rel_error),
              raster.max_depth_rel_error <= tol.max_depth_rel_error);
    s += line("compute primid agreement (all covered px)",
              num("%.3f %%", 100.0 * compute_aov.id_agreement) + " of " + std::to_string(compute_aov.compared),
              compute_aov.id_agreement >= tol.min_id_agreement);
    s += line("compute depth max rel error (equal ids)", num("%.3g", compute_aov.max_depth_rel_error),
              compute_aov.max_depth_rel_error <= tol.max_depth_rel_error);
    s += radiance_lines("path", path, tol);
    s += radiance_lines("whitted", whitted, tol);
    if (instanced) {
        s += radiance_lines("instanced path", instanced->path, tol);
        s += radiance_lines("instanced whitted", instanced->whitted, tol);
    }
    s += "  time: Vulkan raster " + num("%.3f", raster_seconds) + " s/frame; s/spp Vulkan compute path " +
         num("%.3f", vk_path_seconds_per_spp) + ", OpenCL path " + num("%.3f", cl_path_seconds_per_spp) +
         ", Vulkan compute whitted " + num("%.3f", vk_whitted_seconds_per_spp) + ", OpenCL whitted " +
         num("%.3f", cl_whitted_seconds_per_spp) + "\n";
    return s;
}

CrossCheckReport cross_check(const cl::Context& cl_context, const Context& vk_context, const Scene& scene,
                             const FlatBvh& bvh, const Camera& camera, const RenderSettings& settings,
                             const RenderSetup& setup)
{
    CrossCheckReport report;
    report.width = static_cast<std::uint32_t>(settings.width);
    report.height = static_cast<std::uint32_t>(settings.height);
    report.spp = settings.spp;

    // One upload shared by the OpenCL renders of every integrator.
    const auto cl_scene = std::make_shared<const DeviceScene>(
        DeviceScene::upload(cl_context, scene, bvh, load_environment_map(settings), setup.tuning));

    // OpenCL ray-cast AOVs: per-pixel facts, one sample.
    const RenderSettings id_settings = aov_settings(settings, AovKind::PrimitiveId);
    const RenderSettings depth_settings = aov_settings(settings, AovKind::Depth);
    const std::vector<std::int32_t> cl_ids =
        ids_from_film(render_cl(cl_context, setup, cl_scene, camera, id_settings, 1));
    const std::vector<float> cl_depth =
        depth_from_film(render_cl(cl_context, setup, cl_scene, camera, depth_settings, 1));

    RasterPass raster(vk_context, scene, camera, settings);
    const auto t0 = Clock::now();
    const GBuffer g = raster.render();
    report.raster_seconds = seconds_since(t0);
    const dev::GcCamera device_camera = make_camera(camera, settings.width, settings.height);
    report.raster = compare_ids_depth(
        cl_ids, cl_depth, g.primid, g.depth,
        edge_pixels(scene, device_camera, cl_ids, g.primid, report.width, report.height));

    const std::vector<std::int32_t> vk_ids = ids_from_film(render_vk(vk_context, scene, bvh, camera, id_settings, 1));
    const std::vector<float> vk_depth = depth_from_film(render_vk(vk_context, scene, bvh, camera, depth_settings, 1));
    // The compute reference runs the OpenCL traversal code itself: no pixel is excused.
    report.compute_aov = compare_ids_depth(cl_ids, cl_depth, vk_ids, vk_depth, {});

    report.path = compare_integrator(cl_context, setup, cl_scene, vk_context, scene, bvh, camera, settings, IntegratorKind::Path,
                                     report.cl_path_seconds_per_spp, report.vk_path_seconds_per_spp);
    report.whitted = compare_integrator(cl_context, setup, cl_scene, vk_context, scene, bvh, camera, settings, IntegratorKind::Whitted,
                                        report.cl_whitted_seconds_per_spp, report.vk_whitted_seconds_per_spp);
    return report;
}

void add_instanced(CrossCheckReport& report, const cl::Context& cl_context, const Context& vk_context,
                   const PreparedInstances& instances, const Camera& camera, const RenderSettings& settings,
                   const RenderSetup& setup)
{
    const auto cl_scene = std::make_shared<const DeviceScene>(DeviceScene::upload_instanced(
        cl_context, instances.scene, instances.bvh, load_environment_map(settings), setup.tuning));
    const InstancedBvh bvh = assemble_binary(instances.bvh);
    InstancedAgreement agreement;
    for (const IntegratorKind integrator : {IntegratorKind::Path, IntegratorKind::Whitted}) {
        RenderSettings s = settings;
        s.integrator = integrator;
        const Film cl_film = render_cl(cl_context, setup, cl_scene, camera, s, settings.spp);
        ComputeReference reference(vk_context, instances.scene, bvh, camera, s);
        const Film vk_film = render_vk(reference, settings.spp);
        (integrator == IntegratorKind::Path ? agreement.path : agreement.whitted) =
            compare_images(vk_film, cl_film, Tolerances{}.radiance.pixel);
    }
    report.instanced = agreement;
}

}  // namespace gc::vk
