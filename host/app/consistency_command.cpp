#include "host/app/consistency_command.h"

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "host/app/consistency_report.h"
#include "host/app/environment.h"
#include "host/app/lighting_check.h"
#include "host/bvh/bvh.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/image/compare.h"
#include "host/image/image_io.h"
#include "host/render/session.h"
#include "host/util/log.h"

#ifdef GC_HAVE_VULKAN
#include "host/vk/compute_reference.h"
#include "host/vk/context.h"
#endif

namespace gc {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Renders settings.spp samples with any renderer of the Renderer interface (OpenCL
// Renderer, Vulkan ComputeReference) and times the sampling only: kernel builds and scene
// upload happen in the constructor, before this.
template <class R>
Film render_all(R& renderer, std::uint32_t spp, double& seconds)
{
    const auto start = Clock::now();
    while (renderer.samples_done() < spp) renderer.render_sample();
    seconds = seconds_since(start);
    return renderer.film();
}

// The Vulkan column: the compute reference (kernels/vk/path.comp, whitted.comp, aov.comp),
// which runs the same shared shading code as the OpenCL kernels. Appends a render, or a note
// saying why there is none; a build without Vulkan notes nothing.
void add_vulkan_render(const Options& options, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
                       const RenderSettings& settings, ConsistencyRun& run)
{
#ifdef GC_HAVE_VULKAN
    std::unique_ptr<vk::Context> context;
    try {
        context = std::make_unique<vk::Context>(options.vk_device);
    } catch (const DeviceError& e) {
        // No Vulkan device is not a failure of the check: the OpenCL pairs still stand.
        run.notes.push_back(std::string("Vulkan: no device (") + e.what() + ")");
        return;
    }
    log_info("rendering on Vulkan: " + context->description());
    vk::ComputeReference reference(*context, scene, bvh, camera, settings);
    ConsistencyRender r;
    r.api = "vulkan";
    r.device = context->description();  // name, LLVM/driver, Vulkan version, device type
    r.image = render_all(reference, settings.spp, r.seconds);
    run.renders.push_back(std::move(r));
#else
    (void)options, (void)scene, (void)bvh, (void)camera, (void)settings, (void)run;
#endif
}

// Fails before any rendering when an output cannot be written.
void check_outputs(const Options& options)
{
    if (!options.json_path.empty()) {
        const std::filesystem::path parent = std::filesystem::absolute(options.json_path).parent_path();
        if (!std::filesystem::is_directory(parent))
            throw OutputError("cannot write the consistency report '" + options.json_path + "': directory '" +
                              parent.string() + "' does not exist");
        if (std::filesystem::is_directory(options.json_path))
            throw OutputError("cannot write the consistency report '" + options.json_path + "': it is a directory");
    }
    if (!options.heatmap_dir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(options.heatmap_dir, ec);
        if (ec || !std::filesystem::is_directory(options.heatmap_dir))
            throw OutputError("cannot create the heat-map directory '" + options.heatmap_dir + "': " +
                              (ec ? ec.message() : std::string("not a directory")));
    }
}

void write_text(const std::string& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (out) out << text;
    if (out) out.flush();
    if (!out)
        throw OutputError("cannot write the consistency report '" + path + "': " + std::strerror(errno));
}

}  // namespace

ExitCode run_consistency(const Options& options)
{
    check_outputs(options);

    RenderSettings settings = options.render;
    if (!options.spp_given) settings.spp = 64;
    if (!options.res_given) settings.width = settings.height = 128;
    // A time limit would stop devices at different sample counts: not comparable.
    settings.time_limit_seconds = 0.0;
    if (settings.integrator == IntegratorKind::Aov && !options.spp_given) settings.spp = 1;

    const PreparedScene prepared = prepare_scene(scene_request(options));
    const Scene& scene = prepared.scene;
    if (const auto warning = unlit_scene_warning(scene, settings)) log_warning(*warning);

    ConsistencyRun run;
    run.scene = options.scene_path;
    run.integrator = integrator_name(settings.integrator);
    if (settings.integrator == IntegratorKind::Aov) run.integrator += std::string(":") + aov_name(settings.aov);
    run.width = static_cast<std::uint32_t>(settings.width);
    run.height = static_cast<std::uint32_t>(settings.height);
    run.spp = settings.spp;
    run.seed = settings.seed;
    // Radiance needs light: as --cross-check does, a scene that nothing lights gets a white sky.
    if (settings.integrator != IntegratorKind::Aov && !has_light(scene, settings)) {
        settings.env_radiance = glm::vec3(1.0f);
        run.notes.push_back("nothing lights the scene: rendered with --env 1,1,1");
    }

    const RenderSetup setup = render_setup_from_environment();
    std::string why_none;
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why_none);
    if (devices.empty()) run.notes.push_back("OpenCL: no device (" + why_none + ")");
    for (const cl::DeviceInfo& device : devices) {
        log_info("rendering on OpenCL: " + device.device_name + " (" + device.platform_name + ")");
        // The kernels ask for correctly rounded division and sqrt where the device offers it
        // (host/cl/program.h); elsewhere OpenCL allows 2.5 ulp (division) and 3 ulp (sqrt).
        if (!device.correctly_rounded_div_sqrt)
            run.notes.push_back(device.device_name +
                                ": no correctly rounded division/sqrt (CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT): "
                                "expect more differing pixels");
        Session session(device, prepared, settings, setup);
        Renderer& renderer = session.renderer();
        ConsistencyRender r;
        r.api = "opencl";
        r.device = device.device_name;
        r.platform = device.platform_name + ", " + device.driver_version;
        r.image = render_all(renderer, settings.spp, r.seconds);
        run.renders.push_back(std::move(r));
    }
    add_vulkan_render(options, scene, prepared.bvh, prepared.camera, settings, run);

    run.pairs = compare_all(run.renders, run.tolerances);
    std::fputs(format_report(run).c_str(), stdout);
    std::fflush(stdout);

    if (!options.json_path.empty()) write_text(options.json_path, format_json(run));
    if (!options.heatmap_dir.empty()) {
        // PNG needs OpenImageIO; the built-in writers give PPM (8-bit sRGB) instead.
        const char* ext = image_io_has_oiio() ? ".png" : ".ppm";
        for (const ConsistencyPair& pair : run.pairs) {
            const std::filesystem::path path =
                std::filesystem::path(options.heatmap_dir) / (heatmap_stem(run, pair) + ext);
            ImageMetadata meta;
            meta.device = run.renders[pair.a].device + " vs " + run.renders[pair.b].device;
            meta.integrator = "difference heat map of " + run.integrator;
            meta.scene = options.scene_path;
            meta.spp = run.spp;
            meta.seed = run.seed;
            // Largest difference = white, so even bit-level differences are visible.
            write_image(path, difference_heatmap(run.renders[pair.a].image, run.renders[pair.b].image), meta);
            log_info("wrote " + path.string());
        }
    }
    return run.passed() ? ExitCode::Ok : ExitCode::Mismatch;
}

}  // namespace gc
