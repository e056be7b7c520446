// GC_MAT_PBR materials and directions for the BSDF tests of the KHR_materials layers: one
// place that knows every texture slot a test material must leave empty.
#pragma once

#include "gc_bsdf.h"
#include "tests/bsdf/chi2.h"

namespace gc::dev::test_pbr {

inline float3 grey(float v) { return make_float3(v, v, v); }
inline float3 dir_deg(float theta_deg, float phi = 0.7f) { return test::spherical(theta_deg * test::kPi / 180.0, phi); }

// No texture, no layer flag; the specular extension's defaults (factor 1, colour white).
inline GcMaterial pbr(float3 base, float metallic, float roughness, float transmission = 0.0f, float ior = 1.5f)
{
    GcMaterial m{};
    m.type = GC_MAT_PBR;
    m.albedo = make_float4(base.x, base.y, base.z, 1.0f);
    m.emission = make_float4(0.0f, 0.0f, 0.0f, ior);
    m.pbr = make_float4(metallic, roughness, 0.5f, transmission);
    m.specular = make_float4(1.0f, 1.0f, 1.0f, 1.0f);
    m.coat = make_float4(0.0f, 0.0f, 0.0f, 1.0f);
    m.albedo_texture = m.metallic_roughness_texture = m.normal_texture = m.emission_texture = GC_INVALID;
    m.coat_texture = m.coat_roughness_texture = m.specular_texture = m.specular_color_texture = GC_INVALID;
    m.sheen_color_texture = m.sheen_roughness_texture = m.transmission_texture = m.coat_normal_texture = GC_INVALID;
    m.coat_normal_scale = 1.0f;
    return m;
}

// `m` under a KHR_materials_clearcoat layer.
inline GcMaterial coated(GcMaterial m, float factor, float roughness)
{
    m.flags |= GC_MATF_CLEARCOAT;
    m.coat.x = factor;
    m.coat.y = roughness;
    return m;
}

inline GcMaterial sheened(GcMaterial m, float3 colour, float roughness)
{
    m.flags |= GC_MATF_SHEEN;
    m.sheen = make_float4(colour.x, colour.y, colour.z, roughness);
    return m;
}

}  // namespace gc::dev::test_pbr
