// RAII ownership of Vulkan handles that a VkDevice creates: one template instead of one
// hand-written class per handle kind. Move-only; destroys through the matching vkDestroy*.
//
//     using Fence = DeviceHandle<VkFence, vkDestroyFence>;
//     Fence fence(device, raw_fence);   // destroyed when `fence` goes out of scope
#pragma once

#include <utility>

#include <vulkan/vulkan.h>

namespace gc::vk {

template <typename Handle, auto Destroy>
class DeviceHandle {
public:
    DeviceHandle() = default;
    DeviceHandle(VkDevice device, Handle handle) : m_device(device), m_handle(handle) {}
    ~DeviceHandle() { reset(); }

    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;
    DeviceHandle(DeviceHandle&& other) noexcept
        : m_device(other.m_device), m_handle(std::exchange(other.m_handle, VK_NULL_HANDLE))
    {
    }
    DeviceHandle& operator=(DeviceHandle&& other) noexcept
    {
        if (this != &other) {
            reset();
            m_device = other.m_device;
            m_handle = std::exchange(other.m_handle, VK_NULL_HANDLE);
        }
        return *this;
    }

    Handle get() const { return m_handle; }
    explicit operator bool() const { return m_handle != VK_NULL_HANDLE; }

    void reset()
    {
        if (m_handle != VK_NULL_HANDLE) Destroy(m_device, m_handle, nullptr);
        m_handle = VK_NULL_HANDLE;
    }

private:
    VkDevice m_device = VK_NULL_HANDLE;
    Handle m_handle = VK_NULL_HANDLE;
};

using Fence = DeviceHandle<VkFence, vkDestroyFence>;
using CommandPool = DeviceHandle<VkCommandPool, vkDestroyCommandPool>;
using BufferHandle = DeviceHandle<VkBuffer, vkDestroyBuffer>;
using Memory = DeviceHandle<VkDeviceMemory, vkFreeMemory>;
using Image = DeviceHandle<VkImage, vkDestroyImage>;
using ImageView = DeviceHandle<VkImageView, vkDestroyImageView>;
using ShaderModule = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using DescriptorSetLayout = DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using DescriptorPool = DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>;
using PipelineLayout = DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>;
using Pipeline = DeviceHandle<VkPipeline, vkDestroyPipeline>;
using RenderPass = DeviceHandle<VkRenderPass, vkDestroyRenderPass>;
using Framebuffer = DeviceHandle<VkFramebuffer, vkDestroyFramebuffer>;

}  // namespace gc::vk
