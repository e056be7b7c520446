#include "tools/bench/device_probes.h"

#include <cstddef>
#include <exception>
#include <string>

#include "tools/bench/bench_environment.h"
#include "tools/bench/bench_output.h"
#include "tools/bench/packet_probe.h"

namespace gc::bench {

void measure_packet_probe(const Options& o, std::vector<DeviceSlot>& devices, nlohmann::json& doc)
{
    const std::size_t vertices = o.quick ? std::size_t{1} << 14 : std::size_t{1} << 22;
    say("\n== explicit SIMD probe (kernels/test/packet_probe.cl: %zu Lambert vertices, NEE + cosine sample) ==\n", vertices);
    for (DeviceSlot& d : devices) {
        const PacketProbeFigures f = run_packet_probe(*d.context, vertices, o.repeats, bench_render_setup().build);
        say("  %s: 1 vertex per work-item %.1f Mvertices/s; 8 in float8 lanes %.1f = %.2fx; 16 in float16 lanes "
            "%.1f = %.2fx (medians of per-round ratios); %zu of %zu outputs differ from the scalar form's bits\n",
            d.label().c_str(), f.x1_mvertices, f.x8_mvertices, f.x8_ratio, f.x16_mvertices, f.x16_ratio, f.differing,
            2 * f.outputs);
        doc["packet_probe"][d.label()] = {{"x1_mvertices", f.x1_mvertices}, {"x8_mvertices", f.x8_mvertices},
                                          {"x16_mvertices", f.x16_mvertices}, {"x8_ratio", f.x8_ratio},
                                          {"x16_ratio", f.x16_ratio}, {"differing_bits", f.differing}};
    }
}

void report_issue_model(DeviceSlot& d, nlohmann::json& j)
{
    // A probe that fails to build costs this figure only, not the run's other figures
    // (bench_issue_roofline_test is where a broken probe fails).
    try {
        d.issue = issue_model(*d.context, bench_render_setup().build);
    } catch (const std::exception& e) {
        d.issue = {};
        d.issue.why_not = std::string("kernels/test/roofline_probe.cl: ") + e.what();
    }
    if (!d.issue.available) {
        say("  %s: no issue-rate roofline: %s\n", d.label().c_str(), d.issue.why_not.c_str());
        j["issue"] = {{"available", false}, {"why_not", d.issue.why_not}};
        return;
    }
    say("  %s: issue rate %.1f T lane instructions/s (%s); PTX instructions per BVH2 unit "
        "(kernels/test/roofline_probe.cl): ray set-up %.0f, inner node %.0f, triangle %.0f\n",
        d.label().c_str(), d.issue.issue_rate / 1e12, d.issue.rate_text.c_str(), d.issue.setup, d.issue.inner,
        d.issue.triangle);
    j["issue"] = {{"available", true},     {"rate", d.issue.issue_rate}, {"rate_text", d.issue.rate_text},
                  {"setup", d.issue.setup}, {"inner", d.issue.inner},     {"triangle", d.issue.triangle}};
}

}  // namespace gc::bench
