#include "host/vk/compute_reference.h"

#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "host/util/error.h"
#include "host/vk/shaders.h"
#include "kernels/vk/bindings.h"

namespace gc::vk {
namespace {

SceneBuffers upload_for_tracing(const Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
                                const RenderSettings& settings)
{
    const EnvironmentMap environment = load_environment_map(settings);
    return SceneBuffers::upload(context, scene, &bvh, camera, settings, &environment);
}

// The meshes' concatenated trees go where a flat scene's BVH goes (NODES, TRIS); the world
// emitters follow the meshes' triangles.
SceneBuffers upload_for_tracing(const Context& context, const InstancedScene& scene, const InstancedBvh& bvh,
                                const Camera& camera, const RenderSettings& settings)
{
    FlatBvh meshes;
    meshes.nodes = bvh.nodes;
    meshes.triangles = bvh.tris;
    const EnvironmentMap environment = load_environment_map(settings);
    return SceneBuffers::upload(context, with_world_emitters(scene), &meshes, camera, settings, &environment,
                                static_cast<std::uint32_t>(scene.meshes.triangle_count()));
}

std::span<const std::uint32_t> shader_for(IntegratorKind integrator, bool instanced)
{
    switch (integrator) {
    case IntegratorKind::Path: return instanced ? shaders::path_instances_comp() : shaders::path_comp();
    case IntegratorKind::Whitted: return instanced ? shaders::whitted_instances_comp() : shaders::whitted_comp();
    case IntegratorKind::Aov: return instanced ? shaders::aov_instances_comp() : shaders::aov_comp();
    }
    throw UsageError(std::string("the Vulkan compute reference has no ") + integrator_name(integrator) + " integrator");
}

std::string shader_name(IntegratorKind integrator, bool instanced)
{
    return std::string(integrator_name(integrator)) + (instanced ? "_instances" : "") + ".comp";
}

}  // namespace

ComputeReference::ComputeReference(const Context& context, const Scene& scene, const FlatBvh& bvh,
                                   const Camera& camera, const RenderSettings& settings)
    : m_context(context),
      m_width(static_cast<std::uint32_t>(settings.width)),
      m_height(static_cast<std::uint32_t>(settings.height)),
      m_scene(upload_for_tracing(context, scene, bvh, camera, settings)),
      m_film(context, VkDeviceSize(m_width) * m_height * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "film"),
      m_set(context, GC_VK_BINDING_COUNT, VK_SHADER_STAGE_COMPUTE_BIT)
{
    make_pipeline(shader_for(settings.integrator, false), shader_name(settings.integrator, false));
}

ComputeReference::ComputeReference(const Context& context, const InstancedScene& scene, const InstancedBvh& bvh,
                                   const Camera& camera, const RenderSettings& settings)
    : m_context(context),
      m_width(static_cast<std::uint32_t>(settings.width)),
      m_height(static_cast<std::uint32_t>(settings.height)),
      m_scene(upload_for_tracing(context, scene, bvh, camera, settings)),
      m_tlas(Buffer::with_data(context, bvh.tlas, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "top-level nodes")),
      m_instances(Buffer::with_data(context, bvh.instances, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "instances")),
      m_film(context, VkDeviceSize(m_width) * m_height * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "film"),
      m_set(context, GC_VK_INSTANCED_BINDING_COUNT, VK_SHADER_STAGE_COMPUTE_BIT)
{
    m_set.bind(GC_VK_BINDING_TLAS, m_tlas);
    m_set.bind(GC_VK_BINDING_INSTANCES, m_instances);
    make_pipeline(shader_for(settings.integrator, true), shader_name(settings.integrator, true));
}

void ComputeReference::make_pipeline(std::span<const std::uint32_t> shader, const std::string& name)
{
    m_film.fill_zero();
    m_scene.bind(m_set);
    m_set.bind(GC_VK_BINDING_FILM, m_film);
    m_layout = make_pipeline_layout(m_context, m_set, sizeof(std::uint32_t), VK_SHADER_STAGE_COMPUTE_BIT);
    m_pipeline = make_compute_pipeline(m_context, m_layout.get(), shader, name);
}

void ComputeReference::render_sample()
{
    const std::uint32_t pixels = m_width * m_height;
    const std::uint32_t sample_index = m_samples;
    m_context.submit_and_wait(
        [&](VkCommandBuffer cmd) {
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_pipeline.get());
            const VkDescriptorSet set = m_set.set();
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m_layout.get(), 0, 1, &set, 0, nullptr);
            vkCmdPushConstants(cmd, m_layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof sample_index, &sample_index);
            vkCmdDispatch(cmd, (pixels + GC_VK_LOCAL_SIZE - 1) / GC_VK_LOCAL_SIZE, 1, 1);
            VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
            to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
            to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host,
                                 0, nullptr, 0, nullptr);
        },
        "rendering sample " + std::to_string(sample_index) + " with the Vulkan compute reference");
    ++m_samples;
}

Film ComputeReference::film() const
{
    const std::size_t pixels = std::size_t(m_width) * m_height;
    std::vector<glm::vec4> sums(pixels);
    m_film.read(sums.data(), pixels * sizeof(glm::vec4));
    Film film(m_width, m_height);
    // Same arithmetic as Renderer::film(): the sum times the reciprocal of the count.
    const float inv = m_samples > 0 ? 1.0f / static_cast<float>(m_samples) : 0.0f;
    for (std::size_t i = 0; i < pixels; ++i) {
        const auto x = static_cast<std::uint32_t>(i % m_width);
        const auto y = static_cast<std::uint32_t>(i / m_width);
        film.set(x, y, Rgba{sums[i].x * inv, sums[i].y * inv, sums[i].z * inv, 1.0f});
    }
    return film;
}

}  // namespace gc::vk
