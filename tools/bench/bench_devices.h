// The OpenCL devices one geocold-bench run measures, each with its context and the figures
// measured once per device that the per-scene lines then refer to.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "host/cl/context.h"
#include "host/cl/device.h"
#include "tools/bench/bench_options.h"
#include "tools/bench/issue_roofline.h"

namespace gc::bench {

struct DeviceSlot {
    int index = 0;
    cl::DeviceInfo info;
    std::unique_ptr<cl::Context> context;
    double bandwidth = 0.0; // bytes/s, GPUs only
    IssueModel issue;       // the roofline's instruction half, GPUs only (issue_roofline.h)
    // Short: "[0] PoCL cpu"; the header line gives the full device name.
    std::string label() const;
};

// The devices this run measures (all, or the one --device names), without contexts yet.
std::vector<DeviceSlot> selected_devices(const Options& o, const std::vector<cl::DeviceInfo>& all);

}  // namespace gc::bench
