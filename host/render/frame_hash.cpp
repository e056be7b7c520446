#include "host/render/frame_hash.h"

#include <fstream>
#include <iterator>
#include <type_traits>

#include "host/cl/binary_cache.h"
#include "host/util/error.h"

namespace gc {
namespace {

template <class T>
void add_value(cl::Fnv1a& h, const T& value)
{
    static_assert(std::is_trivially_copyable_v<T>);
    h.add(&value, sizeof value);
}

template <class T>
void add_vector(cl::Fnv1a& h, const std::vector<T>& values)
{
    static_assert(std::is_trivially_copyable_v<T>);
    add_value(h, std::uint64_t(values.size()));
    if (!values.empty()) h.add(values.data(), values.size() * sizeof(T));
}

void add_vec3(cl::Fnv1a& h, const glm::vec3& v)
{
    add_value(h, v.x);
    add_value(h, v.y);
    add_value(h, v.z);
}

}  // namespace

std::uint64_t scene_content_hash(const Scene& scene)
{
    cl::Fnv1a h;
    h.add_field("geocold scene v2");
    add_value(h, std::uint64_t(scene.positions.size()));
    for (const Point3& p : scene.positions) add_vec3(h, glm::vec3(p.x, p.y, p.z));
    add_value(h, std::uint64_t(scene.normals.size()));
    for (const Normal3& n : scene.normals) add_vec3(h, glm::vec3(n.x, n.y, n.z));
    add_vector(h, scene.uvs);
    add_vector(h, scene.tangents);
    add_vector(h, scene.material_ids);
    add_vector(h, scene.has_vertex_normals);
    add_value(h, std::uint64_t(scene.materials.size()));
    for (const Material& m : scene.materials) {
        h.add_field(m.name);
        add_value(h, m.type);
        add_vec3(h, m.albedo);
        add_vec3(h, m.specular);
        add_value(h, m.phong_exponent);
        add_vec3(h, m.emission);
        add_value(h, m.ior);
        add_value(h, m.opacity);
        add_value(h, m.metallic);
        add_value(h, m.roughness);
        add_value(h, m.transmission);
        add_value(h, m.alpha_mode);
        add_value(h, m.alpha_cutoff);
        add_value(h, std::uint8_t(m.double_sided));
        add_value(h, m.albedo_texture);
        add_value(h, m.metallic_roughness_texture);
        add_value(h, m.normal_texture);
        add_value(h, m.normal_scale);
        add_value(h, m.emission_texture);
        for (const UvTransform* t : {&m.albedo_uv, &m.metallic_roughness_uv, &m.normal_uv, &m.emission_uv}) {
            add_value(h, t->offset.x);
            add_value(h, t->offset.y);
            add_value(h, t->rotation);
            add_value(h, t->scale.x);
            add_value(h, t->scale.y);
        }
        // Only materials with a KHR_materials_* layer hash one, so other scenes keep their hash.
        const PbrLayers& l = m.layers;
        if (l != PbrLayers{}) {
            h.add_field("layers");
            for (float v : {l.clearcoat, l.clearcoat_roughness, l.specular, l.specular_color.x, l.specular_color.y,
                            l.specular_color.z, l.sheen_color.x, l.sheen_color.y, l.sheen_color.z, l.sheen_roughness,
                            l.attenuation_color.x, l.attenuation_color.y, l.attenuation_color.z, l.attenuation_distance})
                add_value(h, v);
            for (bool on : {l.clearcoat_on, l.specular_on, l.sheen_on, l.volume_on}) add_value(h, std::uint8_t(on));
            add_value(h, l.clearcoat_normal_scale);
            for (const TextureRef* r : {&l.clearcoat_texture, &l.clearcoat_roughness_texture, &l.specular_texture,
                                        &l.specular_color_texture, &l.sheen_color_texture, &l.sheen_roughness_texture,
                                        &l.clearcoat_normal_texture, &l.transmission_texture}) {
                add_value(h, r->texture);
                for (float v : {r->uv.offset.x, r->uv.offset.y, r->uv.rotation, r->uv.scale.x, r->uv.scale.y})
                    add_value(h, v);
            }
        }
    }
    add_value(h, std::uint64_t(scene.textures.size()));
    for (const Texture& t : scene.textures) {
        add_value(h, t.width);
        add_value(h, t.height);
        add_vector(h, t.texels);
        add_vector(h, t.linear);
        add_value(h, std::uint8_t(t.srgb));
        add_value(h, t.wrap_s);
        add_value(h, t.wrap_t);
        add_value(h, std::uint8_t(t.nearest));
    }
    add_value(h, std::uint64_t(scene.point_lights.size()));
    for (const PointLight& l : scene.point_lights) {
        add_vec3(h, glm::vec3(l.position.x, l.position.y, l.position.z));
        add_vec3(h, l.intensity);
    }
    return h.value();
}

std::uint64_t scene_content_hash(const InstancedScene& scene)
{
    cl::Fnv1a h;
    h.add_field("geocold instanced scene v1");
    add_value(h, scene_content_hash(scene.meshes));
    add_value(h, std::uint64_t(scene.mesh_ranges.size()));
    for (const MeshRange& r : scene.mesh_ranges) {
        add_value(h, r.first_triangle);
        add_value(h, r.triangle_count);
    }
    add_value(h, std::uint64_t(scene.instances.size()));
    for (const Instance& inst : scene.instances) {
        add_value(h, inst.mesh);
        for (int c = 0; c < 4; ++c) add_vec3(h, glm::vec3(inst.object_to_world[c]));
    }
    return h.value();
}

std::uint64_t render_options_hash(const RenderSettings& settings, const Camera& camera, std::uint32_t chunk_samples)
{
    cl::Fnv1a h;
    h.add_field("geocold options v2");
    add_value(h, settings.width);
    add_value(h, settings.height);
    add_value(h, settings.max_depth);
    add_value(h, settings.rr_depth);
    add_value(h, settings.integrator);
    add_value(h, settings.aov);
    add_vec3(h, settings.env_radiance);
    add_value(h, chunk_samples);
    // Only when set, so that the hashes of uniform frames stay those of earlier versions.
    if (settings.noise_threshold > 0.0) {
        h.add_field("noise threshold");
        add_value(h, settings.noise_threshold);
    }
    if (settings.sampler != SamplerKind::Independent) h.add_field(sampler_name(settings.sampler));
    add_vec3(h, glm::vec3(camera.look_from.x, camera.look_from.y, camera.look_from.z));
    add_vec3(h, glm::vec3(camera.look_at.x, camera.look_at.y, camera.look_at.z));
    add_vec3(h, glm::vec3(camera.up.x, camera.up.y, camera.up.z));
    add_value(h, camera.vfov_degrees);
    add_value(h, camera.aperture_radius);
    add_value(h, camera.focus_distance);
    if (!settings.env_map_path.empty()) {
        std::ifstream in(settings.env_map_path, std::ios::binary);
        if (!in) throw InputError("cannot read environment map '" + settings.env_map_path + "' to hash it");
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        h.add_field(bytes);
    } else {
        h.add_field("");
    }
    return h.value();
}

std::string hash_text(std::uint64_t hash) { return cl::to_hex(hash); }

}  // namespace gc
