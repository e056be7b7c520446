#include "host/render/kernel_features.h"

#include <cstdlib>

#include "host/util/error.h"

namespace gc {
namespace {

bool specialise_for_scene()
{
    const char* env = std::getenv("GEOCOLD_KERNEL_FEATURES");
    if (!env || !*env) return true;
    const std::string value(env);
    if (value != "all" && value != "scene")
        throw UsageError("GEOCOLD_KERNEL_FEATURES must be 'scene' or 'all', not '" + value + "'");
    return value == "scene";
}

bool has_texture(const dev::GcMaterial& m)
{
    return m.albedo_texture != GC_INVALID || m.metallic_roughness_texture != GC_INVALID ||
           m.normal_texture != GC_INVALID || m.emission_texture != GC_INVALID;
}

void add_define(std::string& options, const char* name, bool on)
{
    if (on) return;
    if (!options.empty()) options += ' ';
    options += "-D ";
    options += name;
    options += "=0";
}

}  // namespace

KernelFeatures kernel_features(std::span<const dev::GcMaterial> materials, std::size_t point_lights, bool env_map)
{
    if (!specialise_for_scene()) return {};
    KernelFeatures f;
    f.textures = f.normal_maps = f.alpha_mask = f.alpha_blend = false;
    f.material_types = 0u;
    for (const dev::GcMaterial& m : materials) {
        f.textures = f.textures || has_texture(m);
        f.normal_maps = f.normal_maps || m.normal_texture != GC_INVALID;
        // A superset of the triangles flatten() flags GC_TRI_ALPHA_TESTED: an untextured MASK
        // material above its cutoff is solid and not flagged, but keeping the test is harmless.
        f.alpha_mask = f.alpha_mask || (m.flags & GC_MATF_ALPHA_MASK) != 0u;
        f.alpha_blend = f.alpha_blend || (m.flags & GC_MATF_ALPHA_BLEND) != 0u;
        // A type beyond the mask's bits keeps every type (the kernels treat unknown types as Lambert).
        f.material_types |= m.type < 32u ? (1u << m.type) : 0xffffffffu;
    }
    f.point_lights = point_lights > 0;
    f.env_map = env_map;
    return f;
}

std::string program_options(const KernelFeatures& features)
{
    std::string options;
    add_define(options, "GC_USE_TEXTURES", features.textures);
    add_define(options, "GC_USE_NORMAL_MAPS", features.normal_maps);
    add_define(options, "GC_USE_ALPHA_MASK", features.alpha_mask);
    add_define(options, "GC_USE_ALPHA_BLEND", features.alpha_blend);
    add_define(options, "GC_USE_POINT_LIGHTS", features.point_lights);
    add_define(options, "GC_USE_ENV_MAP", features.env_map);
    if (features.material_types != 0xffffffffu) {
        if (!options.empty()) options += ' ';
        options += "-D GC_USE_MATERIALS=" + std::to_string(features.material_types) + "u";
    }
    return options;
}

}  // namespace gc
