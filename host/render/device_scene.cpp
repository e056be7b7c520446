#include "host/render/device_scene.h"

#include <span>
#include <string>
#include <vector>

#include "host/render/scene_convert.h"
#include "host/util/error.h"

namespace gc {
std::uint64_t DeviceScene::bytes() const
{
    return bvh.bytes() + attribs.bytes() + materials.bytes() + textures.bytes() +
           texels.bytes() + emitters.bytes() + point_lights.bytes() + env_pixels.bytes() + env_marginal.bytes() +
           env_conditional.bytes();
}

DeviceScene DeviceScene::upload(const cl::Context& context, const Scene& scene, const FlatBvh& bvh,
                                const EnvironmentMap& environment, const DeviceTuning& tuning)
{
    DeviceScene d;
    const DeviceTextures textures = make_textures(scene);
    const std::vector<dev::GcEmitter> emitters = make_emitters(scene);
    const std::vector<dev::GcPointLight> lights = make_point_lights(scene);
    d.bvh = DeviceBvh::upload(context, bvh, bvh_layout_for(context.device(), tuning.bvh_layout));
    auto attribs = std::make_shared<const BigArray<dev::GcTriangleAttribs>>(make_triangle_attribs(scene));
    d.attribs = cl::Buffer<dev::GcTriangleAttribs>::over_host(context, *attribs, "triangle attributes");
    if (context.device().is_cpu) d.host_attribs = std::move(attribs);
    const std::vector<dev::GcMaterial> materials = make_materials(scene);
    d.materials = cl::read_only_buffer(context, materials, "materials");
    d.textures = cl::read_only_buffer(context, textures.textures, "textures");
    d.texels = cl::read_only_buffer(context, textures.texels, "texels");
    d.emitters = cl::read_only_buffer(context, emitters, "emitters");
    d.point_lights = cl::read_only_buffer(context, lights, "point lights");
    d.env_pixels = cl::read_only_buffer(context, environment.pixels, "environment map");
    d.env_marginal = cl::read_only_buffer(context, environment.marginal_cdf, "environment marginal cdf");
    d.env_conditional = cl::read_only_buffer(context, environment.conditional_cdf, "environment conditional cdf");
    d.triangle_count = static_cast<std::uint32_t>(scene.triangle_count());
    d.emitter_count = static_cast<std::uint32_t>(emitters.size());
    d.point_light_count = static_cast<std::uint32_t>(lights.size());
    d.texture_count = static_cast<std::uint32_t>(textures.textures.size());
    d.env_width = environment.width;
    d.env_height = environment.height;
    d.env_source = environment.source;
    d.summary = summarize(scene, emitters, textures.textures.size());
    d.feature_set = tuning.kernel_features;
    d.features = kernel_features(materials, lights.size(), environment.width > 0, tuning.kernel_features);
    return d;
}

void DeviceScene::check_update(const Scene& scene, const char* what) const
{
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
