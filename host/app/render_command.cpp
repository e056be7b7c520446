#include "host/app/render_command.h"

#include <cstdio>
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>

#include "host/app/aov_output.h"
#include "host/app/environment.h"
#include "host/app/frame_checkpoints.h"
#include "host/app/interrupt.h"
#include "host/app/lighting_check.h"
#include "host/app/partial_header.h"
#include "host/cl/device.h"
#include "host/image/denoise.h"
#include "host/image/image_io.h"
#include "host/render/adaptive.h"
#include "host/render/multi_device.h"
#include "host/render/partial_image.h"
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

// The devices that delivered chunks (every device with `all`), each name once: "A; B".
std::string device_names(const FrameOutcome& outcome, bool all)
{
    std::vector<std::string> names;
    for (const DeviceReport& d : outcome.devices)
        if ((all || d.chunks > 0) && std::find(names.begin(), names.end(), d.name) == names.end())
            names.push_back(d.name);
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : "; ") + n;
    return out;
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

std::vector<cl::DeviceInfo> select_devices(const std::string& spec)
{
    if (!names_several_devices(spec)) return {cl::select_device(spec)};
    std::string why;
    const std::vector<cl::DeviceInfo> all = cl::list_devices(&why);
    if (all.empty()) throw DeviceError("no OpenCL device found: " + why);
    if (spec == "all") return all;
    std::vector<cl::DeviceInfo> picked;
    std::size_t p = 0;
    while (p <= spec.size()) {
        std::size_t comma = spec.find(',', p);
        if (comma == std::string::npos) comma = spec.size();
        const std::string one = spec.substr(p, comma - p);
        p = comma + 1;
        if (one.empty()) throw UsageError("--device '" + spec + "' has an empty entry");
        const cl::DeviceInfo device = cl::select_device(one, all);
        for (const cl::DeviceInfo& d : picked)
            if (d.id == device.id) throw UsageError("--device '" + spec + "' names " + device.device_name + " twice");
        picked.push_back(device);
    }
    return picked;
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
    if (options.partial) {
        std::string ext = output.extension().string();
        for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (ext != ".exr")
            throw UsageError("--samples writes a partial image, which is an OpenEXR file: name it .exr, not '" +
                             output.string() + "'");
    } else {
        start_image_io_for(output, ImageAccess::Write);
    }
    if (!options.render.env_map_path.empty()) start_image_io_for(options.render.env_map_path, ImageAccess::Read);

    RenderSettings settings = options.render;
    // Depth, normals and primitive ids are per-pixel facts: more samples add nothing.
    if (settings.integrator == IntegratorKind::Aov && !options.spp_given && !options.partial) settings.spp = 1;
    const ChunkPlan plan = options.partial
                               ? ChunkPlan::for_range(options.samples_first, options.samples_end, options.chunk_samples)
                               : ChunkPlan::for_range(0, settings.spp, options.chunk_samples);
    if (options.partial) settings.spp = plan.end_sample;

    // --denoise without the library fails here, before any rendering, and writes nothing.
    DenoiseOptions denoise_options;
    denoise_options.library = oidn_library_from_environment();
    denoise_options.threads = options.threads;
    if (options.denoise) {
        std::string why;
        if (!denoiser_available(denoise_options, &why)) throw DeviceError("--denoise: " + why);
    }

    SceneRequest request = scene_request(options);
    request.keep_instances = !options.flatten_instances;
    PreparedScene prepared = prepare_scene(request);
    if (const auto warning = unlit_scene_warning(prepared.scene, settings)) log_warning(*warning);

    if (!options.partial) check_output_format(output);
    const std::vector<cl::DeviceInfo> devices = select_devices(options.device);

    install_interrupt_handler();
    // A partial render is a farm's task: SIGTERM (preemption, scancel) stops it like Ctrl-C,
    // and an interrupted partial render writes nothing. So may a checkpointed one be, which
    // then writes its checkpoint.
    if (options.partial || options.checkpoint_seconds > 0) install_termination_handler();
    ProgressBar::Options progress_options;
    progress_options.quiet = options.quiet;
    progress_options.unit = "spp";
    ProgressBar progress("Rendering", plan.end_sample - plan.first_sample, progress_options);
    FrameControl control;
    control.time_limit_seconds = settings.time_limit_seconds;
    control.cancelled = interrupt_requested;
    control.on_progress = [&](std::uint64_t done) { progress.update(done); };

    ImageMetadata meta;
    meta.integrator = integrator_name(settings.integrator);
    if (settings.integrator == IntegratorKind::Aov) meta.integrator += std::string(":") + aov_name(settings.aov);
    meta.scene = options.scene_path;
    meta.seed = settings.seed;

    FrameOutcome outcome;
    std::uint32_t samples = 0;
    std::uint64_t pixel_samples = 0;  // over all pixels: fewer than width x height x samples when adaptive
    const RenderSetup setup = render_setup_from_environment();
    if (options.partial) {
        PartialImage part = partial_image_header(prepared, settings, plan, meta);
        std::map<std::uint32_t, PartialChunk> chunks;
        outcome = render_chunks(devices, prepared, settings, setup, plan, control,
                                [&](const ChunkRange& range, FilmSums&& sums, bool complete) {
                                    if (!complete) return;
                                    sums.squares.clear();  // not kept in partial images
                                    chunks[range.index] = PartialChunk{range, std::move(sums)};
                                });
        progress.finish();
        if (outcome.cancelled) {
            log_info("interrupted: no partial image written (" + std::to_string(chunks.size()) + " of " +
                     std::to_string(plan.chunk_count()) + " chunks were done)");
            return ExitCode::Interrupted;
        }
        for (auto& [index, chunk] : chunks) {
            samples += chunk.range.count;
            part.chunks.push_back(std::move(chunk));
        }
        part.device = device_names(outcome, false);
        if (part.chunks.empty()) throw DeviceError("the time limit ended the render before any chunk was complete");
        write_partial_image(output, part);
    } else {
        const DisplayTransform display = display_transform(options, settings, output);
        FrameCheckpoints checkpoints(options, output, partial_image_header(prepared, settings, plan, meta), meta, display);
        control.with_squares = std::any_of(options.aovs.begin(), options.aovs.end(), needs_squares);
        ResumedFrame resumed;
        if (settings.noise_threshold > 0.0)  // never with --resume or --checkpoint-every (options.cpp)
            resumed.frame = render_frame(devices, prepared, settings, setup, plan, control,
                                         adaptive_rounds(settings.noise_threshold, settings.spp, plan.chunk_samples));
        else
            resumed = render_frame_from(devices, prepared, settings, setup, plan, control, checkpoints.take_start(),
                                        checkpoints.while_rendering());
        FrameResult& frame = resumed.frame;
        progress.finish();
        outcome = frame.outcome;
        samples = frame.end_sample;
        pixel_samples = total_samples(frame.sums);
        if (settings.noise_threshold > 0.0)
            log_info("adaptive sampling: " + std::to_string(pixel_samples) + " samples in total, mean " +
                     fixed(double(pixel_samples) / (double(settings.width) * settings.height), 1) + " spp (cap " +
                     std::to_string(settings.spp) + ")");
        meta.device = device_names(outcome, devices.size() == 1);
        meta.spp = samples;
        meta.seconds = outcome.seconds;
        if (frame.sums.width == 0) {
            frame.sums.width = std::uint32_t(settings.width);
            frame.sums.height = std::uint32_t(settings.height);
            frame.sums.sums.assign(std::size_t(settings.width) * settings.height, glm::vec4(0.0f));
        }
        Film image = mean_film(frame.sums);
        // Ctrl-C asks for the image so far, now: the guides would take another render.
        if (options.denoise && outcome.cancelled) log_warning("interrupted: the image is written without denoising");
        if (options.denoise && !outcome.cancelled && samples > 0) {
            // The guides are facts of the scene and the camera: the first device renders them,
            // in a session of the AOV integrator (whose program they use).
            RenderSettings guide_settings = settings;
            guide_settings.integrator = IntegratorKind::Aov;
            Session guide_session(devices.front(), prepared, guide_settings, setup);
            const DenoiseGuides guides = render_denoise_guides(guide_session.renderer(), samples);
            image = denoise(image, &guides.albedo, &guides.normal, denoise_options);
            log_verbose("denoised with Open Image Denoise (albedo and normal guides)");
        }
        write_image(output, image, meta, display);
        checkpoints.write_final(resumed.complete, meta.device);
        if (!options.aovs.empty() && outcome.cancelled) log_warning("interrupted: no AOV layers written");
        if (!options.aovs.empty() && !outcome.cancelled && samples > 0)
            write_aov_layers(options.aovs, devices.front(), prepared, settings, setup, frame.sums, meta, output);
    }
    prepared = PreparedScene{};

    for (const DeviceReport& d : outcome.devices) {
        const std::string probe =
            d.probe_seconds > 0.0 ? "probe " + fixed(d.probe_seconds, 3) + " s (" + fixed(d.probe_rate, 1) + " spp/s), "
                                  : "";
        log_verbose("device " + d.name + ": " + std::to_string(d.chunks) + " chunks (" + std::to_string(d.backups) +
                    " backups), " + std::to_string(d.samples) + " spp rendered, set up in " + fixed(d.setup_seconds, 3) +
                    " s, " + probe + "busy " + fixed(d.busy_seconds, 3) + " s, last chunk at " + fixed(d.finished_at, 3) +
                    " s" + (d.failure.empty() ? "" : ", failed: " + d.failure) +
                    (d.left_slow ? ", left the frame: under a tenth of the other devices' rate" : ""));
    }
    log_verbose("frame: " + fixed(outcome.seconds, 3) + " s rendering (every device set up), " +
                fixed(outcome.seconds_with_setup, 3) + " s with the set-ups, then " + fixed(outcome.cleanup_seconds, 3) +
                " s releasing the devices");
    const double render_seconds = outcome.seconds;
    if (options.partial) pixel_samples = std::uint64_t(settings.width) * settings.height * samples;
    const double samples_per_second = static_cast<double>(pixel_samples) / std::max(render_seconds, 1e-9);
    log_info("wrote " + output.string() + (options.partial ? " (partial, " : " (") + std::to_string(settings.width) +
             "x" + std::to_string(settings.height) + ", " + std::to_string(samples) + " spp, " +
             fixed(render_seconds, 2) + " s, " + fixed(samples_per_second / 1e6, 2) + " Msamples/s on " +
             std::to_string(devices.size()) + (devices.size() == 1 ? " device" : " devices") + ")");
    return outcome.cancelled ? ExitCode::Interrupted : ExitCode::Ok;
}

ExitCode run_merge(const std::vector<std::string>& args)
{
    std::vector<std::filesystem::path> inputs;
    std::filesystem::path output;
    std::optional<std::uint32_t> spp;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= args.size()) throw UsageError("merge: " + arg + " needs a value");
            return args[++i];
        };
        if (arg == "-o" || arg == "--output") output = value();
        else if (arg == "--spp") {
            const std::string v = value();
            if (v.empty() || v.size() > 9 || v.find_first_not_of("0123456789") != std::string::npos || std::stoul(v) == 0)
                throw UsageError("merge: --spp expects a positive number of samples, not '" + v + "'");
            spp = static_cast<std::uint32_t>(std::stoul(v));
        } else if (arg == "-q" || arg == "--quiet") set_log_level(LogLevel::Quiet);
        else if (!arg.empty() && arg[0] == '-') throw UsageError("merge: unknown option '" + arg + "'");
        else inputs.emplace_back(arg);
    }
    if (inputs.empty()) throw UsageError("merge: no partial images given");
    if (output.empty()) throw UsageError("merge: no output given (-o FRAME.exr)");
    for (const auto& in : inputs)
        if (std::filesystem::weakly_canonical(in) == std::filesystem::weakly_canonical(output))
            throw UsageError("merge: the output '" + output.string() + "' is also an input");
    start_image_io_for(output, ImageAccess::Write);
    check_output_path(output);
    const MergedFrame merged = merge_partial_images(inputs, spp);
    ImageMetadata meta;
    for (const std::string& d : merged.devices) meta.device += (meta.device.empty() ? "" : "; ") + d;
    meta.integrator = merged.first.integrator;
    meta.scene = merged.first.scene;
    meta.spp = merged.spp;
    meta.seed = merged.first.seed;
    write_image(output, mean_film(merged.sums), meta);
    log_info("wrote " + output.string() + " (" + std::to_string(merged.spp) + " spp from " +
             std::to_string(inputs.size()) + " partial images)");
    return ExitCode::Ok;
}

}  // namespace gc
