#include "host/cl/buffer.h"

#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

#include "cl_test_util.h"
#include "gc_types.h"

namespace gc::cl {
namespace {

using test::DeviceTest;

TEST_F(DeviceTest, BufferRoundTrip)
{
    std::vector<float> data(1000);
    std::iota(data.begin(), data.end(), -3.25f);
    auto buffer = Buffer<float>::create(*context, data.size(), CL_MEM_READ_WRITE, "round trip");
    EXPECT_EQ(buffer.count(), 1000u);
    EXPECT_EQ(buffer.bytes(), 4000u);
    buffer.write(data);
    std::vector<float> back(data.size(), 0.0f);
    buffer.read(back);
    EXPECT_EQ(back, data);

    // Partial write at an offset, then a partial read.
    const std::vector<float> patch = {7.0f, 8.0f};
    buffer.write(patch, 500);
    std::vector<float> two(2);
    buffer.read(two, 500);
    EXPECT_EQ(two, patch);

    // Structs cross unchanged too.
    std::vector<dev::GcRay> rays(3);
    rays[1].org_tmin = {1, 2, 3, 0.5f};
    rays[2].dir_tmax = {4, 5, 6, 1e30f};
    auto ray_buffer = Buffer<dev::GcRay>::create(*context, rays.size(), CL_MEM_READ_ONLY, "rays");
    ray_buffer.write(rays);
    std::vector<dev::GcRay> rays_back(3);
    ray_buffer.read(rays_back);
    EXPECT_EQ(rays_back[1].org_tmin, rays[1].org_tmin);
    EXPECT_EQ(rays_back[2].dir_tmax, rays[2].dir_tmax);

    // Moving keeps the allocation.
    Buffer<float> moved = std::move(buffer);
    EXPECT_FALSE(buffer);
    moved.read(back);
    EXPECT_EQ(back[500], 7.0f);
}

TEST_F(DeviceTest, BufferZeroSize)
{
    auto buffer = Buffer<unsigned>::create(*context, 0, CL_MEM_READ_WRITE, "empty");
    EXPECT_TRUE(buffer);
    EXPECT_NE(buffer.mem(), nullptr);
    EXPECT_EQ(buffer.count(), 0u);
    EXPECT_EQ(buffer.bytes(), 0u);
    EXPECT_NO_THROW(buffer.write(std::span<const unsigned>{}));
    EXPECT_THROW(buffer.write(std::vector<unsigned>{1u}), DeviceError);
}

TEST_F(DeviceTest, BufferTooLargeNamesTheBuffer)
{
    const size_t count = context->device().max_alloc / sizeof(dev::GcBvhNode) + 1;
    try {
        Buffer<dev::GcBvhNode>::create(*context, count, CL_MEM_READ_ONLY, "bvh nodes");
        FAIL() << "no error for a buffer above max_alloc";
    } catch (const DeviceError& e) {
        const std::string message = e.what();
        std::printf("%s\n", message.c_str());
        EXPECT_NE(message.find("'bvh nodes'"), std::string::npos);
        EXPECT_NE(message.find(format_bytes(context->device().max_alloc)), std::string::npos);
        EXPECT_NE(message.find(std::to_string(count) + " elements"), std::string::npos);
        EXPECT_NE(message.find(context->device().device_name), std::string::npos);
    }
    // Element-count overflow is caught before any multiplication wraps.
    EXPECT_THROW(Buffer<dev::GcBvhNode>::create(*context, SIZE_MAX, CL_MEM_READ_ONLY, "huge"),
                 DeviceError);
}

TEST_F(DeviceTest, BufferOutOfRangeAccess)
{
    auto buffer = Buffer<int>::create(*context, 4, CL_MEM_READ_WRITE, "four ints");
    std::vector<int> five(5);
    try {
        buffer.read(five);
        FAIL() << "no error reading 5 of 4 elements";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("'four ints'"), std::string::npos) << e.what();
    }
    std::vector<int> two(2);
    EXPECT_THROW(buffer.write(two, 3), DeviceError);
    EXPECT_NO_THROW(buffer.write(two, 2));
}

}  // namespace
}  // namespace gc::cl
