// geocold-cl's documented environment variables become the same settings the libraries
// used to read for themselves.
#include "host/app/environment.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "host/util/error.h"
#include "tests/cl/cl_test_util.h"

namespace gc {
namespace {

using cl::test::ScopedEnv;

// Every variable the function reads, unset for the test's scope.
struct CleanEnvironment {
    ScopedEnv bvh{"GEOCOLD_BVH_WIDTH", nullptr};
    ScopedEnv features{"GEOCOLD_KERNEL_FEATURES", nullptr};
    ScopedEnv path{"GEOCOLD_PATH_KERNEL", nullptr};
    ScopedEnv kernel_dir{"GEOCOLD_KERNEL_DIR", nullptr};
    ScopedEnv no_cache{"GEOCOLD_NO_CACHE", nullptr};
    ScopedEnv cache_dir{"GEOCOLD_CACHE_DIR", nullptr};
    ScopedEnv always{"GEOCOLD_CACHE_ALWAYS", nullptr};
    ScopedEnv kcache{"POCL_KERNEL_CACHE", nullptr};
    ScopedEnv xdg{"XDG_CACHE_HOME", nullptr};
    ScopedEnv home{"HOME", "/home/someone"};
    ScopedEnv module{"GEOCOLD_IMAGE_MODULE", nullptr};
};

TEST(Environment, UnsetMeansTheDefaults)
{
    const CleanEnvironment clean;
    const RenderSetup setup = render_setup_from_environment();
    EXPECT_FALSE(setup.tuning.bvh_layout);
    EXPECT_EQ(setup.tuning.path_kernel, PathKernelForm::Auto);
    EXPECT_EQ(setup.tuning.kernel_features, KernelFeatureSet::Scene);
    EXPECT_FALSE(setup.tuning.wavefront_items_per_unit);
    EXPECT_FALSE(setup.tuning.wavefront_sync_counts);
    EXPECT_TRUE(setup.build.kernel_dir.empty());
    EXPECT_EQ(setup.build.cache_dir, std::filesystem::path("/home/someone/.cache/geocold-cl/kernels"));
    EXPECT_TRUE(setup.build.use_cache);
    EXPECT_FALSE(setup.build.store_when_driver_caches);
    EXPECT_FALSE(setup.build.driver_cache_disabled);
    EXPECT_TRUE(image_module_from_environment().empty());
}

TEST(Environment, TuningVariables)
{
    const CleanEnvironment clean;
    const ScopedEnv bvh("GEOCOLD_BVH_WIDTH", "4");
    const ScopedEnv features("GEOCOLD_KERNEL_FEATURES", "all");
    const ScopedEnv path("GEOCOLD_PATH_KERNEL", "wavefront");
    const DeviceTuning tuning = render_setup_from_environment().tuning;
    EXPECT_EQ(tuning.bvh_layout, BvhLayout::Wide);
    EXPECT_EQ(tuning.kernel_features, KernelFeatureSet::All);
    EXPECT_EQ(tuning.path_kernel, PathKernelForm::Wavefront);
    const ScopedEnv bvh8("GEOCOLD_BVH_WIDTH", "8");
    const ScopedEnv megakernel("GEOCOLD_PATH_KERNEL", "megakernel");
    EXPECT_EQ(render_setup_from_environment().tuning.bvh_layout, BvhLayout::Wide8);
    EXPECT_EQ(render_setup_from_environment().tuning.path_kernel, PathKernelForm::Megakernel);
    const ScopedEnv bvh2("GEOCOLD_BVH_WIDTH", "2");
    EXPECT_EQ(render_setup_from_environment().tuning.bvh_layout, BvhLayout::Binary);
}

TEST(Environment, AValueOutsideTheChoicesIsAUsageErrorNamingTheVariable)
{
    for (const char* name : {"GEOCOLD_BVH_WIDTH", "GEOCOLD_KERNEL_FEATURES", "GEOCOLD_PATH_KERNEL"}) {
        const CleanEnvironment clean;
        const ScopedEnv bad(name, "none");
        try {
            render_setup_from_environment();
            ADD_FAILURE() << name << "=none accepted";
        } catch (const UsageError& e) {
            EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("'none'"), std::string::npos) << e.what();
        }
    }
}

TEST(Environment, CacheFolderOrder)
{
    const CleanEnvironment clean;
    {
        const ScopedEnv xdg("XDG_CACHE_HOME", "/xdg");
        EXPECT_EQ(render_setup_from_environment().build.cache_dir, std::filesystem::path("/xdg/geocold-cl/kernels"));
        const ScopedEnv dir("GEOCOLD_CACHE_DIR", "/explicit");
        EXPECT_EQ(render_setup_from_environment().build.cache_dir, std::filesystem::path("/explicit"));
        const ScopedEnv off("GEOCOLD_NO_CACHE", "1");
        EXPECT_FALSE(render_setup_from_environment().build.use_cache);
    }
    const ScopedEnv no_home("HOME", nullptr);
    EXPECT_TRUE(render_setup_from_environment().build.cache_dir.empty());
}

TEST(Environment, BuildVariables)
{
    const CleanEnvironment clean;
    const cl::test::TempKernelDir kernels;
    const ScopedEnv kernel_dir("GEOCOLD_KERNEL_DIR", kernels.path().c_str());
    const ScopedEnv always("GEOCOLD_CACHE_ALWAYS", "1");
    const ScopedEnv kcache("POCL_KERNEL_CACHE", "0");
    const ScopedEnv module("GEOCOLD_IMAGE_MODULE", "/lib/module.so");
    const cl::BuildConfig build = render_setup_from_environment().build;
    EXPECT_EQ(build.kernel_dir, kernels.path());
    EXPECT_TRUE(build.store_when_driver_caches);
    EXPECT_TRUE(build.driver_cache_disabled);
    EXPECT_EQ(image_module_from_environment(), std::filesystem::path("/lib/module.so"));
}

TEST(Environment, AKernelDirWithoutKernelsIsADeviceErrorNamingTheVariable)
{
    const CleanEnvironment clean;
    const cl::test::TempDir empty;
    const ScopedEnv kernel_dir("GEOCOLD_KERNEL_DIR", empty.path().c_str());
    try {
        render_setup_from_environment();
        ADD_FAILURE() << "no error for a kernel dir without shared/gc_types.h";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("GEOCOLD_KERNEL_DIR=" + empty.path().string()), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace gc
