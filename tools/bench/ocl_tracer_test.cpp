// The bench's GPU ray launches trace the set several times over (OclTracer::set_min_launch_rays),
// so that a launch fills the device; the copies must find the set's own hits, and the times
// must be per pass over the set. Run on every OpenCL device present (PoCL here, the GPU on a
// GPU node), with a small set and a small least launch.
#include "tools/bench/ocl_bench.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "gc_accessors.h"
#include "host/bvh/bvh.h"
#include "host/cl/device.h"
#include "tests/bvh/test_scenes.h"

namespace gc::bench {
namespace {

std::vector<dev::GcRay> rays_through_the_soup(int count)
{
    std::vector<dev::GcRay> rays;
    for (int i = 0; i < count; ++i) {
        const float x = -1.0f + 2.0f * float(i % 64) / 64.0f;
        const float y = -1.0f + 2.0f * float(i / 64) / float(count / 64 + 1);
        rays.push_back(dev::gc_make_ray({x, y, -3.0f}, {0.05f, -0.03f, 1.0f}, 0.0f, GC_RAY_UNBOUNDED));
    }
    return rays;
}

TEST(OclTracer, CopiesOfTheSetFindItsHits)
{
    std::string why;
    const std::vector<cl::DeviceInfo> devices = cl::list_devices(&why);
    if (devices.empty()) GTEST_SKIP() << "no OpenCL device: " << why;
    const Scene scene = test::random_soup(3000, 11);  // in [-1, 1]^3
    const FlatBvh bvh = build_bvh(scene);
    const std::vector<dev::GcRay> rays = rays_through_the_soup(1000);
    for (const cl::DeviceInfo& info : devices) {
        SCOPED_TRACE(info.device_name);
        const cl::Context context(info);
        OclTracer tracer(context, bvh);
        std::vector<std::uint32_t> alone, copied, occluded_alone, occluded_copied;
        tracer.closest(rays, 2, alone);
        EXPECT_EQ(tracer.copies(), 1u);
        tracer.occluded(rays, 2, occluded_alone);

        tracer.set_min_launch_rays(4500);  // 5 copies of 1000 rays
        const std::vector<double> times = tracer.closest(rays, 3, copied);
        EXPECT_EQ(tracer.copies(), 5u);
        tracer.occluded(rays, 2, occluded_copied);
        EXPECT_EQ(tracer.copies(), 5u);

        std::size_t hits = 0;
        for (const std::uint32_t prim : alone) hits += prim != GC_INVALID;
        std::printf("[ ocl tracer ] %s: %zu of %zu rays hit; 5 copies per launch found the same hits: %s, "
                    "occlusion: %s\n",
                    info.device_name.c_str(), hits, rays.size(), copied == alone ? "yes" : "NO",
                    occluded_copied == occluded_alone ? "yes" : "NO");
        EXPECT_GT(hits, rays.size() / 4) << "the rays must cross the soup";
        EXPECT_EQ(copied, alone);
        EXPECT_EQ(occluded_copied, occluded_alone);
        ASSERT_EQ(times.size(), 3u);
        for (const double t : times) EXPECT_GT(t, 0.0);
    }
}

}  // namespace
}  // namespace gc::bench
