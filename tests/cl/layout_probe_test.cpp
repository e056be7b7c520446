#include "host/cl/layout_probe.h"

#include <gtest/gtest.h>

#include <string>

#include "cl_test_util.h"

namespace gc::cl {
namespace {

class LayoutProbeTest : public test::DeviceTest {};

// The device half of the layout contract, on every device present (not only the selected one).
TEST_F(LayoutProbeTest, LayoutProbeMatchesHostOnEveryDevice)
{
    test::TempDir cache;
    for (const DeviceInfo& device : devices) {
        Context ctx(device);
        const auto mismatches = probe_layout(ctx, BuildConfig{{}, cache.path(), true});
        std::printf("%s: %zu entries checked, %zu mismatches\n%s", device.device_name.c_str(),
                    host_layout().size(), mismatches.size(),
                    format_layout_mismatches(mismatches).c_str());
        EXPECT_TRUE(mismatches.empty()) << device.device_name;
        EXPECT_NO_THROW(check_layout(ctx, BuildConfig{{}, cache.path(), true}));
    }
}

// Cold (fresh cache) vs warm (cached binary) build of the probe: the figure for "a warm
// start compiles nothing".
TEST_F(LayoutProbeTest, LayoutProbeColdVsWarmBuild)
{
    for (const DeviceInfo& device : devices) {
        test::TempDir cache;
        Context ctx(device);
        // Our cache on every driver, PoCL included (where it is read-only by default).
        const BuildConfig config{{}, cache.path(), true, true};
        const Program cold(ctx, "test/layout_probe.cl", "", config);
        const Program warm(ctx, "test/layout_probe.cl", "", config);
        std::printf("%s: layout_probe.cl cold %.3f s, warm %.3f s\n", device.device_name.c_str(),
                    cold.build_seconds(), warm.build_seconds());
        EXPECT_FALSE(cold.from_cache());
        EXPECT_TRUE(warm.from_cache());
    }
}

}  // namespace
}  // namespace gc::cl
