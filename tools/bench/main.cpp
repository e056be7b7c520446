// geocold-bench: BVH build speed and quality, ray throughput, path-traced samples per second
// and time to first image, for every OpenCL device, with Embree 3 on the same CPU (same
// triangles, same rays, same run) as the yardstick beside every figure.
//
//   geocold-bench [--device all|SPEC] [--scene cornell,bunny,dragon,large] [--quick] [--json]
//                 [--repeats N] [--rays SIDE] [--no-path] [--no-rays] [--no-first-image]
//                 [--no-packet-probe] [--threads N] [--wavefront N] [--samples-per-pass N]
//
// Each part of a run has its own file: bench_options (the command line), measure_first_images,
// measure_build, measure_rays, measure_paths (per scene), device_probes (per device).
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "host/app/environment.h"
#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/image/image_module.h"
#include "host/util/error.h"
#include "host/util/host_threads.h"
#include "tools/bench/bench_devices.h"
#include "tools/bench/bench_environment.h"
#include "tools/bench/bench_options.h"
#include "tools/bench/bench_output.h"
#include "tools/bench/bench_scenes.h"
#include "tools/bench/device_probes.h"
#include "tools/bench/embree_bench.h"
#include "tools/bench/first_image.h"
#include "tools/bench/host_cpu.h"
#include "tools/bench/measure_build.h"
#include "tools/bench/measure_first_images.h"
#include "tools/bench/measure_paths.h"
#include "tools/bench/measure_rays.h"
#include "tools/bench/ocl_bench.h"
#include "tools/bench/timing.h"

namespace gc::bench {
namespace {

using nlohmann::json;

// One scene's figures: its BVH build, then rays and paths on every device.
json bench_scene(const BenchScene& s, const Options& o, std::vector<DeviceSlot>& devices, json& summary)
{
    json out;
    say("\n== scene %s: %zu triangles ==\n", s.name.c_str(), s.scene.triangle_count());
    out["triangles"] = s.scene.triangle_count();
    // What the path figures render, so that another renderer can be timed on the same view.
    out["view"] = path_view(s);
    const BuiltScene built = measure_build(s, o, out);
    // The same ray sets for Embree and every device.
    if (o.rays) measure_rays(s, o, devices, built.bvh, built.embree.get(), out);
    if (o.path) measure_paths(s, o, devices, built.bvh, out, summary);
    return out;
}

int run(int argc, char** argv)
{
    const Options o = parse_options(argc, argv);
#ifdef GC_HAVE_OIIO
    set_image_module_path(image_module_from_environment());  // a build without OIIO has no module
#endif
    bench_render_setup();  // a bad variable is reported before any measuring starts
    if (o.threads > 0) {
        // Before any OpenCL call (PoCL reads its thread count when it is loaded; the
        // first-image children inherit the variables) and before Embree's device exists.
        set_host_thread_count(o.threads);
        cl::limit_cpu_device_threads(o.threads);
    }
    if (!o.first_image_child.empty()) return first_image_child(o.first_image_child, o.first_image_scene);
    if (o.list_device_keys) return list_device_keys(o);
    if (o.json_out) send_text_to(stderr);  // stdout carries the JSON document

    json doc;
    measure_first_images(o, doc);

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

    if (o.packet_probe) measure_packet_probe(o, devices, doc);

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
