// geocold-grad-bench: one optimisation iteration of the Cornell box (issue 43 item 5), timed,
// with the device bytes it holds, and the gradients' bits for a determinism check (item 3).
//
//   geocold-grad-bench [--device SPEC[,SPEC]] [--sizes 128:4,512:16] [--depth 6] [--repeats N]
//                      [--memory-size 512:16] [--memory-depths 6,64] [--params leftWall|walls]
//                      [--threads N] [--samples-per-item N]
//                      [--primal auto|kernel|wavefront] [--no-time]
//                      [--no-memory] [--determinism] [--view]
//
// An iteration is what an optimiser's step costs: Renderer::render of spp samples (film
// cleared first), the film read back with the loss mean(image) computed on the host, and
// PathAdjoint::backward of d loss / d image for the parameters, spp samples of its own.
// Compile time (the renderer's and the adjoint's programs, and the first iteration, which
// may build more) is reported apart from the median of --repeats iterations after it.
// Memory: the bytes in OpenCL buffers (our own count, cl_alloc_count.h) at their peak over
// set-up and one iteration, at each of --memory-depths; the adjoint replays paths instead of
// storing their vertices, so depth should not change it.
//
// A tool of its own rather than a geocold-bench mode: its unit is an iteration, not samples
// per second, its options share nothing with geocold-bench's, and it counts buffers by
// standing in for clCreateBuffer, which is better kept out of geocold-bench's process.
// Prints a table, then one JSON line (the last line of stdout).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/bvh/bvh.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/render/device_scene.h"
#include "host/render/environment.h"
#include "host/render/gradients.h"
#include "host/render/renderer.h"
#include "host/util/error.h"
#include "host/util/host_threads.h"
#include "tools/bench/bench_environment.h"
#include "tools/bench/bench_scenes.h"
#include "tools/bench/cl_alloc_count.h"
#include "tools/bench/timing.h"

namespace gc::bench {
namespace {

using nlohmann::json;

struct Size {
    int side = 0;
    int spp = 0;
};

struct GradOptions {
    std::vector<std::string> devices{"any"};
    std::vector<Size> sizes{{128, 4}, {512, 16}};
    Size memory_size{512, 16};
    std::vector<int> memory_depths{6, 64};
    int depth = 6;
    int repeats = 5;
    int threads = 0;
    std::string params = "leftWall";
    AdjointOptions adjoint;
    bool time = true;
    bool memory = true;
    bool determinism = false;
    bool view = false;
};

const char* kUsage =
    "Usage: geocold-grad-bench [options]\n"
    "One iteration (render + backward) of the Cornell box, timed, with its device memory.\n"
    "  --device SPEC[,SPEC]  OpenCL devices (any, cpu, gpu, an index; default any)\n"
    "  --sizes LIST          SIDE:SPP per size, SPP for the render and for backward each (default 128:4,512:16)\n"
    "  --depth N             max path depth of the timed iterations (default 6)\n"
    "  --repeats N           timed iterations per size, after a first untimed one (default 5)\n"
    "  --memory-size SIDE:SPP  the size of the memory figures (default 512:16)\n"
    "  --memory-depths LIST  depths of the memory figures (default 6,64)\n"
    "  --params leftWall|walls  materials/leftWall/base_color, or every non-emitting material's base_color\n"
    "  --threads N           CPU device threads (PoCL)\n"
    "  --samples-per-item N  samples of a pixel one adjoint work-item traces (default: the device's choice)\n"
    "  --primal auto|kernel|wavefront  where the adjoint learns each sample's radiance (default auto:\n"
    "                        the wavefront where the renderer runs it)\n"
    "  --no-time             skip the timed iterations\n"
    "  --no-memory           skip the memory figures\n"
    "  --determinism         per device, two iterations' gradient bits and whether they agree; across\n"
    "                        devices, the largest relative difference (at the first size and --depth)\n"
    "  --view                print the scene, camera and settings as JSON and exit\n"
    "  -h, --help            this text\n"
    "Exit status: 0 success (and, with --determinism, bit-identical gradients run to run), 1 an error\n"
    "or gradients that differ run to run, 2 bad usage.\n";

std::vector<std::string> split(const std::string& s)
{
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= s.size()) {
        const std::size_t comma = s.find(',', start);
        const std::size_t end = comma == std::string::npos ? s.size() : comma;
        if (end > start) out.push_back(s.substr(start, end - start));
        start = end + 1;
    }
    return out;
}

int positive(const std::string& option, const std::string& text)
{
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || v < 1 || v > 1 << 16)
        throw UsageError(option + ": '" + text + "' is not a whole number from 1 to 65536");
    return static_cast<int>(v);
}

Size parse_size(const std::string& option, const std::string& text)
{
    const std::size_t colon = text.find(':');
    if (colon == std::string::npos) throw UsageError(option + ": '" + text + "' is not SIDE:SPP");
    return {positive(option, text.substr(0, colon)), positive(option, text.substr(colon + 1))};
}

GradOptions parse(int argc, char** argv)
{
    GradOptions o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw UsageError(a + " needs a value");
            return argv[++i];
        };
        if (a == "-h" || a == "--help") {
            std::fputs(kUsage, stdout);
            std::exit(0);
        } else if (a == "--device") {
            o.devices = split(value());
            if (o.devices.empty()) throw UsageError("--device: no device named");
        } else if (a == "--sizes") {
            o.sizes.clear();
            for (const std::string& s : split(value())) o.sizes.push_back(parse_size(a, s));
            if (o.sizes.empty()) throw UsageError("--sizes: no size given");
        } else if (a == "--memory-size") {
            o.memory_size = parse_size(a, value());
        } else if (a == "--memory-depths") {
            o.memory_depths.clear();
            for (const std::string& s : split(value())) o.memory_depths.push_back(positive(a, s));
            if (o.memory_depths.empty()) throw UsageError("--memory-depths: no depth given");
        } else if (a == "--depth") {
            o.depth = positive(a, value());
        } else if (a == "--repeats") {
            o.repeats = positive(a, value());
        } else if (a == "--threads") {
            o.threads = positive(a, value());
        } else if (a == "--params") {
            o.params = value();
            if (o.params != "leftWall" && o.params != "walls")
                throw UsageError("--params: '" + o.params + "' is neither leftWall nor walls");
        } else if (a == "--primal") {
            const std::string v = value();
            if (v == "auto") o.adjoint.primal = PrimalPass::Auto;
            else if (v == "kernel") o.adjoint.primal = PrimalPass::InKernel;
            else if (v == "wavefront") o.adjoint.primal = PrimalPass::Wavefront;
            else throw UsageError("--primal: '" + v + "' is not auto, kernel or wavefront");
        } else if (a == "--samples-per-item") {
            o.adjoint.samples_per_item = positive(a, value());
        } else if (a == "--no-time") {
            o.time = false;
        } else if (a == "--no-memory") {
            o.memory = false;
        } else if (a == "--determinism") {
            o.determinism = true;
        } else if (a == "--view") {
            o.view = true;
        } else {
            throw UsageError("unknown option '" + a + "' (--help lists them)");
        }
    }
    return o;
}

RenderSettings settings_for(const BenchScene& s, Size size, int depth)
{
    RenderSettings r;
    r.width = r.height = static_cast<std::uint32_t>(size.side);
    r.spp = static_cast<std::uint32_t>(size.spp);
    r.max_depth = static_cast<std::uint32_t>(depth);
    r.rr_depth = static_cast<std::uint32_t>(depth + 1);  // no Russian roulette, as Mitsuba is run
    r.env_radiance = s.env;
    r.seed = 0;
    r.sampler = SamplerKind::Independent;  // as Mitsuba's prb is run (its independent sampler)
    return r;
}

std::vector<std::string> param_names(const Scene& scene, const std::string& which)
{
    if (which == "leftWall") return {"materials/leftWall/base_color"};
    std::vector<std::string> names;
    for (const Material& m : scene.materials)
        if (!m.is_emissive()) names.push_back("materials/" + m.name + "/base_color");
    return names;
}

// One device's scene, renderer and adjoint at one size and depth.
struct Rig {
    std::unique_ptr<Renderer> renderer;
    std::unique_ptr<PathAdjoint> adjoint;
    std::vector<glm::vec4> loss_grad;
    Size size;

    Rig(const cl::Context& context, std::shared_ptr<const DeviceScene> device, const BenchScene& s, Size sz,
        int depth, const AdjointOptions& options)
        : size(sz)
    {
        renderer = std::make_unique<Renderer>(context, std::move(device), s.camera, settings_for(s, sz, depth),
                                              bench_render_setup());
        adjoint = std::make_unique<PathAdjoint>(*renderer, options);
        // d mean(image) / d pixel, per colour channel.
        const float g = 1.0f / (3.0f * float(sz.side) * float(sz.side));
        loss_grad.assign(std::size_t(sz.side) * std::size_t(sz.side), glm::vec4(g, g, g, 0.0f));
    }

    // One iteration; returns the loss.
    double iterate(const Scene& scene, const std::vector<std::string>& params, std::uint32_t seed, Gradients* out)
    {
        renderer->clear(0);
        renderer->render(0, static_cast<std::uint32_t>(size.spp));
        const Film film = renderer->film();
        double loss = 0.0;
        for (std::uint32_t y = 0; y < film.height(); ++y)
            for (std::uint32_t x = 0; x < film.width(); ++x) {
                const float* p = film.pixel(x, y);
                loss += double(p[0]) + double(p[1]) + double(p[2]);
            }
        loss /= 3.0 * double(film.width()) * double(film.height());
        Gradients g = adjoint->backward(*renderer, scene, loss_grad, params, static_cast<std::uint32_t>(size.spp),
                                        seed);
        if (out) *out = std::move(g);
        return loss;
    }
};

std::string label(int index, const cl::DeviceInfo& d)
{
    return "[" + std::to_string(index) + "] " + d.device_name;
}

json time_sizes(const cl::Context& context, const std::shared_ptr<const DeviceScene>& device, const BenchScene& s,
                const GradOptions& o, const std::vector<std::string>& params)
{
    json out = json::array();
    for (const Size& size : o.sizes) {
        const auto start = Clock::now();
        Rig rig(context, device, s, size, o.depth, o.adjoint);
        const double build_s = seconds_since(start);
        const auto first = Clock::now();
        Gradients g;
        rig.iterate(s.scene, params, 1000, &g);
        const double first_s = seconds_since(first);
        std::vector<double> times;
        double loss = 0.0;
        for (int r = 0; r < o.repeats; ++r) {
            const auto t = Clock::now();
            loss = rig.iterate(s.scene, params, 1001 + static_cast<std::uint32_t>(r), &g);
            times.push_back(seconds_since(t));
        }
        const double med = median(times);
        const auto [lo, hi] = std::minmax_element(times.begin(), times.end());
        const std::vector<float>& left = g.at(params.front());
        std::printf("  %4dx%-4d spp %2d+%-2d depth %2d  programs %7.3f s  first iteration %7.3f s  iteration "
                    "%8.4f s (median of %d, %.4f-%.4f)  loss %.5f  d/d %s = (%.4g, %.4g, %.4g)\n",
                    size.side, size.side, size.spp, size.spp, o.depth, build_s, first_s, med, o.repeats, *lo, *hi,
                    loss, params.front().c_str(), left[0], left[1], left[2]);
        std::fflush(stdout);
        out.push_back({{"side", size.side}, {"spp", size.spp}, {"depth", o.depth}, {"programs_s", build_s},
                       {"first_iteration_s", first_s}, {"iteration_median_s", med}, {"iteration_s", times},
                       {"loss", loss}, {"params", params.size()}, {"gradient_first", {params.front(), left}}});
    }
    return out;
}

json measure_memory(const cl::Context& context, const std::shared_ptr<const DeviceScene>& device,
                    const BenchScene& s, const GradOptions& o, const std::vector<std::string>& params)
{
    json out = json::array();
    double first_peak = 0.0;
    for (int depth : o.memory_depths) {
        const AllocCount before = alloc_count();
        reset_alloc_peak();
        {
            Rig rig(context, device, s, o.memory_size, depth, o.adjoint);
            rig.iterate(s.scene, params, 1000, nullptr);
        }
        const AllocCount after = alloc_count();
        const double peak = double(after.peak);
        const double own = double(after.peak - before.live);
        if (first_peak == 0.0) first_peak = peak;
        std::printf("  memory %dx%d spp %d+%d depth %2d: peak %.2f MiB in OpenCL buffers (scene %.2f MiB, renderer + "
                    "adjoint %.2f MiB) = %.3fx depth %d's\n",
                    o.memory_size.side, o.memory_size.side, o.memory_size.spp, o.memory_size.spp, depth,
                    peak / 1048576.0, double(before.live) / 1048576.0, own / 1048576.0, peak / first_peak,
                    o.memory_depths.front());
        std::fflush(stdout);
        out.push_back({{"depth", depth}, {"side", o.memory_size.side}, {"spp", o.memory_size.spp},
                       {"peak_bytes", after.peak}, {"scene_bytes", before.live},
                       {"renderer_adjoint_bytes", after.peak - before.live}, {"ratio_to_first", peak / first_peak}});
    }
    return out;
}

std::string hex_bits(float f)
{
    std::uint32_t u = 0;
    std::memcpy(&u, &f, sizeof u);
    char buf[16];
    std::snprintf(buf, sizeof buf, "%08x", u);
    return buf;
}

// Two iterations' gradients (same seeds); prints their bits. Sets *same when they agree.
std::vector<float> gradient_bits(const cl::Context& context, const std::shared_ptr<const DeviceScene>& device,
                                 const BenchScene& s, const GradOptions& o, const std::vector<std::string>& params,
                                 bool* same, json& j)
{
    std::vector<std::vector<float>> runs;
    for (int run = 0; run < 2; ++run) {
        Rig rig(context, device, s, o.sizes.front(), o.depth, o.adjoint);
        Gradients g;
        rig.iterate(s.scene, params, 1000, &g);
        std::vector<float> flat;
        for (const std::string& p : params) flat.insert(flat.end(), g[p].begin(), g[p].end());
        runs.push_back(std::move(flat));
    }
    *same = runs[0].size() == runs[1].size() &&
            std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * sizeof(float)) == 0;
    std::string bits;
    for (float f : runs[0]) bits += (bits.empty() ? "" : " ") + hex_bits(f);
    std::printf("  gradient bits run 1: %s\n  run to run: %s\n", bits.c_str(),
                *same ? "bit-identical" : "DIFFERENT");
    j = {{"bits", bits}, {"values", runs[0]}, {"bit_identical", *same}};
    return runs[0];
}

int run(int argc, char** argv)
{
    const GradOptions o = parse(argc, argv);
    bench_render_setup();
    if (o.threads > 0) {
        set_host_thread_count(o.threads);
        cl::limit_cpu_device_threads(o.threads);
    }
    std::string why;
    std::optional<BenchScene> s = load_bench_scene("cornell", default_shared_dir(), &why);
    if (!s) throw InputError("the Cornell box is missing: " + why);
    const std::vector<std::string> params = param_names(s->scene, o.params);
    const auto xyz = [](auto v) { return json::array({v.x, v.y, v.z}); };
    json view = {{"source", s->scene.source_path}, {"look_from", xyz(s->camera.look_from)},
                 {"look_at", xyz(s->camera.look_at)}, {"up", xyz(s->camera.up)},
                 {"fov", s->camera.vfov_degrees}, {"env", xyz(s->env)}, {"depth", o.depth},
                 {"rr_depth", o.depth + 1}, {"params", params}};
    if (o.view) {
        std::printf("%s\n", view.dump().c_str());
        return 0;
    }
    const std::vector<cl::DeviceInfo> all = cl::list_devices(&why);
    if (all.empty()) throw DeviceError("no OpenCL device found: " + why);
    json doc = {{"tool", "geocold-grad-bench"}, {"view", view}, {"repeats", o.repeats}};
    const FlatBvh bvh = build_bvh(s->scene);
    std::vector<std::vector<float>> bits;
    bool all_same = true;
    for (const std::string& spec : o.devices) {
        const cl::DeviceInfo info = cl::select_device(spec, all);
        int index = 0;
        for (std::size_t i = 0; i < all.size(); ++i)
            if (all[i].id == info.id) index = static_cast<int>(i);
        const std::string name = label(index, info);
        cl::Context context(info);
        const AllocCount empty = alloc_count();
        auto device = std::make_shared<DeviceScene>(
            DeviceScene::upload(context, s->scene, bvh, load_environment_map(settings_for(*s, o.sizes.front(), 6))));
        std::printf("geocold-grad-bench on %s (%s): Cornell box, %zu parameter(s) (%s), scene %.2f MiB on the device\n",
                    name.c_str(), info.platform_name.c_str(), params.size(), o.params.c_str(),
                    double(alloc_count().live - empty.live) / 1048576.0);
        std::fflush(stdout);
        json& d = doc["devices"][name];
        d["gpu"] = info.is_gpu;
        if (o.time) d["sizes"] = time_sizes(context, device, *s, o, params);
        if (o.memory) d["memory"] = measure_memory(context, device, *s, o, params);
        if (o.determinism) {
            bool same = false;
            bits.push_back(gradient_bits(context, device, *s, o, params, &same, d["determinism"]));
            all_same = all_same && same;
        }
    }
    if (bits.size() >= 2) {
        double worst = 0.0;
        for (std::size_t i = 0; i < bits[0].size() && i < bits[1].size(); ++i) {
            const double a = bits[0][i], b = bits[1][i];
            const double scale = std::max(std::fabs(a), std::fabs(b));
            if (scale > 0.0) worst = std::max(worst, std::fabs(a - b) / scale);
        }
        std::printf("  %s vs %s: largest relative difference %.3g\n", o.devices[0].c_str(), o.devices[1].c_str(),
                    worst);
        doc["relative_difference"] = worst;
    }
    std::printf("%s\n", doc.dump().c_str());
    return o.determinism && !all_same ? 1 : 0;
}

}  // namespace
}  // namespace gc::bench

int main(int argc, char** argv)
{
    try {
        return gc::bench::run(argc, argv);
    } catch (const gc::UsageError& e) {
        std::fprintf(stderr, "geocold-grad-bench: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geocold-grad-bench: %s\n", e.what());
        return 1;
    }
}
