#include "tools/bench/measure_rays.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "host/util/host_threads.h"
#include "tools/bench/bench_environment.h"
#include "tools/bench/bench_output.h"
#include "tools/bench/ocl_bench.h"
#include "tools/bench/rays.h"
#include "tools/bench/timing.h"

namespace gc::bench {

using nlohmann::json;

namespace {

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

// Embree's figures for the three kinds: the better of rtcIntersect1/rtcOccluded1 and their
// 16-wide forms, each the median of `repeats` timed traces after one untimed, and the hits of
// the better one, which the devices' hits are compared with.
struct EmbreeRays {
    double best[3] = {0, 0, 0};               // Mrays/s
    std::vector<std::uint32_t> result[3];
};

EmbreeRays time_embree(const RayKind (&kinds)[3], const EmbreeTracer& embree, int threads, int repeats, json& out)
{
    EmbreeRays e;
    for (int k = 0; k < 3; ++k) {
        const RayKind& kind = kinds[k];
        std::string line;
        for (int width : {1, 16}) {
            std::vector<double> times;
            std::vector<std::uint32_t> result;
            for (int r = 0; r < repeats + 1; ++r) {
                const double t = kind.any ? embree.occluded(*kind.rays, threads, width, result)
                                          : embree.closest(*kind.rays, threads, width, result);
                if (r > 0 || repeats == 1) times.push_back(t);
            }
            const double mrays = double(kind.rays->size()) / median(times) / 1e6;
            out["rays"][kind.name]["embree"][width == 1 ? "single" : "packet16"] = json_number(mrays);
            char buffer[96];
            std::snprintf(buffer, sizeof buffer, "%s %.2f", width == 1 ? (kind.any ? "rtcOccluded1" : "rtcIntersect1")
                                                                       : (kind.any ? "rtcOccluded16" : "rtcIntersect16"),
                          mrays);
            line += std::string(line.empty() ? "" : ", ") + buffer;
            if (mrays > e.best[k]) {
                e.best[k] = mrays;
                e.result[k] = result;
            }
        }
        out["rays"][kind.name]["embree"]["best"] = json_number(e.best[k]);
        say("  Embree %-7s (%d threads): %s Mrays/s\n", kind.name, threads, line.c_str());
    }
    return e;
}

// A GPU ray figure as a share of the two bounds derived from `cost` (the host's count of the
// same rays' traversal work): bytes per ray against the device's copy bandwidth, and, where
// the issue model exists, PTX instructions per ray against its issue rate. Fills
// j["roofline"]; returns the text for the ray line.
std::string roofline_report(const DeviceSlot& d, const TraversalCost& cost, double mrays, json& j)
{
    const double bytes = cost.bytes_per_ray();
    const double bound = d.bandwidth / bytes / 1e6;
    j["roofline"] = {{"bytes_per_ray", bytes}, {"inner_visits", cost.inner_visits},
                     {"triangle_tests", cost.triangle_tests}, {"bound_mrays_per_s", bound},
                     {"fraction", mrays / bound}};
    char buffer[160];
    std::snprintf(buffer, sizeof buffer,
                  "; uncached roofline %.0f B/ray (%.1f inner, %.1f tris) -> %.0f Mrays/s bound, at %.1f%%", bytes,
                  cost.inner_visits, cost.triangle_tests, bound, 100.0 * mrays / bound);
    std::string text = buffer;
    if (d.issue.available) {
        const double instructions = d.issue.instructions_per_ray(cost);
        const double issue_bound = d.issue.bound_rays_per_s(cost) / 1e6;
        j["roofline"]["ptx_instructions_per_ray"] = instructions;
        j["roofline"]["issue_bound_mrays_per_s"] = issue_bound;
        j["roofline"]["issue_fraction"] = mrays / issue_bound;
        std::snprintf(buffer, sizeof buffer, "; issue %.0f PTX instr/ray -> %.0f Mrays/s bound, at %.1f%%",
                      instructions, issue_bound, 100.0 * mrays / issue_bound);
        text += buffer;
    }
    return text;
}

}  // namespace

// Least rays per GPU launch. The dragon's 309k diffuse rays are about one wave of an H200's
// resident threads (132 SMs x 2048), so a launch of them is held by its slowest warps and by
// the launch's fixed cost; the renderer's wavefront launches hold up to 2^24 paths. H200,
// 1024^2 against 2048^2 camera rays (2 runs): dragon primary / diffuse / shadow 5.97-5.80 vs
// 8.83-8.95 G, 1.24-1.21 vs 1.61-1.66 G, 1.45-1.43 vs 2.06-2.12 G rays/s; 5.2M triangles
// 1.76 vs 2.61 G, 1.11 vs 1.34 G, 1.35 vs 1.82 G.
constexpr std::size_t kGpuRaysPerLaunch = std::size_t{1} << 22;

void measure_rays(const BenchScene& s, const Options& o, std::vector<DeviceSlot>& devices, const FlatBvh& bvh,
                  const EmbreeTracer* embree, json& out)
{
    const int threads = host_thread_count();
    const auto rays_start = Clock::now();
    const int side = o.ray_side;
    const RaySet set = make_rays(s.scene, bvh, s.camera, side, side, threads);
    say("rays: %zu primary (%dx%d), %zu diffuse, %zu shadow (made in %.2f s)\n", set.primary.size(), side, side,
        set.diffuse.size(), set.shadow.size(), seconds_since(rays_start));
    const RayKind kinds[] = {{"primary", &set.primary, false}, {"diffuse", &set.diffuse, false}, {"shadow", &set.shadow, true}};

    EmbreeRays embree_rays;
    if (embree) embree_rays = time_embree(kinds, *embree, threads, o.repeats, out);

    bool have_cost = false;
    TraversalCost cost[3];
    for (DeviceSlot& d : devices) {
        OclTracer tracer(*d.context, bvh, bench_render_setup());
        const std::size_t launch_rays = d.info.is_gpu ? kGpuRaysPerLaunch : 0;
        tracer.set_min_launch_rays(launch_rays);
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
            const std::uint32_t copies = tracer.copies();
            // The set alone, in launches of its own size, for comparison (and its hits must be
            // the copies' hits).
            DeviceRays alone;
            if (copies > 1) {
                tracer.set_min_launch_rays(0);
                trace_on_device(kind, tracer, repeats, alone);
                tracer.set_min_launch_rays(launch_rays);
                if (alone.single_result != traced.single_result)
                    throw std::runtime_error(s.name + ", " + d.label() + ": " + kind.name +
                                             " rays traced in copies found other hits than the set alone");
            }
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
            if (copies > 1) {
                const double alone_mrays = mrays_of(alone.single_seconds);
                j["launch_rays"] = double(kind.rays->size()) * copies;
                j["set_alone_mrays_per_s"] = json_number(alone_mrays);
                char buffer[160];
                std::snprintf(buffer, sizeof buffer, ", launches of %.2fM rays: the set %ux over; the set alone %.2f",
                              double(kind.rays->size()) * copies / 1e6, copies, alone_mrays);
                form += buffer;
            }
            if (traces_packets(kind, tracer)) {
                char buffer[128];
                std::snprintf(buffer, sizeof buffer, packets_lead ? ", packets of 8 neighbouring rays; single rays %.2f"
                                                                  : ", single rays; packets of 8 neighbouring rays %.2f",
                              packets_lead ? single : packets);
                form += buffer;
            }
            std::string extra;
            if (embree) {
                const double agree = agreement(result, embree_rays.result[k]);
                if (!interleave) to_embree = mrays / embree_rays.best[k];
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
                extra += roofline_report(d, cost[k], mrays, j);
            }
            say("  %s %-7s: %.2f Mrays/s (%s)%s\n", d.label().c_str(), kind.name, mrays, form.c_str(), extra.c_str());
        }
    }
}

}  // namespace gc::bench
