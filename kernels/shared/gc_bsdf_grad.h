/*
 * gc_bsdf_grad.h — derivatives of gc_bsdf.h's values with respect to the albedo (the diffuse
 * reflectance / glTF base colour after texturing), for the adjoint of the path integrator
 * (gc_path_adjoint.h).
 *
 * Every type's value is affine in the albedo, channel by channel: Lambert, Phong's diffuse term
 * and the mirror's diffuse part are albedo / pi; the glTF model's diffuse lobe is
 * base (1 - metallic)(1 - transmission)(1 - F_d) / pi and its metal Fresnel term
 * base + (1 - base) S, with S Schlick's weight; the thin-walled transmission lobe is
 * base (1 - metallic) transmission (1 - F_d). So the derivative is exact and does not depend on
 * the albedo itself. Sampling densities are not differentiated (path replay treats them as
 * fixed, which keeps the estimate unbiased).
 *
 * Same conventions as gc_bsdf.h (local frame, cosine excluded, two-sided flip).
 */
#ifndef GC_BSDF_GRAD_H
#define GC_BSDF_GRAD_H

#include "gc_bsdf.h"

GC_NAMESPACE_BEGIN

/* d gc_bsdf_eval(m, albedo, wo, wi) / d albedo, per channel (the same in each). */
GC_FUNC float gc_bsdf_eval_dalbedo(GcMaterial m, float3 wo, float3 wi)
{
    if (gc_material_is(m, GC_MAT_DIELECTRIC)) return 0.0f;
    const float side = gc_bsdf_side(wo);
    wo = gc_bsdf_flip(wo, side);
    wi = gc_bsdf_flip(wi, side);
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
    if (gc_material_is(m, GC_MAT_PBR)) {
        const float metallic = clamp(m.pbr.x, 0.0f, 1.0f);
        const float trans = clamp(m.pbr.w, 0.0f, 1.0f);
        const float alpha = gc_pbr_alpha(m);
        const float f0 = gc_pbr_f0(m);
        const float3 wm = gc_normalize(wo + wi);
        const float sw = gc_schlick_weight(gc_dot(wo, wm));
        const float fd = f0 + (1.0f - f0) * sw;
        const float spec = gc_ggx_d(wm, alpha) * gc_ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z);
        return (1.0f - metallic) * (1.0f - trans) * (1.0f - fd) * GC_INV_PI + metallic * (1.0f - sw) * spec;
    }
    return GC_INV_PI; /* Lambert, Phong's and the mirror's diffuse term */
}

/* d bs.f / d albedo for a sample gc_bsdf_sample drew from m at wo: the value's derivative for a
 * non-delta sample, the delta coefficient's for a delta one (only the glTF transmission lobe's
 * depends on the base colour; the mirror's and the dielectric's do not). */
GC_FUNC float gc_bsdf_sample_f_dalbedo(GcMaterial m, float3 wo, GcBsdfSample bs)
{
    if ((bs.flags & GC_BSDF_SPECULAR) == 0u) return gc_bsdf_eval_dalbedo(m, wo, bs.wi);
    if (!gc_material_is(m, GC_MAT_PBR) || (bs.flags & GC_BSDF_TRANSMISSION) == 0u) return 0.0f;
    const float cos_o = fabs(wo.z);
    if (!(cos_o > 0.0f)) return 0.0f;
    const float metallic = clamp(m.pbr.x, 0.0f, 1.0f);
    const float trans = clamp(m.pbr.w, 0.0f, 1.0f);
    const float f0 = gc_pbr_f0(m);
    const float fd = f0 + (1.0f - f0) * gc_schlick_weight(cos_o);
    return (1.0f - metallic) * trans * (1.0f - fd) * (1.0f / cos_o);
}

/* ------------------------------------------------------------------ specular reflectance */

/* d gc_bsdf_eval / d m.specular (Phong's Ks), per channel: Phong's value is affine in Ks, so
 * the value at Ks = 1 minus the value at Ks = 0 is the derivative. The mirror's non-delta
 * part does not depend on it. */
GC_FUNC float3 gc_bsdf_eval_dspecular(GcMaterial m, float3 albedo, float3 wo, float3 wi)
{
    if (!gc_material_is(m, GC_MAT_PHONG)) return make_float3(0.0f, 0.0f, 0.0f);
    GcMaterial one = m;
    one.specular = make_float4(1.0f, 1.0f, 1.0f, m.specular.w);
    GcMaterial zero = m;
    zero.specular = make_float4(0.0f, 0.0f, 0.0f, m.specular.w);
    return gc_bsdf_eval(one, albedo, wo, wi) - gc_bsdf_eval(zero, albedo, wo, wi);
}

/* d bs.f / d m.specular for a sample drawn from m at wo: the mirror's delta coefficient is
 * Ks / cos. */
GC_FUNC float3 gc_bsdf_sample_f_dspecular(GcMaterial m, float3 albedo, float3 wo, GcBsdfSample bs)
{
    if ((bs.flags & GC_BSDF_SPECULAR) == 0u) return gc_bsdf_eval_dspecular(m, albedo, wo, bs.wi);
    if (!gc_material_is(m, GC_MAT_MIRROR) || !(fabs(wo.z) > 0.0f)) return make_float3(0.0f, 0.0f, 0.0f);
    const float k = 1.0f / fabs(wo.z);
    return make_float3(k, k, k);
}

/* ------------------------------------------------------------------ non-linear parameters
 * The Phong exponent and the glTF metallic and roughness factors enter the value
 * non-linearly (powers, the GGX distribution, clamps), so their derivative is a symmetric
 * difference of the value, with a step of 1e-3 (relative above 1), one-sided where the step
 * would leave the parameter's range. Its error, O(step^2) plus float rounding of the value
 * over the step, is far below the noise of any estimate it enters. */
#define GC_BSDF_PARAM_PHONG_EXPONENT 0u
#define GC_BSDF_PARAM_METALLIC 1u
#define GC_BSDF_PARAM_ROUGHNESS 2u

GC_FUNC float gc_bsdf_param(GcMaterial m, uint param)
{
    if (param == GC_BSDF_PARAM_PHONG_EXPONENT) return m.specular.w;
    return param == GC_BSDF_PARAM_METALLIC ? m.pbr.x : m.pbr.y;
}

GC_FUNC GcMaterial gc_bsdf_with_param(GcMaterial m, uint param, float value)
{
    if (param == GC_BSDF_PARAM_PHONG_EXPONENT) m.specular.w = value;
    else if (param == GC_BSDF_PARAM_METALLIC) m.pbr.x = value;
    else m.pbr.y = value;
    return m;
}

/* Whether param changes m's value at all. */
GC_FUNC bool gc_bsdf_has_param(GcMaterial m, uint param)
{
    if (param == GC_BSDF_PARAM_PHONG_EXPONENT) return gc_material_is(m, GC_MAT_PHONG);
    return gc_material_is(m, GC_MAT_PBR);
}

/* The difference's two ends, (lo, hi). */
GC_FUNC float2 gc_bsdf_param_step(GcMaterial m, uint param)
{
    const float v = gc_bsdf_param(m, param);
    const float h = 1.0e-3f * fmax(1.0f, fabs(v));
    const float lo = fmax(v - h, 0.0f);
    const float hi = param == GC_BSDF_PARAM_PHONG_EXPONENT ? v + h : fmin(v + h, 1.0f);
    return make_float2(lo, hi > lo ? hi : lo + h);
}

/* d gc_bsdf_eval / d param, per channel. */
GC_FUNC float3 gc_bsdf_eval_dparam(GcMaterial m, float3 albedo, float3 wo, float3 wi, uint param)
{
    if (!gc_bsdf_has_param(m, param)) return make_float3(0.0f, 0.0f, 0.0f);
    const float2 ends = gc_bsdf_param_step(m, param);
    const float3 hi = gc_bsdf_eval(gc_bsdf_with_param(m, param, ends.y), albedo, wo, wi);
    const float3 lo = gc_bsdf_eval(gc_bsdf_with_param(m, param, ends.x), albedo, wo, wi);
    return (hi - lo) * (1.0f / (ends.y - ends.x));
}

/* d bs.f / d param for a sample drawn from m at wo: the glTF transmission lobe's delta
 * coefficient depends on metallic. */
GC_FUNC float3 gc_bsdf_sample_f_dparam(GcMaterial m, float3 albedo, float3 wo, GcBsdfSample bs, uint param)
{
    if ((bs.flags & GC_BSDF_SPECULAR) == 0u) return gc_bsdf_eval_dparam(m, albedo, wo, bs.wi, param);
    if (param != GC_BSDF_PARAM_METALLIC || !gc_material_is(m, GC_MAT_PBR) || (bs.flags & GC_BSDF_TRANSMISSION) == 0u)
        return make_float3(0.0f, 0.0f, 0.0f);
    const float2 ends = gc_bsdf_param_step(m, param);
    const float3 hi = gc_pbr_sample_transmission(gc_bsdf_with_param(m, param, ends.y), albedo, wo, 1.0f).f;
    const float3 lo = gc_pbr_sample_transmission(gc_bsdf_with_param(m, param, ends.x), albedo, wo, 1.0f).f;
    return (hi - lo) * (1.0f / (ends.y - ends.x));
}

GC_NAMESPACE_END

#endif /* GC_BSDF_GRAD_H */
