#include "host/cl/layout_probe.h"

#include <cstddef>

#include "gc_types.h"
#include "host/cl/buffer.h"
#include "host/cl/kernel.h"

namespace gc::cl {
namespace {

using namespace gc::dev;

constexpr LayoutEntry host_entries[] = {
#define GC_LAYOUT_SIZE(S) {#S, nullptr, static_cast<std::uint32_t>(sizeof(S))},
#define GC_LAYOUT_FIELD(S, f) {#S, #f, static_cast<std::uint32_t>(offsetof(S, f))},
#include "gc_layout_list.h"
#undef GC_LAYOUT_FIELD
#undef GC_LAYOUT_SIZE
};

std::string describe(const LayoutEntry& entry)
{
    return entry.field ? std::string("offsetof(") + entry.type + ", " + entry.field + ")"
                       : std::string("sizeof(") + entry.type + ")";
}

}  // namespace

std::span<const LayoutEntry> host_layout()
{
    return host_entries;
}

std::vector<LayoutMismatch> probe_layout(const Context& context, const BuildConfig& config)
{
    const std::span<const LayoutEntry> host = host_layout();
    Program program(context, "test/layout_probe.cl", {}, config);
    Kernel kernel = program.kernel("gc_layout_probe");
    // Room for one more entry than the host knows, so a longer device list shows up as a count.
    const auto capacity = static_cast<cl_uint>(host.size() + 2);
    std::vector<cl_uint> out(capacity, 0xffffffffu);
    auto buffer =
        Buffer<cl_uint>::create(context, capacity, CL_MEM_READ_WRITE, "layout probe output");
    buffer.write(out);
    kernel.set_args(buffer, capacity);
    kernel.launch(context, 1, 1, "layout probe");
    buffer.read(out);

    std::vector<LayoutMismatch> mismatches;
    if (out[0] != host.size()) {
        mismatches.push_back({"entry count", static_cast<std::uint32_t>(host.size()), out[0]});
    }
    for (size_t i = 0; i < host.size() && i + 1 < out.size(); ++i) {
        if (out[i + 1] != host[i].host)
            mismatches.push_back({describe(host[i]), host[i].host, out[i + 1]});
    }
    return mismatches;
}

std::string format_layout_mismatches(const std::vector<LayoutMismatch>& mismatches)
{
    std::string text;
    for (const LayoutMismatch& m : mismatches) {
        text += "  " + m.what + ": host " + std::to_string(m.host) + ", device " +
                std::to_string(m.device) + "\n";
    }
    return text;
}

void check_layout(const Context& context, const BuildConfig& config)
{
    const std::vector<LayoutMismatch> mismatches = probe_layout(context, config);
    if (!mismatches.empty()) {
        throw DeviceError("the shared struct layout on " + context.device().device_name +
                          " differs from the host's (kernels/shared/gc_types.h):\n" +
                          format_layout_mismatches(mismatches));
    }
}

}  // namespace gc::cl
