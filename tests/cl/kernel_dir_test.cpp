#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cl_test_util.h"
#include "host/cl/program.h"

namespace gc::cl {
namespace {

using test::ScopedEnv;

TEST(KernelDir, DefaultIsTheSourceTree)
{
    ScopedEnv unset("GEOCOLD_KERNEL_DIR", nullptr);
    const auto dir = find_kernel_dir();
    std::printf("kernel dir: %s\n", dir.string().c_str());
    EXPECT_TRUE(is_kernel_dir(dir));
    EXPECT_TRUE(
        std::filesystem::equivalent(dir, std::filesystem::path(GC_TEST_SOURCE_DIR) / "kernels"));
}

TEST(KernelDir, EnvironmentOverrides)
{
    test::TempKernelDir temp;
    ScopedEnv set("GEOCOLD_KERNEL_DIR", temp.path().c_str());
    EXPECT_EQ(find_kernel_dir(), temp.path());
}

TEST(KernelDir, BadEnvironmentIsAnError)
{
    test::TempDir empty;
    ScopedEnv set("GEOCOLD_KERNEL_DIR", empty.path().c_str());
    try {
        find_kernel_dir();
        FAIL() << "no error for a kernel dir without shared/gc_types.h";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find(empty.path().string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(is_kernel_dir(empty.path()));
}

}  // namespace
}  // namespace gc::cl
