// One Vulkan context (and one OpenCL context) for the whole test binary, and fixtures that
// skip, with the reason, when the machine has no such device.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "host/cl/context.h"
#include "host/cl/device.h"
#include "host/util/error.h"
#include "host/vk/context.h"

namespace gc::vk {

// $GEOCOLD_TEST_VK_DEVICE or "any"; null (and *why set) when no device opens.
inline Context* shared_vk_context(std::string* why)
{
    static std::unique_ptr<Context> context;
    static std::string failure;
    static bool tried = false;
    if (!tried) {
        tried = true;
        try {
            const char* spec = std::getenv("GEOCOLD_TEST_VK_DEVICE");
            context = std::make_unique<Context>(spec ? spec : "any");
        } catch (const DeviceError& e) {
            failure = e.what();
        }
    }
    if (why) *why = failure;
    return context.get();
}

// $GEOCOLD_TEST_DEVICE or "any", as in tests/cl.
inline cl::Context* shared_cl_context(std::string* why)
{
    static std::unique_ptr<cl::Context> context;
    static std::string failure;
    static bool tried = false;
    if (!tried) {
        tried = true;
        std::string reason;
        const std::vector<cl::DeviceInfo> devices = cl::list_devices(&reason);
        if (devices.empty()) {
            failure = "no OpenCL device: " + reason;
        } else {
            const char* spec = std::getenv("GEOCOLD_TEST_DEVICE");
            context = std::make_unique<cl::Context>(cl::select_device(spec ? spec : "any", devices));
        }
    }
    if (why) *why = failure;
    return context.get();
}

class VkDeviceTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        std::string why;
        context = shared_vk_context(&why);
        if (!context) GTEST_SKIP() << "no Vulkan device: " << why;
    }
    Context* context = nullptr;
};

}  // namespace gc::vk
