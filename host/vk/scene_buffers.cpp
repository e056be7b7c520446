#include "host/vk/scene_buffers.h"

#include <vector>

#include <glm/glm.hpp>

#include "gc_sheen_table.h"
#include "gc_srgb_table.h"
#include "host/render/scene_convert.h"
#include "kernels/vk/bindings.h"

namespace gc::vk {
namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;

}  // namespace

SceneBuffers SceneBuffers::upload(const Context& context, const Scene& scene, const FlatBvh* bvh, const Camera& camera,
                                  const RenderSettings& settings, const EnvironmentMap* environment,
                                  std::uint32_t first_emitter)
{
    const EnvironmentMap none;
    const EnvironmentMap& env = environment ? *environment : none;
    const DeviceTextures tex = make_textures(scene);
    const std::vector<dev::GcEmitter> emitters = make_emitters(scene, first_emitter);
    std::vector<glm::vec4> positions;
    positions.reserve(scene.positions.size());
    for (const Point3& p : scene.positions) positions.emplace_back(p.x, p.y, p.z, 1.0f);

    SceneBuffers b{
        Buffer(context, sizeof(dev::GcRenderParams), kStorage, "render parameters"),
        Buffer::with_data(context, bvh ? bvh->nodes : BigArray<dev::GcBvhNode>{}, kStorage, "bvh nodes"),
        Buffer::with_data(context, bvh ? bvh->triangles : BigArray<dev::GcTriangle>{}, kStorage, "bvh triangles"),
        Buffer::with_data(context, make_triangle_attribs(scene), kStorage, "triangle attributes"),
        Buffer::with_data(context, make_materials(scene), kStorage, "materials"),
        Buffer::with_data(context, tex.textures, kStorage, "textures"),
        Buffer::with_data(context, tex.texels, kStorage, "texels"),
        Buffer::with_data(context, emitters, kStorage, "emitters"),
        Buffer::with_data(context, positions, kStorage, "vertex positions"),
        Buffer::with_data(context, std::span<const float>(dev::gc_srgb_to_linear_table), kStorage, "sRGB table"),
        Buffer::with_data(context, std::span<const float>(dev::gc_sheen_albedo_table), kStorage, "sheen albedo table"),
        Buffer::with_data(context, make_point_lights(scene), kStorage, "point lights"),
        Buffer::with_data(context, env.pixels, kStorage, "environment map"),
        Buffer::with_data(context, env.marginal_cdf, kStorage, "environment marginal cdf"),
        Buffer::with_data(context, env.conditional_cdf, kStorage, "environment conditional cdf"),
        make_render_params(summarize(scene, emitters, tex.textures.size()), camera, settings),
    };
    if (environment) set_environment_map(b.host_params, settings, env.width, env.height);
    b.params.write(&b.host_params, sizeof b.host_params);
    return b;
}

void SceneBuffers::bind(StorageBufferSet& set) const
{
    set.bind(GC_VK_BINDING_PARAMS, params);
    set.bind(GC_VK_BINDING_NODES, nodes);
    set.bind(GC_VK_BINDING_TRIS, triangles);
    set.bind(GC_VK_BINDING_ATTRIBS, attribs);
    set.bind(GC_VK_BINDING_MATERIALS, materials);
    set.bind(GC_VK_BINDING_TEXTURES, textures);
    set.bind(GC_VK_BINDING_TEXELS, texels);
    set.bind(GC_VK_BINDING_EMITTERS, emitters);
    set.bind(GC_VK_BINDING_POSITIONS, positions);
    set.bind(GC_VK_BINDING_SRGB, srgb_table);
    set.bind(GC_VK_BINDING_SHEEN, sheen_table);
    set.bind(GC_VK_BINDING_POINT_LIGHTS, point_lights);
    set.bind(GC_VK_BINDING_ENV_PIXELS, env_pixels);
    set.bind(GC_VK_BINDING_ENV_MARGINAL, env_marginal);
    set.bind(GC_VK_BINDING_ENV_CONDITIONAL, env_conditional);
}

}  // namespace gc::vk
