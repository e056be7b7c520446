#include "host/app/options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

#include "host/util/error.h"

namespace gc {
namespace {

// Limits that keep a typo from allocating terabytes or rendering for a year.
constexpr int kMaxResolution = 16384;
constexpr unsigned long kMaxSpp = 1u << 24;
constexpr unsigned long kMaxDepth = 1024;
constexpr unsigned long kMaxThreads = 4096;

[[noreturn]] void bad_value(const std::string& option, const std::string& value, const std::string& expected)
{
    throw UsageError(option + " expects " + expected + ", got '" + value + "'");
}

float parse_float(const std::string& option, const std::string& text)
{
    float value = 0.0f;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || !std::isfinite(value)) bad_value(option, text, "a finite number");
    return value;
}

unsigned long parse_count(const std::string& option, const std::string& text, unsigned long lo, unsigned long hi)
{
    unsigned long value = 0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end || value < lo || value > hi)
        bad_value(option, text, "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return value;
}

glm::vec3 parse_triple(const std::string& option, const std::string& text)
{
    glm::vec3 v;
    std::size_t start = 0;
    for (int i = 0; i < 3; ++i) {
        const std::size_t comma = text.find(',', start);
        if ((i < 2) != (comma != std::string::npos)) bad_value(option, text, "three comma-separated numbers x,y,z");
        v[i] = parse_float(option, text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        start = comma + 1;
    }
    return v;
}

void parse_resolution(const std::string& option, const std::string& text, RenderSettings& settings)
{
    const std::size_t x = text.find('x');
    if (x == std::string::npos) bad_value(option, text, "WIDTHxHEIGHT, e.g. 512x512");
    settings.width = static_cast<int>(parse_count(option, text.substr(0, x), 1, kMaxResolution));
    settings.height = static_cast<int>(parse_count(option, text.substr(x + 1), 1, kMaxResolution));
}

IntegratorKind parse_integrator(const std::string& text)
{
    if (const auto kind = integrator_from_name(text)) return *kind;
    bad_value("--integrator", text, "one of path, whitted, aov");
}

SamplerKind parse_sampler(const std::string& text)
{
    if (const auto kind = sampler_from_name(text)) return *kind;
    bad_value("--sampler", text, "one of independent, sobol");
}

AovKind parse_aov(const std::string& text)
{
    if (const auto kind = aov_from_name(text)) return *kind;
    bad_value("--aov", text, "one of preview, albedo, normal, depth, primid, guide-albedo, guide-normal");
}

}  // namespace

Options parse_options(const std::vector<std::string>& args)
{
    Options o;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string arg = args[i];
        std::string inline_value;
        bool has_inline_value = false;
        if (arg.rfind("--", 0) == 0) {
            const std::size_t eq = arg.find('=');
            if (eq != std::string::npos) {
                inline_value = arg.substr(eq + 1);
                arg = arg.substr(0, eq);
                has_inline_value = true;
            }
        }
        auto value = [&]() -> std::string {
            if (has_inline_value) return inline_value;
            if (i + 1 >= args.size()) throw UsageError(arg + " needs a value");
            return args[++i];
        };

        if (arg == "-h" || arg == "--help") o.help = true;
        else if (arg == "--version") o.version = true;
        else if (arg == "--list-devices") o.list_devices = true;
        else if (arg == "-q" || arg == "--quiet") o.quiet = true;
        else if (arg == "-v" || arg == "--verbose") o.verbose = true;
        else if (arg == "-o" || arg == "--output") o.output_path = value();
        else if (arg == "-d" || arg == "--device") o.device = value();
        else if (arg == "--integrator") o.render.integrator = parse_integrator(value());
        else if (arg == "--aov") {
            o.render.aov = parse_aov(value());
            o.render.integrator = IntegratorKind::Aov;
        }
        else if (arg == "--spp") {
            o.render.spp = static_cast<std::uint32_t>(parse_count(arg, value(), 1, kMaxSpp));
            o.spp_given = true;
        }
        else if (arg == "--tonemap") {
            const std::string v = value();
            o.tonemap = parse_tonemap(v);
            if (!o.tonemap) bad_value(arg, v, tonemap_names());
        }
        else if (arg == "--exposure") o.exposure_ev = parse_float(arg, value());
        else if (arg == "--denoise") o.denoise = true;
        else if (arg == "--aperture" || arg == "--focus-distance") {
            const std::string v = value();
            const float x = parse_float(arg, v);
            if (arg == "--aperture" ? x < 0.0f : x <= 0.0f)
                bad_value(arg, v, arg == "--aperture" ? "a radius >= 0" : "a distance > 0");
            (arg == "--aperture" ? o.aperture_radius : o.focus_distance) = x;
        }
        else if (arg == "--seed") o.render.seed = static_cast<std::uint32_t>(parse_count(arg, value(), 0, 0xffffffffu));
        else if (arg == "--sampler") o.render.sampler = parse_sampler(value());
        else if (arg == "--max-depth") o.render.max_depth = static_cast<std::uint32_t>(parse_count(arg, value(), 1, kMaxDepth));
        else if (arg == "--rr-depth") o.render.rr_depth = static_cast<std::uint32_t>(parse_count(arg, value(), 1, kMaxDepth));
        else if (arg == "--time-limit") {
            const std::string v = value();
            const float seconds = parse_float(arg, v);
            if (seconds <= 0.0f) bad_value(arg, v, "a positive number of seconds");
            o.render.time_limit_seconds = seconds;
        }
        else if (arg == "--res") {
            parse_resolution(arg, value(), o.render);
            o.res_given = true;
        }
        else if (arg == "--width") {
            o.render.width = static_cast<int>(parse_count(arg, value(), 1, kMaxResolution));
            o.res_given = true;
        }
        else if (arg == "--height") {
            o.render.height = static_cast<int>(parse_count(arg, value(), 1, kMaxResolution));
            o.res_given = true;
        }
        else if (arg == "--env") {
            // Either a constant radiance r,g,b or a lat-long map file (scaled by --env-scale).
            const std::string v = value();
            if (v.find(',') == std::string::npos && !v.empty()) {
                o.render.env_map_path = v;
                if (!o.env_scale_given) o.render.env_radiance = glm::vec3(1.0f);
            } else {
                const glm::vec3 env = parse_triple(arg, v);
                if (env.x < 0 || env.y < 0 || env.z < 0) bad_value(arg, v, "non-negative radiance r,g,b");
                o.render.env_radiance = env;
                o.render.env_map_path.clear();
            }
        }
        else if (arg == "--env-scale") {
            const std::string v = value();
            const glm::vec3 scale = parse_triple(arg, v);
            if (scale.x < 0 || scale.y < 0 || scale.z < 0) bad_value(arg, v, "a non-negative scale r,g,b");
            o.render.env_radiance = scale;
            o.env_scale_given = true;
        }
        else if (arg == "--samples") {
            const std::string v = value();
            const std::size_t colon = v.find(':');
            if (colon == std::string::npos) bad_value(arg, v, "a sample range A:B (first sample, end)");
            o.samples_first = static_cast<std::uint32_t>(parse_count(arg, v.substr(0, colon), 0, kMaxSpp));
            o.samples_end = static_cast<std::uint32_t>(parse_count(arg, v.substr(colon + 1), 1, kMaxSpp));
            if (o.samples_end <= o.samples_first) bad_value(arg, v, "a non-empty sample range A:B with A < B");
            o.partial = true;
        }
        else if (arg == "--noise-threshold") {
            const std::string v = value();
            const float threshold = parse_float(arg, v);
            if (threshold <= 0.0f) bad_value(arg, v, "a relative standard error > 0, e.g. 0.02");
            o.render.noise_threshold = threshold;
        }
        else if (arg == "--chunk-samples")
            o.chunk_samples = static_cast<std::uint32_t>(parse_count(arg, value(), 1, kMaxSpp));
        else if (arg == "--resume") o.resume_path = value();
        else if (arg == "--checkpoint-every") {
            const std::string v = value();
            o.checkpoint_seconds = parse_float(arg, v);
            if (o.checkpoint_seconds <= 0.0) bad_value(arg, v, "a positive number of seconds");
        }
        else if (arg == "--aovs") o.aovs = parse_aov_layers(value());
        else if (arg == "--threads") o.threads = static_cast<int>(parse_count(arg, value(), 1, kMaxThreads));
        else if (arg == "--wavefront-size")
            o.render.wavefront_size = static_cast<std::uint32_t>(parse_count(arg, value(), 1024, 1u << 26));
        else if (arg == "--samples-per-pass")
            o.render.samples_per_pass = static_cast<std::uint32_t>(parse_count(arg, value(), 1, 1u << 16));
        else if (arg == "--look-from") o.look_from = Point3(parse_triple(arg, value()));
        else if (arg == "--look-at") o.look_at = Point3(parse_triple(arg, value()));
        else if (arg == "--up") o.up = Vec3(parse_triple(arg, value()));
        else if (arg == "--fov") {
            const std::string v = value();
            const float fov = parse_float(arg, v);
            if (fov <= 0.0f || fov >= 180.0f) bad_value(arg, v, "a vertical field of view in (0, 180) degrees");
            o.fov_degrees = fov;
        }
        else if (arg == "--preview") o.preview = true;
        else if (arg == "--cross-check") {
            o.cross_check = value();
            if (o.cross_check != "vulkan") bad_value(arg, o.cross_check, "vulkan");
        }
        else if (arg == "--vk-device") o.vk_device = value();
        else if (arg == "--consistency") o.consistency = true;
        else if (arg == "--json") o.json_path = value();
        else if (arg == "--heatmap") o.heatmap_dir = value();
        else if (arg == "--gltf-scene") o.gltf_scene = static_cast<int>(parse_count(arg, value(), 0, 1u << 20));
        else if (arg == "--flatten-instances") o.flatten_instances = true;
        else if (!arg.empty() && arg[0] == '-' && arg != "-") throw UsageError("unknown option '" + arg + "'");
        else if (o.scene_path.empty()) o.scene_path = arg;
        else throw UsageError("more than one scene given ('" + o.scene_path + "' and '" + arg + "')");
    }
    if (o.exposure_ev && o.tonemap == Tonemap::None)
        throw UsageError("--exposure has no effect with --tonemap none (use --tonemap clamp)");
    if (o.denoise && o.render.integrator == IntegratorKind::Aov)
        throw UsageError("--denoise needs a rendered image (--integrator path or whitted), not an AOV");
    if (o.up && length(*o.up) == 0.0f) throw UsageError("--up must not be the zero vector");
    if (o.look_from && o.look_at && *o.look_from == *o.look_at)
        throw UsageError("--look-from and --look-at must differ");
    if ((!o.json_path.empty() || !o.heatmap_dir.empty()) && !o.consistency)
        throw UsageError(std::string(o.json_path.empty() ? "--heatmap" : "--json") + " needs --consistency");
    if (o.partial && o.samples_first % o.chunk_samples != 0)
        throw UsageError("--samples " + std::to_string(o.samples_first) + ":" + std::to_string(o.samples_end) +
                         " must start at a multiple of the chunk size (--chunk-samples " +
                         std::to_string(o.chunk_samples) + ")");
    if (o.partial && (!o.resume_path.empty() || o.checkpoint_seconds > 0 || !o.aovs.empty()))
        throw UsageError("--resume, --checkpoint-every and --aovs are for a whole frame, not a --samples range");
    if (!o.resume_path.empty() && std::find_if(o.aovs.begin(), o.aovs.end(), needs_squares) != o.aovs.end())
        throw UsageError("--aovs variance cannot go with --resume: the resumed samples' squares are not kept");
    if (o.render.noise_threshold > 0.0 && o.render.integrator != IntegratorKind::Path)
        throw UsageError(std::string("--noise-threshold needs --integrator path, not ") +
                         (o.render.integrator == IntegratorKind::Aov ? "an AOV" : integrator_name(o.render.integrator)));
    if (o.render.noise_threshold > 0.0 && o.partial)
        throw UsageError("--noise-threshold cannot render a partial image (--samples): its decisions need every "
                         "earlier sample of the frame");
    if (o.render.noise_threshold > 0.0 && (!o.resume_path.empty() || o.checkpoint_seconds > 0))
        throw UsageError("--noise-threshold cannot go with --resume or --checkpoint-every: its check points need "
                         "the squares of every earlier sample, which partial images do not keep");
    if (!o.help && !o.version && !o.list_devices && o.scene_path.empty())
        throw UsageError("no scene given");
    return o;
}

bool names_several_devices(const std::string& device_spec)
{
    return device_spec == "all" || device_spec.find(',') != std::string::npos;
}

std::string version_text() { return "geocold-cl 0.1.0"; }

std::string usage_text()
{
    std::ostringstream s;
    s << R"(Usage: geocold-cl [options] SCENE
       geocold-cl --list-devices
       geocold-cl merge PART.exr... -o FRAME.exr [--spp N]

Renders a Wavefront .obj (with .mtl) or glTF 2.0 (.gltf/.glb) scene with OpenCL, on a GPU
or on the CPU through PoCL; every device renders the same image.

Output:
  -o, --output FILE        image to write; .exr (linear float + metadata), .png (sRGB),
                           .pfm, .ppm. Default: <scene name>.png in the current directory
Device:
  -d, --device SPEC        any | gpu | cpu | <index> | <name substring>   (default: any,
                           which prefers a GPU); all, or a list 0,2: one frame on every
                           device named, each pulling chunks of samples (a CPU device then
                           leaves a core, two from 8 cores on, to the threads that drive
                           the others)
      --list-devices       list the OpenCL devices and exit
      --threads N          CPU threads: PoCL's workers on CPU devices, lavapipe's, and the
                           BVH build (default: every core)
      --vk-device SPEC     Vulkan device for --preview / --cross-check: any | lavapipe |
                           <name substring>   (default: any, which prefers a GPU)
Rendering:
      --integrator NAME    path (default; unbiased path tracer with next-event estimation),
                           whitted (classic ray tracing), aov (first-hit outputs)
      --aov NAME           preview | albedo | normal | depth | primid   (implies
                           --integrator aov); guide-albedo | guide-normal: albedo and
                           normal seen through mirrors and glass (--denoise's guides)
      --spp N              samples per pixel (default 64); with --noise-threshold, the cap
      --noise-threshold T  adaptive sampling: 8x8 tiles stop once the relative standard
                           error of every pixel's mean is below T (e.g. 0.02), checked after
                           16 samples (rounded up to a chunk) and each doubling of that; the
                           same image on every run and device (path integrator only)
      --time-limit SEC     stop after the pass that crosses SEC seconds (whichever of
                           --spp and --time-limit ends first)
      --res WxH            image size (default 512x512); also --width N, --height N
      --max-depth N        path segments: 1 = emitters only, 2 = direct light (default 8)
      --rr-depth N         Russian roulette from this depth on (default 5)
      --seed N             random seed (default 0); same seed, same image
      --sampler NAME       sobol (default: Owen-scrambled Sobol points, least noise at
                           powers of two spp) | independent (hashed random numbers)
      --env R,G,B|FILE     constant environment radiance (default 0,0,0), or a lat-long
                           map (.exr/.hdr/.pfm; +Y up), importance sampled
      --env-scale R,G,B    multiplies the environment map (default 1,1,1)
      --wavefront-size N   paths in flight per pass (default: chosen for the device)
      --samples-per-pass N at most N samples per pixel in one pass (default: on CPUs as
                           many as fill half a second, growing to two in long renders, up
                           to 256; on GPUs as many as the wavefront holds); the image is
                           the same bits either way
Several devices and machines (a frame is a fixed list of chunks of samples):
      --chunk-samples N    samples per chunk (default 64); part of the frame: partial
                           images merge only with the same chunk size
      --checkpoint-every SEC
                           every SEC seconds (at the next complete chunk) and when the
                           render ends or is stopped (Ctrl-C, SIGTERM, --time-limit),
                           write the output so far and <output name>.partial.exr: its
                           complete chunks, for --resume
      --resume PART.exr    go on from a checkpoint or a --samples 0:B partial image to
                           --spp: the bits of an uninterrupted render; refuses another
                           scene, options, seed, size or chunk size (exit 3)
      --samples A:B        render samples [A, B) only (A a multiple of the chunk size)
                           into a partial image (.exr with per-chunk sums and counts, scene
                           and options hashes); a partial render stopped by Ctrl-C or
                           SIGTERM writes nothing (exit 130)
  merge PART.exr... -o FRAME.exr [--spp N]
                           add partial images into the frame in chunk order (the bits of one
                           render); refuses different scenes, options or seeds (exit 3) and
                           overlapping or missing samples (exit 7, listing the ranges), and
                           then writes nothing; --spp N: the frame must end at sample N
AOV layers:
      --aovs LIST          also write <output name>.aovs.exr, a multi-part OpenEXR with one
                           part per layer: albedo, normal (16 spp), depth, primid (first
                           sample), variance, sample-count (the beauty's), comma-separated
Display (8-bit outputs: .png, .ppm; .exr/.pfm/.hdr/.tif are always linear):
      --tonemap NAME       pbr-neutral (default; Khronos PBR Neutral: base colours kept,
                           highlights rolled off) | agx (Blender's AgX) | aces (Narkowicz's
                           ACES fit) | clamp (clip at 1) | none (no exposure, clip at 1;
                           the default for --aov outputs)
      --exposure EV        scale by 2^EV before the curve (default 0)
Denoising:
      --denoise            denoise the image with Intel Open Image Denoise (CPU), guided
                           by albedo and normal AOVs seen through mirrors and glass;
                           needs libOpenImageDenoise.so.2 (tools/install-deps.sh installs
                           it; GEOCOLD_OIDN_LIBRARY names it)
Camera (the file's camera if it has one, else framed on the scene bounds):
      --look-from X,Y,Z    --look-at X,Y,Z    --up X,Y,Z    --fov DEGREES (vertical)
      --aperture R         thin-lens depth of field: the lens radius in scene units
                           (default 0, a pinhole)
      --focus-distance D   the distance in focus, along the view axis (default: to the
                           look-at point)
Vulkan (when built with it):
      --preview            draw the rasterised mesh pass (albedo under a headlight) with
                           Vulkan instead of rendering; no OpenCL needed
      --cross-check vulkan render with OpenCL and with Vulkan, print how far apart they
                           are (primitive ids, depth, radiance); exit 6 beyond tolerance
Consistency (same image on every device):
      --consistency        render on every OpenCL device (and Vulkan when built) with one
                           seed/spp/size (default 64 spp, 128x128) and compare each pair:
                           relative MSE, max |difference|, % of pixels within 1e-3
                           relative; exit 6 when a pair fails, 0 with a SKIPPED note when
                           fewer than two devices exist
      --json FILE          with --consistency: also write the figures as JSON
      --heatmap DIR        with --consistency: a difference heat map per pair (PNG, or PPM
                           without OpenImageIO)
Scene:
      --gltf-scene N       which scene of a glTF file (default: the file's default scene)
      --flatten-instances  copy a glTF's reused meshes into one flat scene (by default each
                           mesh is kept once on the device, drawn by instances through a
                           two-level BVH)
Other:
  -q, --quiet              no progress bar (it is also off when stderr is not a terminal)
  -v, --verbose            more detail (kernel build and cache, timings)
  -h, --help               this text;   --version   the version

Environment:
  GEOCOLD_KERNEL_DIR       where the OpenCL kernels are (default: built-in path)
  GEOCOLD_CACHE_DIR        kernel binary cache (default: $XDG_CACHE_HOME/geocold-cl)
  GEOCOLD_NO_CACHE=1       do not read or write the kernel binary cache
  GEOCOLD_CACHE_ALWAYS=1   write it on PoCL too (by default PoCL's own cache is used there)
  GEOCOLD_PATH_KERNEL      wavefront|megakernel: the path integrator's form (default:
                           megakernel on CPUs, wavefront on GPUs; same image either way)
  GEOCOLD_BVH_WIDTH        2|4|8: the BVH layout traversed (default: 8 on CPUs with AVX,
                           where one ray tests 8 boxes at once, else 4; 2 on GPUs; same
                           image either way)
  GEOCOLD_KERNEL_FEATURES  scene|all: compile the kernels for the scene's features only
                           (default: scene; smaller, faster programs) or all of them (same
                           image either way)
  GEOCOLD_IMAGE_MODULE     the OpenImageIO module, loaded only for formats that are not
                           built in (.exr, .hdr, .tif, reading .png; .pfm/.ppm and writing
                           .png need none). Default: geocold-image-oiio.so beside
                           geocold-cl, else ../lib/geocold-cl/geocold-image-oiio.so
  GEOCOLD_OIDN_LIBRARY     Open Image Denoise for --denoise (default:
                           /opt/geocold-cl/oidn/lib/libOpenImageDenoise.so.2, where
                           tools/install-deps.sh puts it, else the system's)
  GEOCOLD_GUARD_BUFFERS=1  a debugging aid on CPU devices: every device buffer ends at an
                           inaccessible page, so a kernel reading past its end crashes
                           there (slower; as a GPU would fault) instead of reading on

Exit status:
  0 success   2 bad command line   3 unreadable or malformed input file
  4 no usable device or a device failure   5 output could not be written
  6 a cross-check or consistency run found images that disagree   130 interrupted (partial image written)
  7 merge: partial images that overlap or leave samples missing
  1 internal error (a bug: please report it)
)";
    return s.str();
}

SceneRequest scene_request(const Options& options)
{
    SceneRequest request;
    request.path = options.scene_path;
    request.load.gltf_scene = options.gltf_scene;
    request.camera.look_from = options.look_from;
    request.camera.look_at = options.look_at;
    request.camera.up = options.up;
    request.camera.fov = options.fov_degrees;
    request.camera.aperture_radius = options.aperture_radius;
    request.camera.focus_distance = options.focus_distance;
    return request;
}

}  // namespace gc
