#include "host/render/device_scene.h"

#include <span>
#include <string>
#include <vector>

#include "host/render/scene_convert.h"
#include "host/util/error.h"

namespace gc {
std::uint64_t DeviceScene::bytes() const
{
    return bvh.bytes() + instance_level.tlas.bytes() + instance_level.instances.bytes() + attribs.bytes() +
           materials.bytes() + textures.bytes() + texels.bytes() + emitters.bytes() + point_lights.bytes() +
           env_pixels.bytes() + env_marginal.bytes() + env_conditional.bytes();
}

DeviceScene DeviceScene::upload(const cl::Context& context, const Scene& scene, const FlatBvh& bvh,
                                const EnvironmentMap& environment, const DeviceTuning& tuning)
{
    DeviceScene d;
    d.bvh = DeviceBvh::upload(context, bvh, bvh_layout_for(context.device(), tuning.bvh_layout));
    d.upload_shading(context, scene, 0, environment, tuning);
    return d;
}

DeviceScene DeviceScene::upload_instanced(const cl::Context& context, const InstancedScene& scene,
                                          const InstanceBvhParts& bvh, const EnvironmentMap& environment,
                                          const DeviceTuning& tuning)
{
    DeviceScene d;
    d.bvh = DeviceBvh::upload_instanced(context, bvh, bvh_layout_for(context.device(), tuning.bvh_layout),
                                        d.instance_level);
    const auto meshes = static_cast<std::uint32_t>(scene.meshes.triangle_count());
    d.upload_shading(context, with_world_emitters(scene), meshes, environment, tuning);
    return d;
}

void DeviceScene::upload_shading(const cl::Context& context, const Scene& scene, std::uint32_t first_emitter,
                                 const EnvironmentMap& environment, const DeviceTuning& tuning)
{
    const DeviceTextures device_textures = make_textures(scene);
    const std::vector<dev::GcEmitter> emitter_list = make_emitters(scene, first_emitter);
    const std::vector<dev::GcPointLight> lights = make_point_lights(scene);
    auto attrib_array = std::make_shared<const BigArray<dev::GcTriangleAttribs>>(make_triangle_attribs(scene));
    attribs = cl::Buffer<dev::GcTriangleAttribs>::over_host(context, *attrib_array, "triangle attributes");
    if (context.device().is_cpu) host_attribs = std::move(attrib_array);
    const std::vector<dev::GcMaterial> material_list = make_materials(scene);
    materials = cl::read_only_buffer(context, material_list, "materials");
    textures = cl::read_only_buffer(context, device_textures.textures, "textures");
    texels = cl::read_only_buffer(context, device_textures.texels, "texels");
    emitters = cl::read_only_buffer(context, emitter_list, "emitters");
    point_lights = cl::read_only_buffer(context, lights, "point lights");
    env_pixels = cl::read_only_buffer(context, environment.pixels, "environment map");
    env_marginal = cl::read_only_buffer(context, environment.marginal_cdf, "environment marginal cdf");
    env_conditional = cl::read_only_buffer(context, environment.conditional_cdf, "environment conditional cdf");
    triangle_count = static_cast<std::uint32_t>(scene.triangle_count());
    emitter_count = static_cast<std::uint32_t>(emitter_list.size());
    point_light_count = static_cast<std::uint32_t>(lights.size());
    texture_count = static_cast<std::uint32_t>(device_textures.textures.size());
    env_width = environment.width;
    env_height = environment.height;
    env_source = environment.source;
    summary = summarize(scene, emitter_list, device_textures.textures.size());
    feature_set = tuning.kernel_features;
    features = kernel_features(material_list, lights.size(), environment.width > 0, tuning.kernel_features);
}

void DeviceScene::check_update(const Scene& scene, const char* what) const
{
    // Its emitters are per instance (with_world_emitters), which a scene of meshes cannot say.
    if (instanced())
        throw UsageError(std::string("a ") + what + " update of an instanced scene is not supported: load it flattened");
    if (scene.triangle_count() != triangle_count || scene.materials.size() != materials.count())
        throw UsageError(std::string("a ") + what + " update needs the uploaded scene: it has " +
                         std::to_string(triangle_count) + " triangles and " + std::to_string(materials.count()) +
                         " materials, the update " + std::to_string(scene.triangle_count()) + " and " +
                         std::to_string(scene.materials.size()));
}

void DeviceScene::update_materials(const cl::Context& context, const Scene& scene)
{
    check_update(scene, "material");
    std::size_t scene_texels = 0;
    for (const Texture& t : scene.textures) scene_texels += t.device_words();
    if (scene_texels != texels.count())
        throw UsageError("a material update cannot change the textures: the device holds " +
                         std::to_string(texels.count()) + " texels, the update's scene " + std::to_string(scene_texels));
    apply_material_update(context, scene);
}

void DeviceScene::update_textures(const cl::Context& context, const Scene& scene)
{
    check_update(scene, "texture");
    texels = cl::read_only_buffer(context, make_textures(scene).texels, "texels");
    apply_material_update(context, scene);
}

void DeviceScene::apply_material_update(const cl::Context& context, const Scene& scene)
{
    const std::vector<dev::GcMaterial> new_materials = make_materials(scene);
    materials.write(std::span<const dev::GcMaterial>(new_materials));
    // The materials index texture views (texture_views): a changed uv transform may add or
    // drop a view. The views are small and share the texels already on the device.
    const std::vector<dev::GcTexture> new_views = texture_views(scene).views;
    textures = cl::read_only_buffer(context, new_views, "textures");
    texture_count = static_cast<std::uint32_t>(new_views.size());
    const std::vector<dev::GcEmitter> new_emitters = make_emitters(scene);
    emitters = cl::read_only_buffer(context, new_emitters, "emitters");
    emitter_count = static_cast<std::uint32_t>(new_emitters.size());
    summary = summarize(scene, new_emitters, new_views.size());
    features = kernel_features(new_materials, point_light_count, env_width > 0, feature_set);
    ++revision;
}

}  // namespace gc
