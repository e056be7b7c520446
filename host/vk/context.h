// A headless Vulkan device: instance (no window-system extensions), one physical device
// chosen by a user spec, a logical device with one graphics+compute queue, and a command
// pool for one-shot submissions. Everything the Vulkan path (raster pass, compute
// reference) needs to start; every failure is a DeviceError naming the call.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "host/vk/handle.h"

namespace gc::vk {

struct PhysicalDeviceInfo {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    std::string name;                 // VkPhysicalDeviceProperties::deviceName
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    std::uint32_t api_version = 0;    // what the driver supports
    bool has_graphics_compute_queue = false;
};

// "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other".
const char* device_type_name(VkPhysicalDeviceType type);

// Which device a spec picks, from a list (pure, so tests run it without a driver):
//   "any"      the first discrete GPU, else integrated, else virtual, else other, else CPU
//              (lavapipe); devices without a graphics+compute queue never qualify;
//   "lavapipe" Mesa's CPU driver (name contains "llvmpipe") or else any CPU device;
//   otherwise  the first device whose name contains the spec, case-insensitively.
// Throws DeviceError listing the devices when nothing matches.
std::size_t choose_device(const std::vector<PhysicalDeviceInfo>& devices, const std::string& spec);

class Context {
public:
    // Creates the instance and the device picked by `device_spec` (see choose_device).
    explicit Context(const std::string& device_spec = "any");
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkDevice device() const { return m_device; }
    VkPhysicalDevice physical_device() const { return m_info.handle; }
    VkQueue queue() const { return m_queue; }
    std::uint32_t queue_family() const { return m_queue_family; }
    const PhysicalDeviceInfo& info() const { return m_info; }
    // "llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan 1.3.230, CPU)".
    std::string description() const;

    // A memory type allowed by type_bits with all the `required` properties; DeviceError
    // naming `what` when there is none.
    std::uint32_t memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required, const std::string& what) const;

    // Records into a fresh primary command buffer, submits it and waits for its fence.
    // `what` completes the error messages ("... while <what>").
    void submit_and_wait(const std::function<void(VkCommandBuffer)>& record, const std::string& what) const;

private:
    VkInstance m_instance = VK_NULL_HANDLE;
    VkDevice m_device = VK_NULL_HANDLE;
    PhysicalDeviceInfo m_info;
    VkQueue m_queue = VK_NULL_HANDLE;
    std::uint32_t m_queue_family = 0;
    VkPhysicalDeviceMemoryProperties m_memory{};
    CommandPool m_pool;
};

}  // namespace gc::vk
