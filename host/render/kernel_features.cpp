#include "host/render/kernel_features.h"

#include <utility>

namespace gc {
namespace {

// A layer's textures count only when its flag is set: the kernels never read them otherwise.
bool has_texture(const dev::GcMaterial& m)
{
    const bool coat = (m.flags & GC_MATF_CLEARCOAT) != 0u &&
                      (m.coat_texture != GC_INVALID || m.coat_roughness_texture != GC_INVALID ||
                       m.coat_normal_texture != GC_INVALID);
    const bool specular = (m.flags & GC_MATF_SPECULAR) != 0u &&
                          (m.specular_texture != GC_INVALID || m.specular_color_texture != GC_INVALID);
    const bool sheen = (m.flags & GC_MATF_SHEEN) != 0u &&
                       (m.sheen_color_texture != GC_INVALID || m.sheen_roughness_texture != GC_INVALID);
    const bool transmission = m.pbr.w > 0.0f && m.transmission_texture != GC_INVALID;
    return m.albedo_texture != GC_INVALID || m.metallic_roughness_texture != GC_INVALID ||
           m.normal_texture != GC_INVALID || m.emission_texture != GC_INVALID || coat || specular || sheen ||
           transmission;
}

// Appends "-D name=value", space-separated from what is there.
void add_define(std::string& options, const char* name, const std::string& value)
{
    if (!options.empty()) options += ' ';
    options += std::string("-D ") + name + "=" + value;
}

}  // namespace

KernelFeatures kernel_features(std::span<const dev::GcMaterial> materials, std::size_t point_lights, bool env_map,
                               KernelFeatureSet set)
{
    if (set == KernelFeatureSet::All) return {};
    KernelFeatures f;
    f.textures = f.normal_maps = f.alpha_mask = f.alpha_blend = false;
    f.clearcoat = f.specular = f.sheen = f.rough_transmission = f.volume = false;
    f.material_types = 0u;
    for (const dev::GcMaterial& m : materials) {
        f.textures = f.textures || has_texture(m);
        f.normal_maps = f.normal_maps || m.normal_texture != GC_INVALID ||
                        ((m.flags & GC_MATF_CLEARCOAT) != 0u && m.coat_normal_texture != GC_INVALID);
        // A superset of the triangles flatten() flags GC_TRI_ALPHA_TESTED: an untextured MASK
        // material above its cutoff is solid and not flagged, but keeping the test is harmless.
        f.alpha_mask = f.alpha_mask || (m.flags & GC_MATF_ALPHA_MASK) != 0u;
        f.alpha_blend = f.alpha_blend || (m.flags & GC_MATF_ALPHA_BLEND) != 0u;
        f.clearcoat = f.clearcoat || (m.flags & GC_MATF_CLEARCOAT) != 0u;
        f.specular = f.specular || (m.flags & GC_MATF_SPECULAR) != 0u;
        f.sheen = f.sheen || (m.flags & GC_MATF_SHEEN) != 0u;
        f.rough_transmission = f.rough_transmission || (m.flags & GC_MATF_ROUGH_TRANSMISSION) != 0u;
        f.volume = f.volume || (m.flags & GC_MATF_VOLUME) != 0u;
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
    const std::pair<const char*, bool> switches[] = {
        {"GC_USE_TEXTURES", features.textures},         {"GC_USE_NORMAL_MAPS", features.normal_maps},
        {"GC_USE_ALPHA_MASK", features.alpha_mask},     {"GC_USE_ALPHA_BLEND", features.alpha_blend},
        {"GC_USE_POINT_LIGHTS", features.point_lights}, {"GC_USE_ENV_MAP", features.env_map},
        {"GC_USE_CLEARCOAT", features.clearcoat},       {"GC_USE_SPECULAR", features.specular},
        {"GC_USE_SHEEN", features.sheen},               {"GC_USE_ROUGH_TRANSMISSION", features.rough_transmission},
        {"GC_USE_VOLUME", features.volume},
    };
    for (const auto& [name, on] : switches)
        if (!on) add_define(options, name, "0");
    if (features.material_types != 0xffffffffu)
        add_define(options, "GC_USE_MATERIALS", std::to_string(features.material_types) + "u");
    return options;
}

}  // namespace gc
