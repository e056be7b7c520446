// geocold-bench: BVH build speed and quality, ray throughput, path-traced samples per second
// and time to first image, for every OpenCL device, with Embree 3 on the same CPU (same
// triangles, same rays, same run) as the yardstick beside every figure.
//
//   geocold-bench [--device all|SPEC] [--scene cornell,bunny,dragon,large] [--quick] [--json]
//                 [--repeats N] [--rays SIDE] [--no-path] [--no-rays] [--no-first-image]
//                 [--no-packet-probe] [--threads N] [--wavefront N] [--samples-per-pass N]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "host/bvh/bvh.h"
#include "host/bvh/widen.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/render/pass_planner.h"
#include "host/util/error.h"
#include "host/util/host_threads.h"
#include "tools/bench/bench_scenes.h"
#include "tools/bench/embree_bench.h"
#include "tools/bench/first_image.h"
#include "tools/bench/host_cpu.h"
#include "tools/bench/issue_roofline.h"
#include "tools/bench/ocl_bench.h"
#include "tools/bench/packet_probe.h"
#include "tools/bench/rays.h"
#include "tools/bench/timing.h"

namespace gc::bench {
namespace {

using nlohmann::json;

// Anchors from issue 6 (measured independently; see the issue for conditions). They are
// fixed figures from another day and load, so the ratios to them move with this machine's
// speed: tools/bench/mitsuba_yardstick.py times Mitsuba 3 in the same run instead. On the
// 2-core VM on 2026-12-01, one quiet hour: Mitsuba llvm_ad_rgb ran 1.84 M Cornell samples/s on
// one thread, not 0.96 M, and our 1.27 M read 1.33x this anchor but 0.69x Mitsuba.
constexpr double kMitsubaLlvmPerThread = 0.96e6; // Cornell 512x512, depth 8, 1 thread: 0.92-1.0 Msamples/s
constexpr double kMitsubaCudaCornell = 221e6;    // H200, Cornell 512x512
constexpr double kMitsubaCudaDragon = 410e6;     // H200, dragon under a constant environment, 320x240

// The path figures' settings, as the anchors': max depth 8 and no Russian roulette.
constexpr int kPathMaxDepth = 8;
constexpr int kPathRrDepth = kPathMaxDepth + 1;

struct Options {
    std::string device = "all";
    std::vector<std::string> scenes;
    bool quick = false;
    bool json_out = false;
    int repeats = 5;
    int ray_side = 1024;
    bool path = true;
    bool packet_probe = true;
    bool rays = true;
    bool first_image = true;
    int threads = 0;                // --threads: 0 = every core
    int wavefront = 0;              // --wavefront: paths in flight per pass, 0 = the renderer's default
    int samples_per_pass = 0;       // --samples-per-pass: a fixed count, 0 = the renderer's plan
    std::string first_image_child; // the device key (device_key()) in the child process
    std::string first_image_scene = "cornell"; // and the scene it renders
    bool list_device_keys = false;  // child: print "<label>\t<key>" per selected device
};

std::vector<std::string> split(const std::string& s)
{
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

Options parse(int argc, char** argv)
{
    Options o;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw UsageError(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    auto integer = [&](int& i, long lo = 0, long hi = 1 << 20) {
        const std::string v = value(i);
        char* end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (!end || *end || n < lo || n > hi)
            throw UsageError(std::string(argv[i - 1]) + " wants an integer from " +
                             std::to_string(lo) + " to " + std::to_string(hi) + ", got '" + v + "'");
        return static_cast<int>(n);
    };
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--device") o.device = value(i);
        else if (a == "--scene") o.scenes = split(value(i));
        else if (a == "--quick") o.quick = true;
        else if (a == "--json") o.json_out = true;
        else if (a == "--repeats") o.repeats = std::max(1, integer(i));
        else if (a == "--rays") o.ray_side = std::max(1, integer(i));
        else if (a == "--no-path") o.path = false;
        else if (a == "--no-rays") o.rays = false;
        else if (a == "--no-first-image") o.first_image = false;
        else if (a == "--no-packet-probe") o.packet_probe = false;
        else if (a == "--threads") o.threads = integer(i, 1, 4096);
        else if (a == "--wavefront") o.wavefront = integer(i, 1, 1 << 24);
        else if (a == "--samples-per-pass") o.samples_per_pass = integer(i, 0, 1 << 16);
        else if (a == "--first-image-child") o.first_image_child = value(i);
        else if (a == "--first-image-scene") o.first_image_scene = value(i);
        else if (a == "--list-device-keys") o.list_device_keys = true;
        else if (a == "--help" || a == "-h") {
            std::printf("usage: geocold-bench [--device all|gpu|cpu|N|text] [--scene cornell,bunny,dragon,large]\n"
                        "                     [--quick] [--json] [--repeats N] [--rays SIDE] [--no-path]\n"
                        "                     [--no-rays] [--no-first-image] [--no-packet-probe] [--threads N]\n"
                        "                     [--wavefront N] [--samples-per-pass N]\n"
                        "--threads N caps every CPU thread of the run: PoCL's workers, Embree's and the host's\n"
                        "(default: every core). With --threads 1 the per-core figure is one thread's, the\n"
                        "conditions of the Mitsuba llvm_ad_rgb anchor.\n"
                        "--json puts each scene's view in the document too; tools/bench/mitsuba_yardstick.py\n"
                        "reads it to time Mitsuba 3 on the same view in the same run (the anchors are fixed\n"
                        "figures from another day).\n"
                        "--wavefront N and --samples-per-pass N (0: the default) fix what the renderer otherwise\n"
                        "chooses per device: paths in flight per pass, and samples per pixel in one pass (a CPU\n"
                        "plans passes of half a second, in long runs up to two, and up to 256 samples:\n"
                        "host/render/pass_planner.h).\n");
            std::exit(0);
        } else {
            throw UsageError("unknown option '" + a + "' (see --help)");
        }
    }
    if (o.quick) {
        o.repeats = 1;
        o.ray_side = std::min(o.ray_side, 64);
        if (o.scenes.empty()) o.scenes = {"tiny"};
    }
    if (o.scenes.empty()) o.scenes = default_scene_names();
    return o;
}

// Text goes to stdout, or to stderr when stdout carries the JSON document.
FILE* g_text = stdout;

void say(const char* format, ...)
{
    va_list args;
    va_start(args, format);
    std::vfprintf(g_text, format, args);
    va_end(args);
    std::fflush(g_text);
}

std::string ratio(double ours, double theirs)
{
    if (!(theirs > 0.0) || !(ours > 0.0)) return "n/a";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.2fx", ours / theirs);
    return buffer;
}

double json_number(double v) { return std::isfinite(v) ? v : 0.0; }

struct DeviceSlot {
    int index = 0;
    cl::DeviceInfo info;
    std::unique_ptr<cl::Context> context;
    double bandwidth = 0.0; // bytes/s, GPUs only
    IssueModel issue;       // the roofline's instruction half, GPUs only (issue_roofline.h)
    // Short: "[0] PoCL cpu"; the header line gives the full device name.
    std::string label() const
    {
        const std::string& p = info.platform_name;
        std::string s = "[";
        s += std::to_string(index);
        s += "] ";
        s += p.find("Portable") != std::string::npos ? std::string("PoCL") : p.substr(0, p.find(' '));
        s += " ";
        s += info.type_name();
        return s;
    }
};

struct RayKind {
    const char* name;
    const std::vector<dev::GcRay>* rays;
    bool any;
};

double agreement(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b)
{
    if (a.empty() || a.size() != b.size()) return 0.0;
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.size(); ++i) same += a[i] == b[i];
    return double(same) / double(a.size());
}

// Our forms of tracing `kind`: single rays, and packets of eight where the tracer has them
// (closest hits only: there is no any-hit packet). Seconds: one entry per timed trace of the
// set; results: the last trace's.
struct DeviceRays {
    std::vector<double> single_seconds;
    std::vector<double> packet_seconds;
    std::vector<std::uint32_t> single_result;
    std::vector<std::uint32_t> packet_result;
};

bool traces_packets(const RayKind& kind, const OclTracer& tracer) { return !kind.any && tracer.has_packets(); }

// Traces the set `repeats` times in each form, appending to `out`; returns our faster form's
// rays per second in the last of them.
double trace_on_device(const RayKind& kind, OclTracer& tracer, int repeats, DeviceRays& out)
{
    const double n = double(kind.rays->size());
    const std::vector<double> single = kind.any ? tracer.occluded(*kind.rays, repeats, out.single_result)
                                                : tracer.closest(*kind.rays, repeats, out.single_result);
    out.single_seconds.insert(out.single_seconds.end(), single.begin(), single.end());
    double best = single.empty() || !(single.back() > 0.0) ? 0.0 : n / single.back();
    if (traces_packets(kind, tracer)) {
        const std::vector<double> packets = tracer.closest_packets(*kind.rays, repeats, out.packet_result);
        out.packet_seconds.insert(out.packet_seconds.end(), packets.begin(), packets.end());
        if (!packets.empty() && packets.back() > 0.0) best = std::max(best, n / packets.back());
    }
    return best;
}

// A CPU device's timings, in rounds interleaved with Embree on the same cores: each round
// times Embree's single-ray and 16-wide calls and then the device once in each of its forms,
// so a change in the machine's load between them hits both sides alike. (Separate runs,
// Embree's first, moved the ratio by up to 1.6x between runs a minute apart on a shared VM.)
// Returns the median of the per-round ratios, our faster form to Embree's.
double trace_interleaved(const RayKind& kind, const EmbreeTracer& embree, OclTracer& tracer, int threads, int rounds,
                         DeviceRays& result)
{
    std::vector<double> ratios;
    std::vector<std::uint32_t> embree_scratch;
    for (int r = 0; r < rounds; ++r) {
        double embree_best = 0.0;
        for (int width : {1, 16}) {
            const double t = kind.any ? embree.occluded(*kind.rays, threads, width, embree_scratch)
                                      : embree.closest(*kind.rays, threads, width, embree_scratch);
            embree_best = std::max(embree_best, double(kind.rays->size()) / t);
        }
        const double ours = trace_on_device(kind, tracer, 1, result);
        if (ours > 0.0) ratios.push_back(ours / embree_best);
    }
    return ratios.empty() ? 0.0 : median(ratios);
}

void bench_rays(const BenchScene& s, const Options& o, std::vector<DeviceSlot>& devices, const FlatBvh& bvh,
                const EmbreeTracer* embree, json& out)
{
    const int threads = host_thread_count();
    const auto rays_start = Clock::now();
    const int side = o.ray_side;
    const RaySet set = make_rays(s.scene, bvh, s.camera, side, side, threads);
    say("rays: %zu primary (%dx%d), %zu diffuse, %zu shadow (made in %.2f s)\n", set.primary.size(), side, side,
        set.diffuse.size(), set.shadow.size(), seconds_since(rays_start));
    const RayKind kinds[] = {{"primary", &set.primary, false}, {"diffuse", &set.diffuse, false}, {"shadow", &set.shadow, true}};

    double embree_best[3] = {0, 0, 0};
    std::vector<std::uint32_t> embree_result[3];
    if (embree) {
        for (int k = 0; k < 3; ++k) {
            const RayKind& kind = kinds[k];
            double best = 0.0;
            std::string line;
            for (int width : {1, 16}) {
                std::vector<double> times;
                std::vector<std::uint32_t> result;
                for (int r = 0; r < o.repeats + 1; ++r) {
                    const double t = kind.any ? embree->occluded(*kind.rays, threads, width, result)
                                              : embree->closest(*kind.rays, threads, width, result);
                    if (r > 0 || o.repeats == 1) times.push_back(t);
                }
                const double mrays = double(kind.rays->size()) / median(times) / 1e6;
                out["rays"][kind.name]["embree"][width == 1 ? "single" : "packet16"] = json_number(mrays);
                char buffer[96];
                std::snprintf(buffer, sizeof buffer, "%s %.2f", width == 1 ? (kind.any ? "rtcOccluded1" : "rtcIntersect1")
                                                                           : (kind.any ? "rtcOccluded16" : "rtcIntersect16"),
                              mrays);
                line += std::string(line.empty() ? "" : ", ") + buffer;
                if (mrays > best) {
                    best = mrays;
                    embree_result[k] = result;
                }
            }
            embree_best[k] = best;
            out["rays"][kind.name]["embree"]["best"] = json_number(best);
            say("  Embree %-7s (%d threads): %s Mrays/s\n", kind.name, threads, line.c_str());
        }
    }

    bool have_cost = false;
    TraversalCost cost[3];
    for (DeviceSlot& d : devices) {
        OclTracer tracer(*d.context, bvh);
        const int repeats = d.info.is_gpu ? 4 * o.repeats : o.repeats;
        for (int k = 0; k < 3; ++k) {
            const RayKind& kind = kinds[k];
            // A CPU is timed in the rounds interleaved with Embree; a GPU (or any device when
            // there is no Embree) alone, and compared with Embree's medians above.
            const bool interleave = embree && !d.info.is_gpu;
            DeviceRays traced;
            double to_embree = 0.0;
            if (interleave) to_embree = trace_interleaved(kind, *embree, tracer, threads, repeats, traced);
            else trace_on_device(kind, tracer, repeats, traced);
            const auto mrays_of = [&](const std::vector<double>& t) {
                return t.empty() ? 0.0 : double(kind.rays->size()) / median(t) / 1e6;
            };
            const double single = mrays_of(traced.single_seconds);
            const double packets = mrays_of(traced.packet_seconds);
            const bool packets_lead = packets > single;
            const double mrays = std::max(single, packets);
            // Packets must find the single rays' hits (gc_packet8.h promises the same bits; the
            // device tests check it on test rays, this on every bench set).
            if (traces_packets(kind, tracer) && traced.packet_result != traced.single_result) {
                char buffer[160];
                std::snprintf(buffer, sizeof buffer, "packets of eight found the single rays' hits on only %.3f%% of %zu %s rays",
                              100.0 * agreement(traced.packet_result, traced.single_result), traced.single_result.size(),
                              kind.name);
                throw std::runtime_error(s.name + ", " + d.label() + ": " + buffer);
            }
            const std::vector<std::uint32_t>& result = traced.single_result;
            json& j = out["rays"][kind.name]["devices"][d.label()];
            j["mrays_per_s"] = json_number(mrays);
            j["form"] = packets_lead ? "packets8" : "single";
            j["single_mrays_per_s"] = json_number(single);
            if (traces_packets(kind, tracer)) j["packets8_mrays_per_s"] = json_number(packets);
            j["bvh_layout"] = tracer.layout();  // BVH2 on GPUs, BVH8 or BVH4 on CPUs
            std::string form = tracer.layout();
            if (traces_packets(kind, tracer)) {
                char buffer[128];
                std::snprintf(buffer, sizeof buffer, packets_lead ? ", packets of 8 neighbouring rays; single rays %.2f"
                                                                  : ", single rays; packets of 8 neighbouring rays %.2f",
                              packets_lead ? single : packets);
                form += buffer;
            }
            std::string extra;
            if (embree) {
                const double agree = agreement(result, embree_result[k]);
                if (!interleave) to_embree = mrays / embree_best[k];
                j["ratio_to_embree"] = json_number(to_embree);
                j["agreement_with_embree"] = agree;
                char buffer[160];
                std::snprintf(buffer, sizeof buffer, " = %.2fx Embree best%s; same result as Embree on %.3f%% of rays",
                              to_embree, interleave ? " (median of per-round ratios)" : "", 100.0 * agree);
                extra += buffer;
            }
            if (d.info.is_gpu && d.bandwidth > 0.0) {
                if (!have_cost) {
                    for (int c = 0; c < 3; ++c) cost[c] = traversal_cost(bvh, *kinds[c].rays, kinds[c].any, 65536);
                    have_cost = true;
                }
                const double bytes = cost[k].bytes_per_ray();
                const double bound = d.bandwidth / bytes / 1e6;
                j["roofline"] = {{"bytes_per_ray", bytes}, {"inner_visits", cost[k].inner_visits},
                                 {"triangle_tests", cost[k].triangle_tests}, {"bound_mrays_per_s", bound},
                                 {"fraction", mrays / bound}};
                char buffer[160];
                std::snprintf(buffer, sizeof buffer,
                              "; uncached roofline %.0f B/ray (%.1f inner, %.1f tris) -> %.0f Mrays/s bound, at %.1f%%",
                              bytes, cost[k].inner_visits, cost[k].triangle_tests, bound, 100.0 * mrays / bound);
                extra += buffer;
                if (d.issue.available) {
                    const double instructions = d.issue.instructions_per_ray(cost[k]);
                    const double issue_bound = d.issue.bound_rays_per_s(cost[k]) / 1e6;
                    j["roofline"]["ptx_instructions_per_ray"] = instructions;
                    j["roofline"]["issue_bound_mrays_per_s"] = issue_bound;
                    j["roofline"]["issue_fraction"] = mrays / issue_bound;
                    std::snprintf(buffer, sizeof buffer, "; issue %.0f PTX instr/ray -> %.0f Mrays/s bound, at %.1f%%",
                                  instructions, issue_bound, 100.0 * mrays / issue_bound);
                    extra += buffer;
                }
            }
            say("  %s %-7s: %.2f Mrays/s (%s)%s\n", d.label().c_str(), kind.name, mrays, form.c_str(), extra.c_str());
        }
    }
}

json bench_scene(const BenchScene& s, const Options& o, std::vector<DeviceSlot>& devices, json& summary)
{
    json out;
    const std::size_t tris = s.scene.triangle_count();
    const int threads = host_thread_count();
    say("\n== scene %s: %zu triangles ==\n", s.name.c_str(), tris);
    out["triangles"] = tris;
    // What the path figures render, so that another renderer can be timed on the same view
    // (tools/bench/mitsuba_yardstick.py reads it). "source" is empty for a generated scene.
    const auto xyz = [](auto v) { return json::array({v.x, v.y, v.z}); };
    out["view"] = {{"source", s.scene.source_path},
                   {"look_from", xyz(s.camera.look_from)},
                   {"look_at", xyz(s.camera.look_at)},
                   {"up", xyz(s.camera.up)},
                   {"fov", s.camera.vfov_degrees},
                   {"width", s.pt_width},
                   {"height", s.pt_height},
                   {"env", xyz(s.env)},
                   {"max_depth", kPathMaxDepth},
                   {"rr_depth", kPathRrDepth}};

    // ---- BVH build: ours vs Embree's binned SAH BVH2 (rtcBuildBVH) with the same constants,
    // in interleaved rounds (ours, then Embree's) so that a change in the machine's load hits
    // both alike: the speed ratio is the median of the per-round ratios. Builds under 0.1 s
    // get at least 9 rounds; one build is too short to time on a shared machine. Each round
    // also times what a CPU render builds before it traces, on both sides: our BVH2 plus its
    // collapse into the BVH8 the CPU kernels trace (widen8, done at upload), and Embree's
    // scene commit (its BVH4/8); the last round's Embree scene traces the rays below.
    const BvhBuildOptions build_options;
    const bool with_embree = embree_available();
    int build_repeats = tris > 1000000 ? std::min(o.repeats, 3) : o.repeats;
    std::vector<double> ours_build, ours_layout, embree_build, build_ratios, collapse, commit, pipeline_ratios;
    std::vector<double> ours_bounds, embree_prims; // the bounds pass each side's time starts with
    FlatBvh bvh;
    EmbreeBuildFigures embree_fig;
    std::unique_ptr<EmbreeTracer> embree;
    for (int r = 0; r < build_repeats; ++r) {
        // The tree (triangle bounds, binned SAH) is what rtcBuildBVH makes; the device layout
        // (flatten: depth-first nodes and the triangles' vertices gathered in leaf order) is
        // timed apart and counted in the CPU start below.
        bvh = build_bvh(s.scene, build_options);
        ours_build.push_back(bvh.tree_seconds);
        ours_bounds.push_back(bvh.bounds_seconds);
        ours_layout.push_back(bvh.build_seconds - bvh.tree_seconds);
        const auto collapse_start = Clock::now();
        const Wide8Bvh wide = widen8(bvh);
        collapse.push_back(seconds_since(collapse_start));
        if (with_embree) {
            embree_fig = embree_build_bvh2(s.scene, build_options);
            embree_build.push_back(embree_fig.bvh2_seconds);
            embree_prims.push_back(embree_fig.prims_seconds);
            build_ratios.push_back(embree_fig.bvh2_seconds / ours_build.back());
            embree.reset();  // one Embree scene at a time: the large one takes gigabytes
            embree = std::make_unique<EmbreeTracer>(s.scene);
            commit.push_back(embree->commit_seconds());
            pipeline_ratios.push_back(commit.back() / (bvh.build_seconds + collapse.back()));
        }
        if (r == 0 && bvh.build_seconds < 0.1 && !o.quick) build_repeats = std::max(build_repeats, 9);
    }
    const BvhStats stats = bvh_stats(bvh, build_options.traversal_cost, build_options.intersection_cost);
    const double ours_build_s = median(ours_build);
    const double ours_mtris = double(tris) / ours_build_s / 1e6;
    const double layout_s = median(ours_layout);
    const double collapse_s = median(collapse);
    // The bounds pass is timed apart on both sides: it is memory-bound and scales unlike the
    // binning below it, so the two parts of a gap are told apart.
    const double bounds_s = median(ours_bounds);
    say("BVH build  ours: %.3f s = %.2f Mtris/s (bounds pass %.3f s), SAH %.2f, %zu nodes, depth %zu (%d threads, "
        "median of %d); device layout %.3f s, BVH8 collapse %.3f s\n",
        ours_build_s, ours_mtris, bounds_s, stats.sah_cost, stats.nodes, stats.max_depth, threads, build_repeats,
        layout_s, collapse_s);
    out["build"] = {{"seconds", ours_build_s}, {"mtris_per_s", ours_mtris}, {"bounds_seconds", bounds_s},
                    {"sah", stats.sah_cost}, {"nodes", stats.nodes}, {"depth", stats.max_depth}, {"rounds", build_repeats},
                    {"layout_seconds", layout_s}, {"bvh8_collapse_seconds", collapse_s}};

    if (with_embree) {
        const double e_s = median(embree_build);
        const double e_mtris = double(tris) / e_s / 1e6;
        const double speed_ratio = median(build_ratios);
        const double commit_s = median(commit);
        const double pipeline_ratio = median(pipeline_ratios);
        const double prims_s = median(embree_prims);
        say("           Embree rtcBuildBVH BVH2: %.3f s = %.2f Mtris/s (primitive array %.3f s), SAH %.2f, %zu nodes | "
            "ours/Embree: speed %.2fx (median of per-round ratios), SAH %s\n",
            e_s, e_mtris, prims_s, embree_fig.bvh2_sah, embree_fig.bvh2_nodes, speed_ratio,
            ratio(stats.sah_cost, embree_fig.bvh2_sah).c_str());
        say("           CPU start: ours BVH2 + device layout + BVH8 collapse %.3f s | Embree scene commit (its BVH4/8) "
            "%.3f s | ours/Embree speed %.2fx (median of per-round ratios)\n",
            ours_build_s + layout_s + collapse_s, commit_s, pipeline_ratio);
        out["build"]["embree_bvh2"] = {{"seconds", e_s}, {"mtris_per_s", e_mtris}, {"prims_seconds", prims_s},
                                       {"sah", embree_fig.bvh2_sah},
                                       {"nodes", embree_fig.bvh2_nodes}};
        out["build"]["embree_commit_seconds"] = commit_s;
        out["build"]["ratio_speed"] = speed_ratio;
        out["build"]["ratio_sah"] = stats.sah_cost / embree_fig.bvh2_sah;
        out["build"]["ratio_cpu_start"] = pipeline_ratio;
    } else {
        say("           Embree: not built in (no yardstick)\n");
    }

    // ---- Rays: the same sets for Embree and every device.
    if (o.rays) bench_rays(s, o, devices, bvh, embree.get(), out);

    // ---- Path tracing: samples/s, no Russian roulette (rr_depth > max_depth).
    if (o.path) {
        RenderSettings settings;
        settings.width = s.pt_width;
        settings.height = s.pt_height;
        settings.max_depth = kPathMaxDepth;
        settings.rr_depth = kPathRrDepth;
        settings.env_radiance = s.env;
        settings.wavefront_size = static_cast<std::uint32_t>(o.wavefront);
        settings.samples_per_pass = static_cast<std::uint32_t>(o.samples_per_pass);
        for (DeviceSlot& d : devices) {
            // A CPU times --repeats passes of its steady size (up to PassPlanner::kMaxSamples).
            const int samples =
                o.quick ? 1 : (d.info.is_gpu ? 64 : o.repeats * static_cast<int>(PassPlanner::kMaxSamples));
            const double budget = o.quick ? 0.0 : (d.info.is_gpu ? 5.0 : 20.0);
            // The renderer sizes its path slots for spp: small images then trace several
            // samples per pass on a wide device, as geocold-cl does.
            settings.spp = static_cast<std::uint32_t>(samples);
            const PathFigures pf = path_samples(*d.context, s.scene, bvh, s.camera, settings, samples, budget);
            const double sps = pf.pixels / median(pf.sample_seconds);
            json& j = out["path"][d.label()];
            j = {{"width", settings.width}, {"height", settings.height}, {"samples_per_s", sps},
                 {"samples_timed", pf.sample_seconds.size()}, {"wavefront", pf.wavefront},
                 {"samples_per_pass", pf.samples_per_pass},
                 {"form", pf.megakernel ? "megakernel" : "wavefront"},
                 {"device_bytes", pf.scene_bytes}, {"device_bytes_per_triangle", pf.scene_bytes / double(std::max<std::size_t>(tris, 1))}};
            std::string anchor;
            if (d.info.is_cpu && !d.info.is_gpu && (s.name == "cornell" || s.name == "tiny")) {
                const double per_core = sps / std::max(1u, d.info.compute_units);
                j["per_core"] = per_core;
                j["ratio_mitsuba_llvm_per_thread"] = per_core / kMitsubaLlvmPerThread;
                // A core delivers less with every core busy than one thread alone does (16
                // threads gave 12.4-13x one thread's Cornell samples on the H200 host), and the
                // anchor was measured on one thread: --threads 1 reproduces its conditions.
                anchor = "; per core " + std::to_string(per_core / 1e6).substr(0, 6) + " M = " +
                         ratio(per_core, kMitsubaLlvmPerThread) + " the issue's Mitsuba llvm_ad_rgb anchor (0.96 M per thread" +
                         (d.info.compute_units > 1 ? "; on all " + std::to_string(d.info.compute_units) +
                                                         " cores, --threads 1 for one thread's)"
                                                   : ")");
            }
            if (d.info.is_gpu && (s.name == "cornell" || s.name == "dragon")) {
                const double mitsuba = s.name == "cornell" ? kMitsubaCudaCornell : kMitsubaCudaDragon;
                j["ratio_mitsuba_cuda_h200"] = sps / mitsuba;
                anchor = "; " + ratio(sps, mitsuba) + " the issue's Mitsuba cuda_ad_rgb anchor on an H200 (" +
                         std::to_string(int(mitsuba / 1e6)) + " M)";
            }
            say("  path %s: %dx%d depth %d, %.4f Msamples/s (median of %zu), %s %u x %u samples per pass, %.1f device "
                "bytes/triangle%s\n",
                d.label().c_str(), settings.width, settings.height, kPathMaxDepth, sps / 1e6, pf.sample_seconds.size(),
                pf.megakernel ? "megakernel, pixels" : "wavefront, pixels", pf.wavefront, pf.samples_per_pass,
                pf.scene_bytes / double(std::max<std::size_t>(tris, 1)), anchor.c_str());
            if (s.name == "cornell" || s.name == "tiny") summary["cornell_path"][d.info.is_gpu ? "gpu" : "cpu"] = sps;
        }
    }
    return out;
}

// The devices this run measures (all, or the one --device names).
std::vector<DeviceSlot> selected_devices(const Options& o, const std::vector<cl::DeviceInfo>& all)
{
    std::vector<DeviceSlot> devices;
    for (std::size_t i = 0; i < all.size(); ++i) {
        if (o.device != "all" && cl::select_device(o.device, all).id != all[i].id) continue;
        DeviceSlot slot;
        slot.index = static_cast<int>(i);
        slot.info = all[i];
        devices.push_back(std::move(slot));
    }
    return devices;
}

// Child: one line per selected device, "<label>\t<key>".
int list_device_keys(const Options& o)
{
    std::string why;
    const std::vector<cl::DeviceInfo> all = cl::list_devices(&why);
    for (const DeviceSlot& d : selected_devices(o, all)) std::printf("%s\t%s\n", d.label().c_str(), device_key(d.info, all).c_str());
    return 0;
}

// Time to first image, each scene on each device in fresh child processes with fresh caches
// (a cold start compiles the program each scene's features ask for). The parent must not
// have touched OpenCL yet: on the lent H200 node a child started after the parent had merely
// enumerated the NVIDIA platform no longer saw it (while the same child started from a shell
// did), so even the device list comes from a child here.
void bench_first_images(const Options& o, json& doc)
{
    if (!o.first_image) return;
    say("\n== time to first image (each scene's path view, 1 sample, depth 8, a fresh process; cold: empty "
        "kernel caches) ==\n");
    std::vector<std::pair<std::string, std::string>> devices;  // label, key
    {
        const std::string exe = std::filesystem::read_symlink("/proc/self/exe").string();
        FILE* pipe = popen(("'" + exe + "' --list-device-keys --device '" + o.device + "'").c_str(), "r");
        if (!pipe) {
            say("  failed: cannot start the device-list child\n");
            return;
        }
        char line[1024];
        while (std::fgets(line, sizeof line, pipe)) {
            std::string text(line);
            while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
            const std::size_t tab = text.find('\t');
            if (tab != std::string::npos) devices.emplace_back(text.substr(0, tab), text.substr(tab + 1));
        }
        pclose(pipe);
    }
    for (const std::string& scene : o.scenes) {
        for (std::size_t i = 0; i < devices.size(); ++i) {
            const auto& [name, key] = devices[i];
            namespace fs = std::filesystem;
            const fs::path root =
                fs::temp_directory_path() / ("geocold-bench-cache-" + std::to_string(::getpid()) + "-" + std::to_string(i));
            fs::remove_all(root);
            fs::create_directories(root);
            const FirstImage cold = run_first_image(key, scene, root.string());
            const FirstImage warm = cold.skipped ? cold : run_first_image(key, scene, root.string());
            fs::remove_all(root);
            if (cold.skipped) {
                say("  %s: skipped (%s)\n", scene.c_str(), cold.error.c_str());
                doc["first_image"][scene] = {{"skipped", cold.error}};
                break;
            }
            for (const auto& [label, fi] : {std::pair<const char*, const FirstImage&>{"cold", cold}, {"warm", warm}}) {
                if (!fi.ok) {
                    say("  %s %s %s: failed: %s\n", scene.c_str(), name.c_str(), label, fi.error.c_str());
                    continue;
                }
                say("  %s %s %s: %.3f s in process (%.3f s wall with process start): scene + BVH %.3f s, device "
                    "layout %.3f s, program %s %.3f s, first sample + read-back %.3f s; devices listed %.3f s, "
                    "context %.3f s\n",
                    scene.c_str(), name.c_str(), label, fi.total_seconds, fi.process_seconds, fi.scene_seconds,
                    fi.upload_seconds, fi.from_cache ? "from cache" : "compiled", fi.compile_seconds, fi.render_seconds,
                    fi.devices_seconds, fi.context_seconds);
                doc["first_image"][scene][name][label] = {
                    {"seconds", fi.total_seconds},       {"process_seconds", fi.process_seconds},
                    {"scene_seconds", fi.scene_seconds}, {"upload_seconds", fi.upload_seconds},
                    {"compile_seconds", fi.compile_seconds}, {"render_seconds", fi.render_seconds},
                    {"from_cache", fi.from_cache},       {"devices_seconds", fi.devices_seconds},
                    {"context_seconds", fi.context_seconds}};
            }
        }
    }
}

// What explicit SIMD across paths would gain per device (tools/bench/packet_probe.h): the
// figure behind the CPU shading design, re-measurable on any machine.
void bench_packet_probe(const Options& o, std::vector<DeviceSlot>& devices, json& doc)
{
    const std::size_t vertices = o.quick ? std::size_t{1} << 14 : std::size_t{1} << 22;
    say("\n== explicit SIMD probe (kernels/packet_probe.cl: %zu Lambert vertices, NEE + cosine sample) ==\n", vertices);
    for (DeviceSlot& d : devices) {
        const PacketProbeFigures f = run_packet_probe(*d.context, vertices, o.repeats);
        say("  %s: 1 vertex per work-item %.1f Mvertices/s; 8 in float8 lanes %.1f = %.2fx; 16 in float16 lanes "
            "%.1f = %.2fx (medians of per-round ratios); %zu of %zu outputs differ from the scalar form's bits\n",
            d.label().c_str(), f.x1_mvertices, f.x8_mvertices, f.x8_ratio, f.x16_mvertices, f.x16_ratio, f.differing,
            2 * f.outputs);
        doc["packet_probe"][d.label()] = {{"x1_mvertices", f.x1_mvertices}, {"x8_mvertices", f.x8_mvertices},
                                          {"x16_mvertices", f.x16_mvertices}, {"x8_ratio", f.x8_ratio},
                                          {"x16_ratio", f.x16_ratio}, {"differing_bits", f.differing}};
    }
}

// The GPU roofline's instruction half: the issue rate and what each unit of traversal
// compiles to (issue_roofline.h), printed once per device; the ray lines then give each
// figure's share of it.
void report_issue_model(DeviceSlot& d, json& j)
{
    // A probe that fails to build costs this figure only, not the run's other figures
    // (bench_issue_roofline_test is where a broken probe fails).
    try {
        d.issue = issue_model(*d.context);
    } catch (const std::exception& e) {
        d.issue = {};
        d.issue.why_not = std::string("kernels/roofline_probe.cl: ") + e.what();
    }
    if (!d.issue.available) {
        say("  %s: no issue-rate roofline: %s\n", d.label().c_str(), d.issue.why_not.c_str());
        j["issue"] = {{"available", false}, {"why_not", d.issue.why_not}};
        return;
    }
    say("  %s: issue rate %.1f T lane instructions/s (%s); PTX instructions per BVH2 unit "
        "(kernels/roofline_probe.cl): ray set-up %.0f, inner node %.0f, triangle %.0f\n",
        d.label().c_str(), d.issue.issue_rate / 1e12, d.issue.rate_text.c_str(), d.issue.setup, d.issue.inner,
        d.issue.triangle);
    j["issue"] = {{"available", true},     {"rate", d.issue.issue_rate}, {"rate_text", d.issue.rate_text},
                  {"setup", d.issue.setup}, {"inner", d.issue.inner},     {"triangle", d.issue.triangle}};
}

int run(int argc, char** argv)
{
    const Options o = parse(argc, argv);
    if (o.threads > 0) {
        // Before any OpenCL call (PoCL reads its thread count when it is loaded; the
        // first-image children inherit the variables) and before Embree's device exists.
        set_host_thread_count(o.threads);
        cl::limit_cpu_device_threads(o.threads);
    }
    if (!o.first_image_child.empty()) return first_image_child(o.first_image_child, o.first_image_scene);
    if (o.list_device_keys) return list_device_keys(o);
    if (o.json_out) g_text = stderr;

    json doc;
    bench_first_images(o, doc);

    std::string why;
    const std::vector<cl::DeviceInfo> all = cl::list_devices(&why);
    if (all.empty()) throw DeviceError("no OpenCL device found: " + why);
    std::vector<DeviceSlot> devices = selected_devices(o, all);
    for (DeviceSlot& d : devices) d.context = std::make_unique<cl::Context>(d.info);
    doc["embree"] = embree_available() ? embree_version() : "not built in";
    doc["threads"] = host_thread_count();
    const HostCpu cpu = read_host_cpu();
    doc["host_cpu"] = {{"model", cpu.model}, {"family", cpu.family}, {"model_number", cpu.model_number},
                       {"widest_simd", cpu.widest_simd}, {"logical_cpus", cpu.logical_cpus},
                       {"summary", cpu.summary()}};
    say("geocold-bench: %zu device(s), Embree %s, %d host threads%s\n", devices.size(),
        embree_available() ? embree_version().c_str() : "not built in (no yardstick ratios)",
        host_thread_count(), o.quick ? ", quick" : "");
    say("  host CPU: %s\n", cpu.summary().c_str());
    for (DeviceSlot& d : devices) {
        if (d.info.is_gpu) d.bandwidth = copy_bandwidth(*d.context, std::size_t{1} << 30, o.quick ? 1 : 5);
        say("  %s: %s (%s), %u compute units, work-group %zu%s\n", d.label().c_str(), d.info.device_name.c_str(), d.info.platform_name.c_str(), d.info.compute_units,
            d.context->default_local_size(),
            d.bandwidth > 0 ? (", copy bandwidth " + std::to_string(int(d.bandwidth / 1e9)) + " GB/s").c_str() : "");
        doc["devices"][d.label()] = {{"type", d.info.type_name()}, {"compute_units", d.info.compute_units},
                                     {"local_size", d.context->default_local_size()}, {"bandwidth", d.bandwidth}};
        if (d.info.is_gpu) report_issue_model(d, doc["devices"][d.label()]);
    }

    json summary;
    const std::string shared = default_shared_dir();
    for (const std::string& name : o.scenes) {
        std::string missing;
        const auto start = Clock::now();
        std::optional<BenchScene> scene = load_bench_scene(name, shared, &missing);
        if (!scene) {
            say("\n== scene %s: skipped (%s) ==\n", name.c_str(), missing.c_str());
            doc["scenes"][name] = {{"skipped", missing}};
            continue;
        }
        const double load_s = seconds_since(start);
        doc["scenes"][name] = bench_scene(*scene, o, devices, summary);
        doc["scenes"][name]["load_seconds"] = load_s;
    }

    if (o.packet_probe) bench_packet_probe(o, devices, doc);

    if (summary.contains("cornell_path") && summary["cornell_path"].contains("gpu") &&
        summary["cornell_path"].contains("cpu")) {
        const double r = summary["cornell_path"]["gpu"].get<double>() / summary["cornell_path"]["cpu"].get<double>();
        say("\nCornell path tracing GPU / CPU (this run): %.1fx\n", r);
        summary["gpu_over_cpu"] = r;
    }
    doc["summary"] = summary;
    if (o.json_out) std::printf("%s\n", doc.dump(2).c_str());
    return 0;
}

}  // namespace
}  // namespace gc::bench

int main(int argc, char** argv)
{
    try {
        return gc::bench::run(argc, argv);
    } catch (const gc::UsageError& e) {
        std::fprintf(stderr, "geocold-bench: %s\n", e.what());
        return 2;  // a bad command line, as geocold-cl's exit status 2
    } catch (const std::exception& e) {
        std::fprintf(stderr, "geocold-bench: %s\n", e.what());
        return 1;
    }
}
