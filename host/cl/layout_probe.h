// The device half of the layout contract of kernels/shared/gc_types.h: run
// kernels/test/layout_probe.cl and compare every sizeof and field offset it reports with the
// host's (the same gc_layout_list.h expanded with offsetof/sizeof).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "host/cl/context.h"
#include "host/cl/program.h"

namespace gc::cl {

struct LayoutEntry {
    const char* type;    // "GcRay"
    const char* field;   // "dir_tmax", or nullptr for the struct's sizeof
    std::uint32_t host;  // the host's offsetof / sizeof
};

// gc_layout_list.h in order, with the host's values.
std::span<const LayoutEntry> host_layout();

struct LayoutMismatch {
    std::string what;  // "offsetof(GcRay, dir_tmax)", "sizeof(GcRay)" or "entry count"
    std::uint32_t host = 0;
    std::uint32_t device = 0;
};

// Builds and runs the probe on the context's device; empty when every entry agrees.
std::vector<LayoutMismatch> probe_layout(const Context& context, const BuildConfig& config = {});

// "offsetof(GcRay, dir_tmax): host 16, device 32" lines.
std::string format_layout_mismatches(const std::vector<LayoutMismatch>& mismatches);

// Throws DeviceError listing the mismatches, naming the device. For renderer start-up.
void check_layout(const Context& context, const BuildConfig& config = {});

}  // namespace gc::cl
