#include "host/app/lighting_check.h"

#include <algorithm>

namespace gc {
namespace {

bool any_emissive_triangle(const Scene& scene)
{
    return std::any_of(scene.material_ids.begin(), scene.material_ids.end(),
                       [&](std::uint32_t m) { return scene.materials[m].is_emissive(); });
}

bool environment_lights(const RenderSettings& settings)
{
    const glm::vec3 e = settings.env_radiance;
    // A constant environment is env_radiance itself; a map is scaled by it (1 unless
    // --env-scale says otherwise, so a map scaled by zero lights nothing either).
    return e.x > 0.0f || e.y > 0.0f || e.z > 0.0f;
}

}  // namespace

bool has_light(const Scene& scene, const RenderSettings& settings)
{
    return any_emissive_triangle(scene) || !scene.point_lights.empty() || environment_lights(settings);
}

std::optional<std::string> unlit_scene_warning(const Scene& scene, const RenderSettings& settings)
{
    if (settings.integrator == IntegratorKind::Aov || has_light(scene, settings)) return std::nullopt;
    return scene.source_path +
           ": nothing lights this scene (no emissive material, no point light) and the environment is black, so the "
           "image will be black; light it with --env R,G,B or --env FILE";
}

}  // namespace gc
