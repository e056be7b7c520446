#include "host/vk/pipeline.h"

#include <vector>

#include "host/vk/no_contraction.h"
#include "host/vk/vk_error.h"

namespace gc::vk {

ShaderModule make_shader_module(const Context& context, std::span<const std::uint32_t> spirv, const std::string& name)
{
    const std::vector<std::uint32_t> code = without_contraction(spirv);
    VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    ci.codeSize = code.size() * sizeof(std::uint32_t);
    ci.pCode = code.data();
    VkShaderModule module = VK_NULL_HANDLE;
    check(vkCreateShaderModule(context.device(), &ci, nullptr, &module), "vkCreateShaderModule",
          "loading shader '" + name + "'");
    return ShaderModule(context.device(), module);
}

StorageBufferSet::StorageBufferSet(const Context& context, std::uint32_t count, VkShaderStageFlags stages)
    : m_context(context)
{
    std::vector<VkDescriptorSetLayoutBinding> bindings(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        bindings[i].binding = i;
        bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bindings[i].descriptorCount = 1;
        bindings[i].stageFlags = stages;
    }
    VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    lci.bindingCount = count;
    lci.pBindings = bindings.data();
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    check(vkCreateDescriptorSetLayout(context.device(), &lci, nullptr, &layout), "vkCreateDescriptorSetLayout",
          "describing the scene buffers");
    m_layout = DescriptorSetLayout(context.device(), layout);

    VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, count};
    VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pci.maxSets = 1;
    pci.poolSizeCount = 1;
    pci.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    check(vkCreateDescriptorPool(context.device(), &pci, nullptr, &pool), "vkCreateDescriptorPool",
          "creating the descriptor pool");
    m_pool = DescriptorPool(context.device(), pool);

    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = pool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &layout;
    check(vkAllocateDescriptorSets(context.device(), &ai, &m_set), "vkAllocateDescriptorSets",
          "allocating the scene descriptor set");
}

void StorageBufferSet::bind(std::uint32_t binding, const Buffer& buffer)
{
    VkDescriptorBufferInfo info{buffer.get(), 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = m_set;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &info;
    vkUpdateDescriptorSets(m_context.device(), 1, &w, 0, nullptr);
}

PipelineLayout make_pipeline_layout(const Context& context, const StorageBufferSet& set, std::uint32_t push_bytes,
                                    VkShaderStageFlags push_stages)
{
    const VkDescriptorSetLayout set_layout = set.layout();
    VkPushConstantRange range{push_stages, 0, push_bytes};
    VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    ci.setLayoutCount = 1;
    ci.pSetLayouts = &set_layout;
    ci.pushConstantRangeCount = push_bytes > 0 ? 1 : 0;
    ci.pPushConstantRanges = push_bytes > 0 ? &range : nullptr;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    check(vkCreatePipelineLayout(context.device(), &ci, nullptr, &layout), "vkCreatePipelineLayout",
          "creating a pipeline layout");
    return PipelineLayout(context.device(), layout);
}

Pipeline make_compute_pipeline(const Context& context, VkPipelineLayout layout, std::span<const std::uint32_t> spirv,
                               const std::string& name)
{
    const ShaderModule module = make_shader_module(context, spirv, name);
    VkComputePipelineCreateInfo ci{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
    ci.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    ci.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    ci.stage.module = module.get();
    ci.stage.pName = "main";
    ci.layout = layout;
    VkPipeline pipeline = VK_NULL_HANDLE;
    check(vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &ci, nullptr, &pipeline),
          "vkCreateComputePipelines", "building compute pipeline '" + name + "'");
    return Pipeline(context.device(), pipeline);
}

}  // namespace gc::vk
