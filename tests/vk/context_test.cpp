// Device choice and error messages (pure), and the headless context on whatever Vulkan
// device the machine has (lavapipe in CI); device tests skip without one.
#include <gtest/gtest.h>

#include <vector>

#include "host/util/error.h"
#include "host/vk/buffer.h"
#include "host/vk/context.h"
#include "host/vk/vk_error.h"
#include "tests/vk/vk_test_util.h"

namespace gc::vk {
namespace {

PhysicalDeviceInfo device(const char* name, VkPhysicalDeviceType type, bool queue = true)
{
    PhysicalDeviceInfo d;
    d.name = name;
    d.type = type;
    d.api_version = VK_API_VERSION_1_3;
    d.has_graphics_compute_queue = queue;
    return d;
}

const std::vector<PhysicalDeviceInfo> kDevices = {
    device("llvmpipe (LLVM 15.0.6, 256 bits)", VK_PHYSICAL_DEVICE_TYPE_CPU),
    device("Intel(R) UHD Graphics 630", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU),
    device("NVIDIA H100 80GB HBM3", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU),
    device("Compute-only accelerator", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, false),
};

TEST(ChooseDevice, AnyPrefersDiscreteThenIntegratedThenCpu)
{
    EXPECT_EQ(choose_device(kDevices, "any"), 2u);
    EXPECT_EQ(choose_device({kDevices[0], kDevices[1]}, "any"), 1u);
    EXPECT_EQ(choose_device({kDevices[0]}, "any"), 0u);
}

TEST(ChooseDevice, LavapipeAndNameSubstring)
{
    EXPECT_EQ(choose_device(kDevices, "lavapipe"), 0u);
    EXPECT_EQ(choose_device(kDevices, "LAVAPIPE"), 0u);
    EXPECT_EQ(choose_device(kDevices, "h100"), 2u);
    EXPECT_EQ(choose_device(kDevices, "UHD"), 1u);
}

TEST(ChooseDevice, DevicesWithoutAGraphicsComputeQueueNeverQualify)
{
    EXPECT_THROW(choose_device(kDevices, "accelerator"), DeviceError);
    EXPECT_THROW(choose_device({kDevices[3]}, "any"), DeviceError);
}

TEST(ChooseDevice, NoMatchNamesTheSpecAndTheDevices)
{
    try {
        choose_device(kDevices, "radeon");
        FAIL() << "expected DeviceError";
    } catch (const DeviceError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("--vk-device 'radeon'"), std::string::npos) << m;
        EXPECT_NE(m.find("NVIDIA H100"), std::string::npos) << m;
    }
    EXPECT_THROW(choose_device({}, "any"), DeviceError);
    EXPECT_THROW(choose_device({kDevices[1]}, "lavapipe"), DeviceError);
}

TEST(VkError, MessageNamesCallResultAndContext)
{
    EXPECT_EQ(format_failure("vkAllocateMemory", VK_ERROR_OUT_OF_DEVICE_MEMORY, "allocating 'bvh nodes'"),
              "vkAllocateMemory failed: VK_ERROR_OUT_OF_DEVICE_MEMORY while allocating 'bvh nodes'");
    EXPECT_EQ(format_failure("vkQueueSubmit", VK_ERROR_DEVICE_LOST, ""), "vkQueueSubmit failed: VK_ERROR_DEVICE_LOST");
    EXPECT_EQ(result_name(static_cast<VkResult>(-424242)), "VK_RESULT(-424242)");
    EXPECT_NO_THROW(check(VK_SUCCESS, "vkCreateFence"));
    EXPECT_THROW(check(VK_ERROR_INITIALIZATION_FAILED, "vkCreateInstance"), DeviceError);
}

TEST_F(VkDeviceTest, OpensAHeadlessDeviceWithAGraphicsComputeQueue)
{
    std::printf("Vulkan device: %s\n", context->description().c_str());
    EXPECT_TRUE(context->info().has_graphics_compute_queue);
    EXPECT_GE(context->info().api_version, VK_API_VERSION_1_1);
    EXPECT_NE(context->device(), VK_NULL_HANDLE);
}

TEST_F(VkDeviceTest, BufferRoundTrip)
{
    const std::vector<std::uint32_t> data = {1, 2, 3, 0xdeadbeefu};
    Buffer b = Buffer::with_data(*context, data, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "round trip");
    std::vector<std::uint32_t> back(4);
    b.read(back.data(), 16);
    EXPECT_EQ(back, data);
    EXPECT_THROW(b.read(back.data(), 32), DeviceError);
    // Vulkan has no empty buffers: an empty upload still makes a valid (16-byte) buffer.
    const Buffer empty = Buffer::with_data(*context, std::vector<float>{}, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "empty");
    EXPECT_EQ(empty.size(), 16u);
}

TEST_F(VkDeviceTest, AllocationFailureNamesTheBuffer)
{
    try {
        Buffer b(*context, VkDeviceSize(1) << 52, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "absurd film");
        GTEST_SKIP() << "the driver accepted a 4 PiB buffer";
    } catch (const DeviceError& e) {
        const std::string m = e.what();
        std::printf("%s\n", m.c_str());
        EXPECT_NE(m.find("failed: VK_ERROR_"), std::string::npos) << m;
        EXPECT_NE(m.find("while allocating 'absurd film'"), std::string::npos) << m;
    }
}

TEST_F(VkDeviceTest, UnknownDeviceSpecIsADeviceError)
{
    EXPECT_THROW(Context("no-such-vulkan-device-xyz"), DeviceError);
}

}  // namespace
}  // namespace gc::vk
