#include "host/cl/buffer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <new>
#include <numeric>
#include <span>
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

// over_host: a CPU device reads the host array in place (the buffer's CL_MEM_HOST_PTR is the
// array itself); a GPU, or an array whose base the device would not accept, gets a copy.
// Either way the buffer holds the array's contents. Every device present is tried.
TEST_F(DeviceTest, BufferOverHostReadsTheArrayInPlaceOnCpus)
{
    constexpr std::size_t count = 4096;
    constexpr std::size_t align = 4096;
    struct Free {
        void operator()(float* p) const { ::operator delete(p, std::align_val_t{align}); }
    };
    const std::unique_ptr<float, Free> raw(
        static_cast<float*>(::operator new((count + 1) * sizeof(float), std::align_val_t{align})));
    std::iota(raw.get(), raw.get() + count + 1, 0.5f);
    for (const DeviceInfo& device : devices) {
        const Context device_context(device);
        for (const std::size_t offset : {std::size_t{0}, std::size_t{1}}) {  // aligned, then 4 bytes off
            const std::span<const float> data(raw.get() + offset, count);
            auto buffer = Buffer<float>::over_host(device_context, data, "over host");
            void* host_ptr = nullptr;
            ASSERT_EQ(clGetMemObjectInfo(buffer.mem(), CL_MEM_HOST_PTR, sizeof(host_ptr), &host_ptr, nullptr),
                      CL_SUCCESS);
            const bool in_place = host_ptr == static_cast<const void*>(data.data());
            const bool expected = device.is_cpu && offset == 0 && device.base_addr_align > 0 &&
                                  align % device.base_addr_align == 0;
            std::vector<float> back(count);
            buffer.read(back);
            std::size_t same = 0;
            for (std::size_t i = 0; i < count; ++i) same += back[i] == data[i] ? 1 : 0;
            std::printf("[over_host] %s (asks %u-byte bases), base offset %zu bytes: %s, %zu of %zu elements read back\n",
                        device.device_name.c_str(), device.base_addr_align, offset * sizeof(float),
                        in_place ? "in place" : "copied", same, count);
            EXPECT_EQ(in_place, expected) << device.device_name;
            EXPECT_EQ(same, count) << device.device_name;
        }
    }
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
