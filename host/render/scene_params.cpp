#include "host/render/scene_params.h"

#include <algorithm>
#include <charconv>

#include "host/util/error.h"

namespace gc {
namespace {

constexpr std::string_view k_materials = "materials/";
constexpr std::string_view k_env_radiance = "environment/radiance";

bool has_base_color(const Material& m) { return m.type != MaterialType::Dielectric; }

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
    throw UsageError("unknown parameter '" + std::string(full_name) + "': the scene has no material '" +
                     std::string(key) + "' (list_params names them)");
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
        if (has_base_color(m)) out.push_back({prefix + "base_color", {3}});
        if (m.is_emissive()) out.push_back({prefix + "emission", {3}});
    }
    out.push_back({std::string(k_env_radiance), {3}});
    return out;
}

ParamRef resolve_param(const Scene& scene, std::string_view name)
{
    if (name == k_env_radiance) return {ParamRef::Kind::EnvRadiance, 0};
    if (name.starts_with("camera") || name.starts_with("geometry") || name.starts_with("positions") ||
        name.starts_with("vertices") || name.starts_with("normals") || name.starts_with("shapes"))
        not_differentiable(name, "the adjoint does not sample visibility (silhouettes), so gradients with respect "
                                 "to geometry and the camera would be biased");
    if (!name.starts_with(k_materials))
        throw UsageError("unknown parameter '" + std::string(name) + "' (list_params names the scene's parameters)");
    const std::string_view rest = name.substr(k_materials.size());
    const std::size_t slash = rest.rfind('/');
    if (slash == std::string_view::npos)
        throw UsageError("unknown parameter '" + std::string(name) + "': expected materials/<material>/<field>");
    const std::uint32_t material = find_material(scene, rest.substr(0, slash), name);
    const std::string_view field = rest.substr(slash + 1);
    const Material& m = scene.materials[material];
    if (field == "base_color") {
        if (!has_base_color(m)) not_differentiable(name, "a smooth dielectric has no base colour");
        return {ParamRef::Kind::BaseColor, material};
    }
    if (field == "emission") {
        if (!m.is_emissive())
            not_differentiable(name, "the material emits nothing, so it is no light for next-event estimation "
                                     "and its emission's gradient would be biased; give it a small emission first");
        return {ParamRef::Kind::Emission, material};
    }
    if (field == "ior")
        not_differentiable(name, "refraction directions are sampled, not differentiated (as Mitsuba's prb)");
    if (field == "specular" || field == "phong_exponent" || field == "metallic" || field == "roughness")
        throw UsageError("'" + std::string(name) + "' is not differentiated yet: the adjoint covers base_color, "
                         "emission and environment/radiance");
    throw UsageError("unknown parameter '" + std::string(name) + "': a material's fields are base_color and emission");
}

SceneParams::SceneParams(const cl::Context& context, Scene& scene, DeviceScene& device, Renderer& renderer)
    : m_context(context), m_scene(scene), m_device(device), m_renderer(renderer)
{
}

std::vector<float> SceneParams::get(std::string_view name) const
{
    const ParamRef ref = resolve_param(m_scene, name);
    glm::vec3 v(0.0f);
    switch (ref.kind) {
    case ParamRef::Kind::BaseColor: v = m_scene.materials[ref.material].albedo; break;
    case ParamRef::Kind::Emission: v = m_scene.materials[ref.material].emission; break;
    case ParamRef::Kind::EnvRadiance: v = m_renderer.settings().env_radiance; break;
    }
    return {v.x, v.y, v.z};
}

void SceneParams::set(std::string_view name, std::span<const float> value)
{
    const ParamRef ref = resolve_param(m_scene, name);
    if (value.size() != 3)
        throw UsageError("'" + std::string(name) + "' has 3 values, the new value " + std::to_string(value.size()));
    const glm::vec3 v(value[0], value[1], value[2]);
    switch (ref.kind) {
    case ParamRef::Kind::BaseColor:
        m_scene.materials[ref.material].albedo = v;
        m_device.update_materials(m_context, m_scene);
        break;
    case ParamRef::Kind::Emission:
        m_scene.materials[ref.material].emission = v;
        m_device.update_materials(m_context, m_scene);
        break;
    case ParamRef::Kind::EnvRadiance: m_renderer.set_env_radiance(v); break;
    }
}

}  // namespace gc
