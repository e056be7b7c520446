// host/render/renderer and wavefront_launches: how many paths a pass holds by default, and how
// many work-items a wavefront launch gets (the device side of both is in tests/validation/determinism_test.cpp).
#include <gtest/gtest.h>

#include <cstdio>
#include <optional>
#include <vector>

#include "host/render/wavefront_path.h"

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

TEST(WavefrontSize, LaunchesAreCappedOnlyWhenAWidthIsSet)
{
    EXPECT_EQ(wavefront_launch_size(1000, 0), 1000u);
    EXPECT_EQ(wavefront_launch_size(1000, 256), 256u);
    EXPECT_EQ(wavefront_launch_size(100, 256), 100u);
}

// Queue lengths of a batch of 10000 paths over 3 depths: rays queued for the next depth, then
// shadow rays, per depth.
constexpr std::uint32_t kRecordedPaths = 10000;
const std::vector<std::uint32_t> kRecordedLengths = {8000, 9000, 5000, 7000, 2000, 4000};

TEST(WavefrontLaunches, FirstBatchUsesTheFirstWidthAfterTheFirstBounce)
{
    const WavefrontLaunches launches(3, std::nullopt, 4096, 64);
    EXPECT_FALSE(launches.has_history());
    EXPECT_EQ(launches.ray_width(0, kRecordedPaths), 0u);  // one per entry: the full first queue
    EXPECT_EQ(launches.shadow_width(0, kRecordedPaths), 0u);
    EXPECT_EQ(launches.ray_width(1, kRecordedPaths), 4096u);
    EXPECT_EQ(launches.shadow_width(2, kRecordedPaths), 4096u);
}

TEST(WavefrontLaunches, LaterBatchesAreSizedFromTheLastOnesLengthsAtTheSameDepth)
{
    WavefrontLaunches launches(3, std::nullopt, 4096, 64);
    launches.record(kRecordedLengths, kRecordedPaths);
    ASSERT_TRUE(launches.has_history());
    // Extend and shade at depth d see the rays depth d - 1 queued; a sixteenth more, plus 64.
    EXPECT_EQ(launches.ray_width(0, kRecordedPaths), 0u);
    EXPECT_EQ(launches.ray_width(1, kRecordedPaths), 8000u + 500u + 64u);
    EXPECT_EQ(launches.ray_width(2, kRecordedPaths), 5000u + 312u + 64u);
    EXPECT_EQ(launches.shadow_width(0, kRecordedPaths), 9000u + 562u + 64u);
    EXPECT_EQ(launches.shadow_width(2, kRecordedPaths), 4000u + 250u + 64u);
    // Scaled to a batch of half the paths; never wider than the batch.
    EXPECT_EQ(launches.ray_width(2, kRecordedPaths / 2), 2500u + 156u + 64u);
    EXPECT_EQ(launches.shadow_width(0, 100), 100u);
    std::printf("depth 1 of 10000 paths after a batch that queued 8000: %u work-items\n", launches.ray_width(1, 10000));
}

TEST(WavefrontLaunches, EmptyQueuesStillGetTheLeastWidth)
{
    // A depth no path reached last time may be reached now: the kernels loop over whatever
    // the queue holds, so a small launch is enough, but never 0 (one per entry).
    WavefrontLaunches launches(3, std::nullopt, 4096, 64);
    launches.record(std::vector<std::uint32_t>(6, 0u), kRecordedPaths);
    EXPECT_EQ(launches.ray_width(2, kRecordedPaths), 64u);
    EXPECT_EQ(launches.shadow_width(1, 10), 10u);
}

TEST(WavefrontLaunches, AFixedWidthIgnoresRecordedBatches)
{
    WavefrontLaunches launches(3, 132u, 4096, 64);
    launches.record(kRecordedLengths, kRecordedPaths);
    EXPECT_EQ(launches.ray_width(0, kRecordedPaths), 0u);
    EXPECT_EQ(launches.ray_width(1, kRecordedPaths), 132u);
    EXPECT_EQ(launches.shadow_width(0, kRecordedPaths), 0u);
    EXPECT_EQ(launches.shadow_width(2, kRecordedPaths), 132u);
}

TEST(WavefrontLaunches, LengthsOfTheWrongCountAreIgnored)
{
    WavefrontLaunches launches(4, std::nullopt, 4096, 64);
    launches.record(kRecordedLengths, kRecordedPaths);  // 3 depths' worth, 4 expected
    EXPECT_FALSE(launches.has_history());
    launches.record(std::vector<std::uint32_t>(8, 1u), 0);  // from no paths
    EXPECT_FALSE(launches.has_history());
    EXPECT_EQ(launches.ray_width(3, kRecordedPaths), 4096u);
}

}  // namespace
}  // namespace gc
