#include "tools/bench/issue_roofline.h"

#include <CL/cl_ext.h>

#include <map>
#include <string>
#include <vector>

#include "host/cl/device.h"
#include "host/cl/program.h"
#include "host/render/device_bvh.h"
#include "tools/bench/ptx_count.h"

namespace gc::bench {

IssueModel issue_model(const cl::Context& context, const cl::BuildConfig& build)
{
    IssueModel m;
    const cl::DeviceInfo& info = context.device();
    if (cl::device_string(info.id, CL_DEVICE_EXTENSIONS).find("cl_nv_device_attribute_query") == std::string::npos) {
        m.why_not = "needs NVIDIA's OpenCL (PTX binaries, cl_nv_device_attribute_query)";
        return m;
    }
    const cl_uint major = cl::device_uint(info.id, CL_DEVICE_COMPUTE_CAPABILITY_MAJOR_NV);
    const cl_uint warp = cl::device_uint(info.id, CL_DEVICE_WARP_SIZE_NV);
    const cl_uint mhz = cl::device_uint(info.id, CL_DEVICE_MAX_CLOCK_FREQUENCY);
    // From Volta (7.0) on, an SM has four partitions, each issuing one warp instruction per
    // clock. Earlier GPUs differ by generation; they get no figure rather than a guess.
    if (major < 7 || warp == 0 || mhz == 0 || info.compute_units == 0) {
        m.why_not = "compute capability " + std::to_string(major) + ": the issue rate is known from 7.0 on";
        return m;
    }
    constexpr int kSchedulersPerSm = 4;
    m.issue_rate = double(info.compute_units) * kSchedulersPerSm * warp * mhz * 1e6;
    m.rate_text = std::to_string(info.compute_units) + " SMs x " + std::to_string(kSchedulersPerSm) + " x " +
                  std::to_string(warp) + " lanes x " + std::to_string(mhz) + " MHz";

    const cl::Program program(context, "test/roofline_probe.cl", program_options(BvhLayout::Binary), build);
    const std::vector<unsigned char> binary = program.binary();
    const std::string ptx(binary.begin(), binary.end());
    if (!looks_like_ptx(ptx)) {
        m.why_not = "the driver's binary of roofline_probe.cl is not PTX";
        return m;
    }
    const std::map<std::string, int> counts = count_ptx_instructions(ptx);
    // A unit's instructions: the kernel doing it twice minus the one doing it once.
    const auto unit = [&](const std::string& name) -> double {
        const auto once = counts.find("probe_" + name + "_x1");
        const auto twice = counts.find("probe_" + name + "_x2");
        if (once == counts.end() || twice == counts.end()) return 0.0;
        return double(twice->second - once->second);
    };
    m.setup = unit("setup");
    m.inner = unit("inner");
    m.triangle = unit("triangle");
    if (!(m.setup > 0.0 && m.inner > 0.0 && m.triangle > 0.0)) {
        m.why_not = "roofline_probe.cl's PTX lacks a probe kernel, or a unit counted no instructions";
        return m;
    }
    m.available = true;
    return m;
}

}  // namespace gc::bench
