#include "host/vk/instanced_aov.h"

#include <vector>

#include <glm/glm.hpp>

#include "host/vk/buffer.h"
#include "host/vk/pipeline.h"
#include "host/vk/scene_buffers.h"
#include "host/vk/shaders.h"
#include "kernels/vk/bindings.h"

namespace gc::vk {

Film render_instanced_aov(const Context& context, const InstancedScene& scene, const InstancedBvh& bvh,
                          const Camera& camera, const RenderSettings& settings)
{
    // The meshes' concatenated trees go where a flat scene's BVH goes (NODES, TRIS).
    FlatBvh meshes;
    meshes.nodes = bvh.nodes;
    meshes.triangles = bvh.tris;
    const EnvironmentMap environment = load_environment_map(settings);
    const SceneBuffers buffers = SceneBuffers::upload(context, scene.meshes, &meshes, camera, settings, &environment);
    const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    const Buffer tlas = Buffer::with_data(context, bvh.tlas, usage, "top-level nodes");
    const Buffer instances = Buffer::with_data(context, bvh.instances, usage, "instances");
    const auto width = static_cast<std::uint32_t>(settings.width);
    const auto height = static_cast<std::uint32_t>(settings.height);
    const std::size_t pixels = std::size_t(width) * height;
    Buffer film(context, pixels * sizeof(glm::vec4), usage, "film");
    film.fill_zero();

    StorageBufferSet set(context, GC_VK_INSTANCED_BINDING_COUNT, VK_SHADER_STAGE_COMPUTE_BIT);
    buffers.bind(set);
    set.bind(GC_VK_BINDING_FILM, film);
    set.bind(GC_VK_BINDING_TLAS, tlas);
    set.bind(GC_VK_BINDING_INSTANCES, instances);
    const PipelineLayout layout = make_pipeline_layout(context, set, sizeof(std::uint32_t), VK_SHADER_STAGE_COMPUTE_BIT);
    const Pipeline pipeline = make_compute_pipeline(context, layout.get(), shaders::aov_instances_comp(), "aov_instances.comp");
    const std::uint32_t sample_index = 0;
    context.submit_and_wait(
        [&](VkCommandBuffer cmd) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
            const VkDescriptorSet descriptors = set.set();
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout.get(), 0, 1, &descriptors, 0, nullptr);
            vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof sample_index, &sample_index);
            vkCmdDispatch(cmd, static_cast<std::uint32_t>((pixels + GC_VK_LOCAL_SIZE - 1) / GC_VK_LOCAL_SIZE), 1, 1);
            VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
            to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host,
                                 0, nullptr, 0, nullptr);
        },
        "rendering instanced AOVs with the Vulkan compute reference");
    std::vector<glm::vec4> sums(pixels);
    film.read(sums.data(), pixels * sizeof(glm::vec4));
    Film out(width, height);
    for (std::size_t i = 0; i < pixels; ++i)
        out.set(static_cast<std::uint32_t>(i % width), static_cast<std::uint32_t>(i / width),
                Rgba{sums[i].x, sums[i].y, sums[i].z, 1.0f});
    return out;
}

}  // namespace gc::vk
