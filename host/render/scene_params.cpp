#include "host/render/scene_params.h"

#include <algorithm>
#include <charconv>

#include "gc_texture.h"
#include "host/util/error.h"

namespace gc {
namespace {

constexpr std::string_view k_materials = "materials/";

bool has_base_color(const Material& m)
{
    return m.type != MaterialType::Dielectric;
}
// Whether the adjoint's BSDF derivative (gc_bsdf_grad.h) covers the material's lobes: not the
// KHR layers (clearcoat, specular, sheen) or rough transmission and volumes, which came later.
bool bsdf_differentiated(const Material& m)
{
    if (m.type != MaterialType::Pbr) return true;
    const PbrLayers& l = m.layers;
    const bool rough_transmission = m.transmission > 0.0f && m.roughness > 0.0f;
    return !(l.clearcoat_on || l.specular_on || l.sheen_on || l.volume_on || rough_transmission);
}
constexpr std::string_view k_not_in_bsdf_derivative =
    "not differentiated yet: the adjoint's BSDF derivative does not cover this material's "
    "KHR_materials layers (clearcoat, specular, sheen) or rough transmission and volume";
constexpr std::string_view k_env_radiance = "environment/radiance";
constexpr std::string_view k_textures = "textures/";

// Whether a material reads texture `i` in a slot the adjoint differentiates: base colour,
// metallic-roughness (glTF) or emission (of a material that emits).
bool is_differentiated_texture(const Scene& scene, std::size_t i)
{
    const int t = static_cast<int>(i);
    return std::any_of(scene.materials.begin(), scene.materials.end(), [&](const Material& m) {
        return (m.albedo_texture == t && has_base_color(m) && bsdf_differentiated(m)) ||
               (m.metallic_roughness_texture == t && m.type == MaterialType::Pbr && bsdf_differentiated(m)) ||
               (m.emission_texture == t && m.is_emissive());
    });
}

// The name a material goes by in parameter names: its own where unique, else its index.
std::string material_key(const Scene& scene, std::size_t i)
{
    const std::string& name = scene.materials[i].name;
    const bool unique = !name.empty() && name.find('/') == std::string::npos &&
                        std::count_if(scene.materials.begin(), scene.materials.end(),
                                      [&](const Material& m) { return m.name == name; }) == 1;
    return unique ? name : std::to_string(i);
}

std::uint32_t find_material(const Scene& scene, std::string_view key, std::string_view full_name)
{
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (material_key(scene, i) == key) return static_cast<std::uint32_t>(i);
    throw UsageError("unknown parameter '" + std::string(full_name) +
                     "': the scene has no material '" + std::string(key) +
                     "' (list_params names them)");
}

[[noreturn]] void not_differentiable(std::string_view name, const std::string& why)
{
    throw UsageError("'" + std::string(name) + "' is not differentiable: " + why);
}

}  // namespace

std::vector<ParamInfo> list_params(const Scene& scene)
{
    std::vector<ParamInfo> out;
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const Material& m = scene.materials[i];
        const std::string prefix = std::string(k_materials) + material_key(scene, i) + "/";
        if (has_base_color(m) && bsdf_differentiated(m)) out.push_back({prefix + "base_color", {3}});
        if (m.is_emissive()) out.push_back({prefix + "emission", {3}});
        if (m.type == MaterialType::Phong || m.type == MaterialType::Mirror)
            out.push_back({prefix + "specular", {3}});
        if (m.type == MaterialType::Phong) out.push_back({prefix + "phong_exponent", {1}});
        if (m.type == MaterialType::Pbr && bsdf_differentiated(m)) {
            out.push_back({prefix + "metallic", {1}});
            out.push_back({prefix + "roughness", {1}});
        }
    }
    out.push_back({std::string(k_env_radiance), {3}});
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& t = scene.textures[i];
        if (is_differentiated_texture(scene, i))
            out.push_back(
                {std::string(k_textures) + std::to_string(i) + "/texels",
                 {static_cast<std::size_t>(t.height), static_cast<std::size_t>(t.width), 4}});
    }
    return out;
}

ParamRef resolve_param(const Scene& scene, std::string_view name)
{
    if (name == k_env_radiance) return {ParamRef::Kind::EnvRadiance, 0};
    if (name.starts_with("camera") || name.starts_with("geometry") ||
        name.starts_with("positions") || name.starts_with("vertices") ||
        name.starts_with("normals") || name.starts_with("shapes"))
        not_differentiable(
            name,
            "the adjoint does not sample visibility (silhouettes), so gradients with respect "
            "to geometry and the camera would be biased");
    if (name.starts_with(k_textures)) {
        const std::string_view rest = name.substr(k_textures.size());
        std::uint32_t index = 0;
        const auto [end, ec] = std::from_chars(rest.data(), rest.data() + rest.size(), index);
        if (ec != std::errc() ||
            std::string_view(end, rest.data() + rest.size() - end) != "/texels")
            throw UsageError("unknown parameter '" + std::string(name) +
                             "': expected textures/<index>/texels");
        if (index >= scene.textures.size())
            throw UsageError("unknown parameter '" + std::string(name) + "': the scene has " +
                             std::to_string(scene.textures.size()) + " textures");
        if (!is_differentiated_texture(scene, index))
            throw UsageError("'" + std::string(name) +
                             "' is not differentiated yet: only base-colour textures' "
                             "texels are (metallic-roughness, emissive and normal maps are not)");
        ParamRef ref;
        ref.kind = ParamRef::Kind::Texels;
        ref.texture = index;
        return ref;
    }
    if (!name.starts_with(k_materials))
        throw UsageError("unknown parameter '" + std::string(name) +
                         "' (list_params names the scene's parameters)");
    const std::string_view rest = name.substr(k_materials.size());
    const std::size_t slash = rest.rfind('/');
    if (slash == std::string_view::npos)
        throw UsageError("unknown parameter '" + std::string(name) +
                         "': expected materials/<material>/<field>");
    const std::uint32_t material = find_material(scene, rest.substr(0, slash), name);
    const std::string_view field = rest.substr(slash + 1);
    const Material& m = scene.materials[material];
    if ((field == "base_color" || field == "metallic" || field == "roughness") && !bsdf_differentiated(m))
        throw UsageError("'" + std::string(name) + "' is " + std::string(k_not_in_bsdf_derivative));
    if (field == "base_color") {
        if (!has_base_color(m)) not_differentiable(name, "a smooth dielectric has no base colour");
        return {ParamRef::Kind::BaseColor, material};
    }
    if (field == "emission") {
        if (!m.is_emissive())
            not_differentiable(
                name,
                "the material emits nothing, so it is no light for next-event estimation "
                "and its emission's gradient would be biased; give it a small emission first");
        return {ParamRef::Kind::Emission, material};
    }
    if (field == "ior")
        not_differentiable(
            name, "refraction directions are sampled, not differentiated (as Mitsuba's prb)");
    const auto only_for = [&](bool applies, ParamRef::Kind kind, const char* types) -> ParamRef {
        if (!applies)
            throw UsageError("unknown parameter '" + std::string(name) + "': only " + types +
                             " materials have " + std::string(field));
        return {kind, material};
    };
    if (field == "specular")
        return only_for(m.type == MaterialType::Phong || m.type == MaterialType::Mirror,
                        ParamRef::Kind::Specular, "Phong and mirror");
    if (field == "phong_exponent")
        return only_for(m.type == MaterialType::Phong, ParamRef::Kind::PhongExponent, "Phong");
    if (field == "metallic")
        return only_for(m.type == MaterialType::Pbr, ParamRef::Kind::Metallic, "glTF");
    if (field == "roughness")
        return only_for(m.type == MaterialType::Pbr, ParamRef::Kind::Roughness, "glTF");
    throw UsageError("unknown parameter '" + std::string(name) +
                     "': a material's fields are base_color, emission, specular, phong_exponent, "
                     "metallic and roughness");
}

SceneParams::SceneParams(const cl::Context& context, Scene& scene, DeviceScene& device,
                         Renderer& renderer)
    : m_context(context), m_scene(scene), m_device(device), m_renderer(renderer)
{
}

std::vector<float> texels_linear(const Texture& t)
{
    std::vector<float> out;
    if (!t.linear.empty()) {
        for (const glm::vec4& v : t.linear) out.insert(out.end(), {v.x, v.y, v.z, v.w});
        return out;
    }
    out.reserve(t.texels.size() * 4);
    for (std::uint32_t packed : t.texels) {
        const dev::float4 v = dev::gc_unpack_texel(packed, t.srgb);
        out.insert(out.end(), {v.x, v.y, v.z, v.w});
    }
    return out;
}

std::vector<float> SceneParams::get(std::string_view name) const
{
    const ParamRef ref = resolve_param(m_scene, name);
    if (ref.kind == ParamRef::Kind::Texels) return texels_linear(m_scene.textures[ref.texture]);
    if (ref.kind == ParamRef::Kind::EnvRadiance) {
        const glm::vec3 v = m_renderer.settings().env_radiance;
        return {v.x, v.y, v.z};
    }
    const Material& m = m_scene.materials[ref.material];
    switch (ref.kind) {
        case ParamRef::Kind::BaseColor:
            return {m.albedo.x, m.albedo.y, m.albedo.z};
        case ParamRef::Kind::Emission:
            return {m.emission.x, m.emission.y, m.emission.z};
        case ParamRef::Kind::Specular:
            return {m.specular.x, m.specular.y, m.specular.z};
        case ParamRef::Kind::PhongExponent:
            return {m.phong_exponent};
        case ParamRef::Kind::Metallic:
            return {m.metallic};
        case ParamRef::Kind::Roughness:
            return {m.roughness};
        default:
            return {};
    }
}

void SceneParams::set(std::string_view name, std::span<const float> value)
{
    const ParamRef ref = resolve_param(m_scene, name);
    if (ref.kind == ParamRef::Kind::Texels) {
        Texture& t = m_scene.textures[ref.texture];
        const std::size_t count =
            static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
        if (value.size() != 4 * count)
            throw UsageError("'" + std::string(name) + "' has " + std::to_string(4 * count) +
                             " values (" + std::to_string(t.height) + " x " +
                             std::to_string(t.width) + " x 4), the new value " +
                             std::to_string(value.size()));
        // From now on the texture is linear floats: an optimiser's small steps must not be
        // rounded to 8 bits.
        t.linear.resize(count);
        for (std::size_t i = 0; i < count; ++i)
            t.linear[i] =
                glm::vec4(value[4 * i], value[4 * i + 1], value[4 * i + 2], value[4 * i + 3]);
        m_device.update_textures(m_context, m_scene);
        return;
    }
    const std::size_t size = get(name).size();
    if (value.size() != size)
        throw UsageError("'" + std::string(name) + "' has " + std::to_string(size) +
                         " values, the new value " + std::to_string(value.size()));
    if (ref.kind == ParamRef::Kind::EnvRadiance) {
        m_renderer.set_env_radiance(glm::vec3(value[0], value[1], value[2]));
        return;
    }
    Material& m = m_scene.materials[ref.material];
    switch (ref.kind) {
        case ParamRef::Kind::BaseColor:
            m.albedo = glm::vec3(value[0], value[1], value[2]);
            break;
        case ParamRef::Kind::Emission:
            m.emission = glm::vec3(value[0], value[1], value[2]);
            break;
        case ParamRef::Kind::Specular:
            m.specular = glm::vec3(value[0], value[1], value[2]);
            break;
        case ParamRef::Kind::PhongExponent:
            m.phong_exponent = value[0];
            break;
        case ParamRef::Kind::Metallic:
            m.metallic = value[0];
            break;
        case ParamRef::Kind::Roughness:
            m.roughness = value[0];
            break;
        default:
            break;
    }
    m_device.update_materials(m_context, m_scene);
}

}  // namespace gc
