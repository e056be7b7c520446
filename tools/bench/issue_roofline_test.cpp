// The GPU roofline's instruction half (issue_roofline.h) on every OpenCL device present:
// kernels/test/roofline_probe.cl must build wherever the BVH2 traversal does (it calls the same
// functions, so a change to their signatures shows here and not only on a GPU node), and on
// an NVIDIA GPU each unit must come out as a positive PTX instruction count. Elsewhere the
// model says why it has no figure.
#include "tools/bench/issue_roofline.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/cl/program.h"
#include "host/render/device_bvh.h"

namespace gc::bench {
namespace {

TEST(IssueRoofline, ProbeBuildsAndCountsOnEveryDevice)
{
    std::string why;
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why);
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device: " << why;
    for (const cl::DeviceInfo& info : devices) {
        SCOPED_TRACE(info.device_name);
        const cl::Context context(info);
        const cl::Program probe(context, "test/roofline_probe.cl", program_options(BvhLayout::Binary));
        for (const char* unit : {"setup", "inner", "triangle"}) {
            for (const char* times : {"_x1", "_x2"}) {
                const std::string name = std::string("probe_") + unit + times;
                EXPECT_NO_THROW(probe.kernel(name.c_str()));
            }
        }

        const IssueModel m = issue_model(context);
        const std::string figures = m.available ? "set-up " + std::to_string(m.setup) + ", inner " +
                                                      std::to_string(m.inner) + ", triangle " +
                                                      std::to_string(m.triangle) + " PTX instructions; " + m.rate_text
                                                : "no figure: " + m.why_not;
        std::printf("[issue] %s: %s\n", info.device_name.c_str(), figures.c_str());
        if (!m.available) {
            EXPECT_FALSE(m.why_not.empty());
            continue;
        }
        // A box test alone is a dozen instructions and an inner node has two; the triangle
        // test is longer than one box. Counts this far off mean the probe lost its work.
        EXPECT_GT(m.inner, 20.0);
        EXPECT_GT(m.triangle, 20.0);
        EXPECT_GT(m.setup, 10.0);
        EXPECT_GT(m.issue_rate, 1e12);
        TraversalCost cost;
        cost.inner_visits = 10.0;
        cost.triangle_tests = 5.0;
        EXPECT_DOUBLE_EQ(m.instructions_per_ray(cost), m.setup + 10.0 * m.inner + 5.0 * m.triangle);
    }
}

}  // namespace
}  // namespace gc::bench
