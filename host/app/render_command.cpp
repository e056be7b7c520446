#include "host/app/render_command.h"

#include <cstdio>
#include <filesystem>

#include "host/app/environment.h"
#include "host/app/interrupt.h"
#include "host/app/lighting_check.h"
#include "host/cl/device.h"
#include "host/image/denoise.h"
#include "host/image/image_io.h"
#include "host/render/denoise_guides.h"
#include "host/render/session.h"
#include "host/util/log.h"
#include "host/util/progress.h"

namespace gc {
namespace {

std::string fixed(double value, int decimals)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

std::filesystem::path default_output(const std::string& scene_path)
{
    return std::filesystem::path(scene_path).stem().string() + ".png";
}

// The CLI's display transform: the options', else Khronos PBR Neutral for rendered images and
// none for AOVs (their values are data: albedo, normals, depth, ids).
DisplayTransform display_transform(const Options& options, const RenderSettings& settings,
                                   const std::filesystem::path& output)
{
    DisplayTransform display;
    display.tonemap = options.tonemap.value_or(settings.integrator == IntegratorKind::Aov ? Tonemap::None
                                                                                         : Tonemap::PbrNeutral);
    display.exposure_ev = options.exposure_ev.value_or(0.0f);
    if ((options.tonemap || options.exposure_ev) && !is_display_referred(output))
        log_warning(output.string() + " is a float format and is written linear: --tonemap and --exposure "
                    "apply to 8-bit outputs (.png, .ppm)");
    return display;
}

}  // namespace

ExitCode run_list_devices()
{
    std::string why;
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why);
    if (devices.empty()) throw DeviceError("no OpenCL device found: " + why);
    std::fputs(cl::format_device_list(devices).c_str(), stdout);
    return ExitCode::Ok;
}

ExitCode run_render(const Options& options)
{
    const std::filesystem::path output = options.output_path.empty() ? default_output(options.scene_path)
                                                                      : std::filesystem::path(options.output_path);
    // Fail on an unwritable output before spending minutes rendering. Formats that are not
    // built in need the image module (~0.35 s of dynamic linking): it loads in the background
    // while the scene loads and the BVH builds, and whether the format can be written is
    // asked after those, before any device work. (Waiting for it there also keeps its
    // dlopen() from holding up the OpenCL driver's: both take the dynamic linker's lock.)
    check_output_location(output);
    start_image_io_for(output, ImageAccess::Write);
    if (!options.render.env_map_path.empty()) start_image_io_for(options.render.env_map_path, ImageAccess::Read);

    RenderSettings settings = options.render;
    // Depth, normals and primitive ids are per-pixel facts: more samples add nothing.
    if (settings.integrator == IntegratorKind::Aov && !options.spp_given) settings.spp = 1;

    // --denoise without the library fails here, before any rendering, and writes nothing.
    DenoiseOptions denoise_options;
    denoise_options.library = oidn_library_from_environment();
    denoise_options.threads = options.threads;
    if (options.denoise) {
        std::string why;
        if (!denoiser_available(denoise_options, &why)) throw DeviceError("--denoise: " + why);
    }

    PreparedScene prepared = prepare_scene(scene_request(options));
    if (const auto warning = unlit_scene_warning(prepared.scene, settings)) log_warning(*warning);

    check_output_format(output);
    const cl::DeviceInfo device = cl::select_device(options.device);
    Session session(device, prepared, settings, render_setup_from_environment());
    // The device holds its own copy of the scene and the BVH (a CPU device the wide BVH made
    // from it): for the rest of the render they are dead weight, 85 bytes per triangle for
    // the flat BVH alone.
    prepared = PreparedScene{};
    const Renderer& renderer = session.renderer();
    log_verbose("device " + device.device_name + " (" + device.platform_name + "); kernels " +
                (renderer.program().from_cache() ? "loaded from cache" : "compiled") + " in " +
                fixed(renderer.program().build_seconds(), 3) + " s; scene uses " +
                std::to_string(renderer.device_scene().bytes() / 1024) + " KiB on the device");

    install_interrupt_handler();
    ProgressBar::Options progress_options;
    progress_options.quiet = options.quiet;
    progress_options.unit = "spp";
    ProgressBar progress("Rendering", settings.spp, progress_options);
    RenderControl control;
    control.time_limit_seconds = settings.time_limit_seconds;
    control.cancelled = interrupt_requested;
    control.on_pass = [&](std::uint32_t done) { progress.update(done); };
    const RenderOutcome outcome = session.render(control);
    progress.finish();
    const double render_seconds = outcome.seconds;

    ImageMetadata meta;
    meta.device = device.device_name + " (" + device.platform_name + ")";
    meta.integrator = integrator_name(settings.integrator);
    if (settings.integrator == IntegratorKind::Aov) meta.integrator += std::string(":") + aov_name(settings.aov);
    meta.scene = options.scene_path;
    meta.spp = renderer.samples_done();
    meta.seconds = render_seconds;
    meta.seed = settings.seed;
    Film image = renderer.film();
    // Ctrl-C asks for the image so far, now: the guides would take another render.
    if (options.denoise && outcome.cancelled) log_warning("interrupted: the image is written without denoising");
    if (options.denoise && !outcome.cancelled && renderer.samples_done() > 0) {
        const DenoiseGuides guides = render_denoise_guides(renderer);
        image = denoise(image, &guides.albedo, &guides.normal, denoise_options);
        log_verbose("denoised with Open Image Denoise (albedo and normal guides)");
    }
    write_image(output, image, meta, display_transform(options, settings, output));

    const double samples_per_second =
        static_cast<double>(settings.width) * settings.height * renderer.samples_done() / std::max(render_seconds, 1e-9);
    log_info("wrote " + output.string() + " (" + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
             ", " + std::to_string(renderer.samples_done()) + " spp, " + fixed(render_seconds, 2) + " s, " +
             fixed(samples_per_second / 1e6, 2) + " Msamples/s on " + device.device_name + ")");
    return outcome.cancelled ? ExitCode::Interrupted : ExitCode::Ok;
}

}  // namespace gc
