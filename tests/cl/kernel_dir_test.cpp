#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cl_test_util.h"
#include "host/cl/program.h"

namespace gc::cl {
namespace {

TEST(KernelDir, DefaultIsTheSourceTree)
{
    const auto dir = find_kernel_dir();
    std::printf("kernel dir: %s\n", dir.string().c_str());
    EXPECT_TRUE(is_kernel_dir(dir));
    EXPECT_TRUE(
        std::filesystem::equivalent(dir, std::filesystem::path(GC_TEST_SOURCE_DIR) / "kernels"));
}

TEST(KernelDir, ChosenDirectoryOverrides)
{
    test::TempKernelDir temp;
    EXPECT_EQ(find_kernel_dir(temp.path()), temp.path());
}

TEST(KernelDir, ChosenDirectoryWithoutKernelsIsAnError)
{
    test::TempDir empty;
    try {
        find_kernel_dir(empty.path());
        FAIL() << "no error for a kernel dir without shared/gc_types.h";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find(empty.path().string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(is_kernel_dir(empty.path()));
}

}  // namespace
}  // namespace gc::cl
