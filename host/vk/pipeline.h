// Shader modules, a descriptor set of storage buffers, and compute pipelines: the pieces
// both Vulkan passes share. Pipelines are built once per pass ("one-shot"); nothing here
// caches or reuses them.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include <vulkan/vulkan.h>

#include "host/vk/buffer.h"
#include "host/vk/context.h"
#include "host/vk/handle.h"

namespace gc::vk {

ShaderModule make_shader_module(const Context& context, std::span<const std::uint32_t> spirv, const std::string& name);

// One descriptor set whose bindings 0 .. count-1 are all storage buffers, visible to
// `stages`. Bind every binding before the set is used.
class StorageBufferSet {
public:
    StorageBufferSet(const Context& context, std::uint32_t count, VkShaderStageFlags stages);
    void bind(std::uint32_t binding, const Buffer& buffer);

    VkDescriptorSetLayout layout() const { return m_layout.get(); }
    VkDescriptorSet set() const { return m_set; }

private:
    const Context& m_context;
    DescriptorSetLayout m_layout;
    DescriptorPool m_pool;
    VkDescriptorSet m_set = VK_NULL_HANDLE; // freed with the pool
};

// A pipeline layout of one StorageBufferSet plus `push_bytes` of push constants (0 = none)
// for `push_stages`.
PipelineLayout make_pipeline_layout(const Context& context, const StorageBufferSet& set, std::uint32_t push_bytes,
                                    VkShaderStageFlags push_stages);

Pipeline make_compute_pipeline(const Context& context, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                               const std::string& name);

}  // namespace gc::vk
