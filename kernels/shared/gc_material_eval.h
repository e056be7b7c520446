/*
 * gc_material_eval.h — a material evaluated at a surface point: glTF base colour and alpha,
 * metallicRoughness, normal, emissive and KHR_materials_* layer textures looked up at the hit's uv and folded into
 * plain numbers, so that gc_bsdf.h (which knows no textures) sees a GcMaterial and an albedo;
 * and glTF alpha BLEND as a stochastic pass-through decision (gc_alpha_transparent, applied
 * in gc_shade_vertex). alpha MASK never reaches this code: the traversal drops cut-away hits
 * (gc_alpha.h), so a MASK hit that is shaded is solid.
 *
 * Used by the path vertex (gc_path_vertex.h), light sampling (gc_light_sample.h), the aov
 * and whitted integrators and the Vulkan raster pass, so every integrator reads a texture
 * the same way. Scene buffers come in as the scene-buffer group shade (gc_scene_buffers.h):
 * GC_SHADE_PARAMS / GC_SHADE_ARGS, read through GC_ATTRIB(i), GC_MATERIAL(i), GC_TEXTURE(i)
 * and the texel accessor; GC_SHADE_UNUSED() marks them all used in helpers that read only
 * some. The Vulkan reference reads its SSBOs instead (kernels/vk/scene_bindings.glsl).
 */
#ifndef GC_MATERIAL_EVAL_H
#define GC_MATERIAL_EVAL_H

#include "gc_frame.h"
#include "gc_scene_buffers.h"
#include "gc_tangent.h"
#include "gc_texture.h"
#include "gc_types.h"
#include "gc_vecmath.h"

GC_NAMESPACE_BEGIN

/* Diffuse reflectance at uv: the material's albedo times its texture, if any. */
GC_FUNC float3 gc_shade_albedo(GC_SHADE_PARAMS, GcMaterial m, float2 uv)
{
    GC_SHADE_UNUSED();
    float3 albedo = GC_XYZ(m.albedo);
    if (GC_USE_TEXTURES != 0 && m.albedo_texture != GC_INVALID)
        albedo *= GC_XYZ(gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.albedo_texture), uv.x, uv.y));
    return albedo;
}

/* glTF base colour and alpha at uv: baseColorFactor times the (sRGB-decoded) texture. */
GC_FUNC float4 gc_shade_base_color(GC_SHADE_PARAMS, GcMaterial m, float2 uv)
{
    GC_SHADE_UNUSED();
    float4 c = m.albedo;
    if (GC_USE_TEXTURES != 0 && m.albedo_texture != GC_INVALID)
        c *= gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.albedo_texture), uv.x, uv.y);
    return c;
}

/* Emitted radiance at uv: emissiveFactor (times KHR_materials_emissive_strength) times the
 * sRGB emissive texture. Light selection and MIS densities use the untextured factor (it is
 * what the host's emitter power sums), so only the radiance is textured: still unbiased. */
GC_FUNC float3 gc_shade_emission(GC_SHADE_PARAMS, GcMaterial m, float2 uv)
{
    GC_SHADE_UNUSED();
    float3 e = GC_XYZ(m.emission);
    if (GC_USE_TEXTURES != 0 && m.emission_texture != GC_INVALID)
        e *= GC_XYZ(gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.emission_texture), uv.x, uv.y));
    return e;
}

/* The material with its metallicRoughness texture folded into the factors (glTF: B = metal,
 * G = roughness, linear), and its transmissionTexture (R) into the transmission factor, so
 * gc_bsdf.h sees plain numbers. */
GC_FUNC GcMaterial gc_shade_material(GC_SHADE_PARAMS, GcMaterial m, float2 uv)
{
    GC_SHADE_UNUSED();
    if (GC_USE_TEXTURES != 0 && m.metallic_roughness_texture != GC_INVALID) {
        const float4 mr = gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.metallic_roughness_texture), uv.x, uv.y);
        m.pbr.x *= mr.z;
        m.pbr.y *= mr.y;
    }
    if (GC_USE_TEXTURES != 0 && m.pbr.w > 0.0f && m.transmission_texture != GC_INVALID)
        m.pbr.w *= gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.transmission_texture), uv.x, uv.y).x;
    /* The KHR_materials_* layers' textures (channels as their specifications give them);
     * compiled in only where the scene has the layer (#if: two constants in an && warn). */
#if GC_USE_TEXTURES != 0 && GC_USE_CLEARCOAT != 0
    if ((m.flags & GC_MATF_CLEARCOAT) != 0u) {
        if (m.coat_texture != GC_INVALID)
            m.coat.x *= gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.coat_texture), uv.x, uv.y).x;
        if (m.coat_roughness_texture != GC_INVALID)
            m.coat.y *= gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.coat_roughness_texture), uv.x, uv.y).y;
    }
#endif
#if GC_USE_TEXTURES != 0 && GC_USE_SPECULAR != 0
    if ((m.flags & GC_MATF_SPECULAR) != 0u) {
        if (m.specular_texture != GC_INVALID)
            m.coat.w *= gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.specular_texture), uv.x, uv.y).w;
        if (m.specular_color_texture != GC_INVALID) {
            const float4 c = gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.specular_color_texture), uv.x, uv.y);
            m.specular = make_float4(m.specular.x * c.x, m.specular.y * c.y, m.specular.z * c.z, m.specular.w);
        }
    }
#endif
#if GC_USE_TEXTURES != 0 && GC_USE_SHEEN != 0
    if ((m.flags & GC_MATF_SHEEN) != 0u) {
        if (m.sheen_color_texture != GC_INVALID) {
            const float4 c = gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.sheen_color_texture), uv.x, uv.y);
            m.sheen = make_float4(m.sheen.x * c.x, m.sheen.y * c.y, m.sheen.z * c.z, m.sheen.w);
        }
        if (m.sheen_roughness_texture != GC_INVALID)
            m.sheen.w *= gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.sheen_roughness_texture), uv.x, uv.y).w;
    }
#endif
    return m;
}

/* ns with the tangent-space normal map `texture` applied (xy scaled by `xy_scale`), at
 * barycentrics bary = (u, v) of v1 and v2. The tangent is the file's per-vertex one
 * interpolated, else the host's per-triangle one (gc_triangle_tangent); it is
 * re-orthogonalised against the interpolated normal ns here (Gram-Schmidt),
 * B = w * cross(ns, T). A perturbed normal that would face away from ns's side (a texel at the
 * grazing limit) keeps ns. */
GC_FUNC float3 gc_mapped_normal(GC_SHADE_PARAMS, uint texture, float xy_scale, GcTriangleAttribs a, float2 bary,
                                float3 ns, float2 uv)
{
    GC_SHADE_UNUSED();
    const float4 tangent = gc_triangle_tangent(a, bary.x, bary.y);
    const float3 t_tri = GC_XYZ(tangent);
    const float3 t_raw = t_tri - ns * gc_dot(ns, t_tri);
    const float t_len = gc_length(t_raw);
    if (!(t_len > 1.0e-6f)) return ns;
    const float3 t = t_raw * (1.0f / t_len);
    const float3 b = gc_cross(ns, t) * tangent.w;
    const GcTexture view = GC_TEXTURE(texture);
    const float4 tex = gc_texture_sample(GC_TEXELS_ARG, view, uv.x, uv.y);
    /* glTF's normal texture scale multiplies x and y only (then the result is renormalised); a
     * view's uv transform turns them into the mesh's frame (gc_texture_tangent_xy). */
    const float2 xy = gc_texture_tangent_xy(view, (2.0f * tex.x - 1.0f) * xy_scale, (2.0f * tex.y - 1.0f) * xy_scale);
    const float3 n = t * xy.x + b * xy.y + ns * (2.0f * tex.z - 1.0f);
    const float n_len = gc_length(n);
    if (!(n_len > 1.0e-6f)) return ns;
    const float3 nn = n * (1.0f / n_len);
    return gc_dot(nn, ns) > 0.0f ? nn : ns;
}

/* The shading normal: ns with the material's normal map applied. */
GC_FUNC float3 gc_shade_normal(GC_SHADE_PARAMS, GcMaterial m, GcTriangleAttribs a, float2 bary, float3 ns, float2 uv)
{
    if (GC_USE_NORMAL_MAPS == 0 || m.normal_texture == GC_INVALID) return ns;
    return gc_mapped_normal(GC_SHADE_ARGS, m.normal_texture, m.normal_scale, a, bary, ns, uv);
}

/* m with its coat's own normal (KHR_materials_clearcoat clearcoatNormalTexture: the map
 * applied to the interpolated normal ns, not to the base's mapped normal) in `frame`, the
 * shading frame the BSDF works in, for gc_bsdf.h's coat; m unchanged without that texture. */
GC_FUNC GcMaterial gc_with_coat_normal(GC_SHADE_PARAMS, GcMaterial m, GcTriangleAttribs a, float2 bary, float3 ns,
                                       float2 uv, GcFrame frame)
{
    if (GC_USE_NORMAL_MAPS == 0 || m.coat_normal_texture == GC_INVALID) return m;
    if (GC_USE_CLEARCOAT == 0 || (m.flags & GC_MATF_CLEARCOAT) == 0u) return m;
    const float3 n = gc_frame_to_local(frame, gc_mapped_normal(GC_SHADE_ARGS, m.coat_normal_texture,
                                                               m.coat_normal_scale, a, bary, ns, uv));
    /* A coat normal on the far side of the base's (two maps bent apart past 90 degrees) keeps
     * the base's: gc_bsdf.h mirrors the coat with the directions and needs z > 0. */
    if (!(n.z > 1.0e-4f)) return m;
    m.coat_normal = make_float4(n.x, n.y, n.z, 0.0f);
    m.flags |= GC_MATF_COAT_NORMAL;
    return m;
}

/* Texture coordinates at barycentrics b = (b0, b1, b2) of the triangle's corners. */
GC_FUNC float2 gc_triangle_uv(GcTriangleAttribs a, float3 b)
{
    return make_float2(b.x * a.uv01.x + b.y * a.uv01.z + b.z * a.uv2_u, b.x * a.uv01.y + b.y * a.uv01.w + b.z * a.uv2_v);
}

/* glTF alphaMode BLEND as stochastic transparency: transparent with probability 1 - alpha
 * (u uniform in [0, 1)). MASK is decided in traversal (gc_alpha.h), not here. */
GC_FUNC bool gc_alpha_transparent(GcMaterial m, float alpha, float u)
{
    if (GC_USE_ALPHA_BLEND != 0 && (m.flags & GC_MATF_ALPHA_BLEND) != 0u) return u >= alpha;
    return false;
}

GC_NAMESPACE_END

#endif /* GC_MATERIAL_EVAL_H */
