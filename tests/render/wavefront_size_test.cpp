// host/render/renderer: how many paths a pass holds by default, and how many work-items a
// wavefront launch gets (the device side of both is in tests/validation/determinism_test.cpp).
#include <gtest/gtest.h>

#include <cstdio>

#include "host/render/renderer.h"

namespace gc {
namespace {

cl::DeviceInfo gpu_with(cl_ulong global_mem, cl_ulong max_alloc)
{
    cl::DeviceInfo d;
    d.is_gpu = true;
    d.global_mem = global_mem;
    d.max_alloc = max_alloc;
    return d;
}

constexpr cl_ulong kGiB = cl_ulong{1} << 30;

TEST(WavefrontSize, LargeGpusHoldTheFullWavefront)
{
    // The H200 as NVIDIA's OpenCL reports it: 140 GiB, 35 GiB per buffer.
    const std::uint32_t paths = default_wavefront_size(gpu_with(140 * kGiB, 35 * kGiB));
    std::printf("H200-sized GPU: %u paths of %llu bytes\n", paths, static_cast<unsigned long long>(kWavefrontBytesPerPath));
    EXPECT_EQ(paths, kGpuWavefrontPaths);
}

TEST(WavefrontSize, SmallGpusKeepTheirPathsWithinAnEighthOfTheirMemory)
{
    const cl::DeviceInfo small = gpu_with(4 * kGiB, 1 * kGiB);
    const std::uint32_t paths = default_wavefront_size(small);
    std::printf("4 GiB GPU: %u paths, %.0f MiB\n", paths, double(paths) * double(kWavefrontBytesPerPath) / (1 << 20));
    EXPECT_LT(paths, kGpuWavefrontPaths);
    EXPECT_LE(std::uint64_t{paths} * kWavefrontBytesPerPath, small.global_mem / 8);
    EXPECT_GE(paths, kCpuWavefrontPaths);
    // A small largest buffer caps it too: the shadow rays are one buffer of 64 bytes a path.
    const std::uint32_t capped = default_wavefront_size(gpu_with(140 * kGiB, 64 * (cl_ulong{1} << 20)));
    EXPECT_EQ(capped, (64u << 20) / sizeof(dev::GcShadowRay));
}

TEST(WavefrontSize, CpusKeepSmallPasses)
{
    cl::DeviceInfo cpu;
    cpu.is_cpu = true;
    cpu.global_mem = 64 * kGiB;
    cpu.max_alloc = 16 * kGiB;
    EXPECT_EQ(default_wavefront_size(cpu), kCpuWavefrontPaths);
}

TEST(WavefrontSize, LaunchesAreCappedOnlyWhenAGridIsSet)
{
    EXPECT_EQ(wavefront_launch_size(1000, 0), 1000u);
    EXPECT_EQ(wavefront_launch_size(1000, 256), 256u);
    EXPECT_EQ(wavefront_launch_size(100, 256), 100u);
}

}  // namespace
}  // namespace gc
