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

GC_NAMESPACE_END

#endif /* GC_BSDF_GRAD_H */
