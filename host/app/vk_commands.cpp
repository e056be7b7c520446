#include "host/app/vk_commands.h"

#ifdef GC_HAVE_VULKAN
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "host/app/environment.h"
#include "host/app/lighting_check.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/image/image_io.h"
#include "host/util/log.h"
#include "host/vk/context.h"
#include "host/vk/cross_check.h"
#include "host/vk/raster_pass.h"
#endif

namespace gc {

#ifdef GC_HAVE_VULKAN
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

ExitCode run_preview(const Options& options)
{
    const std::filesystem::path output =
        options.output_path.empty() ? std::filesystem::path(std::filesystem::path(options.scene_path).stem().string() + ".png")
                                    : std::filesystem::path(options.output_path);
    check_output_path(output);
    const PreparedScene prepared = load_with_camera(scene_request(options));
    const vk::Context context(options.vk_device);
    vk::RasterPass pass(context, prepared.scene, prepared.camera, options.render);
    const auto t0 = Clock::now();
    const vk::GBuffer g = pass.render();
    const double seconds = seconds_since(t0);

    ImageMetadata meta;
    meta.device = context.description();
    meta.integrator = "raster:preview";
    meta.scene = options.scene_path;
    meta.spp = 1;
    meta.seconds = seconds;
    write_image(output, g.preview, meta);
    char timing[64];
    std::snprintf(timing, sizeof timing, "%.3f", seconds);
    log_info("wrote " + output.string() + " (" + std::to_string(g.width) + "x" + std::to_string(g.height) +
             " raster preview, " + timing + " s on " + context.description() + ")");
    return ExitCode::Ok;
}

ExitCode run_cross_check(const Options& options)
{
    RenderSettings settings = options.render;
    // The Vulkan side is a megakernel on (typically) a CPU rasteriser: keep the defaults cheap.
    if (!options.spp_given) settings.spp = 4;
    if (!options.res_given) settings.width = settings.height = 128;
    const PreparedScene prepared = prepare_scene(scene_request(options));
    // Radiance needs light: a scene that nothing lights gets a white environment.
    if (!has_light(prepared.scene, settings)) {
        settings.env_radiance = glm::vec3(1.0f);
        log_info("nothing lights the scene: the radiance checks use --env 1,1,1");
    }
    const cl::DeviceInfo device = cl::select_device(options.device);
    const cl::Context cl_context(device);
    const vk::Context vk_context(options.vk_device);
    log_info("OpenCL: " + device.device_name + " (" + device.platform_name + "); Vulkan: " + vk_context.description());
    const RenderSetup setup = render_setup_from_environment();
    vk::CrossCheckReport report =
        vk::cross_check(cl_context, vk_context, prepared.scene, prepared.bvh, prepared.camera, settings, setup);
    // A file that reuses meshes renders as instances (render_command.cpp): check that form too.
    if (!options.flatten_instances) {
        SceneRequest request = scene_request(options);
        request.keep_instances = true;
        const PreparedScene instanced = prepare_scene(request);
        if (instanced.instances)
            vk::add_instanced(report, cl_context, vk_context, *instanced.instances, prepared.camera, settings, setup);
    }
    std::fputs(report.format().c_str(), stdout);
    const bool ok = report.passed();
    std::puts(ok ? "cross-check passed" : "cross-check FAILED: OpenCL and Vulkan disagree beyond tolerance");
    return ok ? ExitCode::Ok : ExitCode::Mismatch;
}

#else

ExitCode run_preview(const Options&) { throw UsageError("this build has no Vulkan support (--preview)"); }
ExitCode run_cross_check(const Options&) { throw UsageError("this build has no Vulkan support (--cross-check)"); }

#endif

}  // namespace gc
