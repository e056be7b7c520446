/*
 * gc_bsdf.h — evaluation, density and sampling of every GcMaterial type, in the LOCAL
 * shading frame (normal = +z; see gc_frame.h for the change of basis).
 *
 * Conventions (shared by the integrator and tests/bsdf):
 *   - wo (towards the previous vertex / camera) and wi (towards the light) both point AWAY
 *     from the surface; neither needs to be in the upper hemisphere.
 *   - f excludes the cosine; pdf_w is a density per unit solid angle of wi.
 *   - u0 picks the lobe (or reflection vs refraction), (u1, u2) pick the direction; all in
 *     [0,1).
 *   - `albedo` is the diffuse reflectance / base colour after texturing; the caller passes
 *     it because it may come from a texture (else it is m.albedo.xyz).
 *
 * Delta lobes (the mirror of GC_MAT_MIRROR, both lobes of GC_MAT_DIELECTRIC) follow
 * pbrt-v4: f and pdf_w returned by gc_bsdf_sample are the coefficients of the Dirac delta
 * (f = R / |cos wi|, pdf_w = probability of choosing the lobe), flags has GC_BSDF_SPECULAR.
 * For EVERY sample the path throughput is multiplied by `weight` (= f |cos wi| / pdf_w, the
 * same quotient for delta and non-delta samples); pdf_w is meaningful for MIS only when
 * GC_BSDF_SPECULAR is clear. gc_bsdf_eval and gc_bsdf_pdf see only the non-delta part (a
 * delta lobe has zero value/density at any direction given in advance); for a mixture the
 * density includes the probability of choosing the non-delta lobe, so it integrates to that
 * probability over the sphere. A failed sample has flags == 0 and weight == 0.
 *
 * Two-sidedness: the references treat every non-dielectric surface as two-sided
 * (/work/shared/refs/README.md). Lambert, Phong, mirror and the PBR stub therefore mirror wo
 * and wi through the tangent plane when wo.z < 0, evaluate the upper-hemisphere BRDF, and
 * mirror the sampled wi back: the surface reflects on whichever side wo is, never transmits.
 * eval, pdf and sample all go through the same gc_bsdf_side / gc_bsdf_flip, so they agree.
 *
 * The dielectric is one-interface, non-symmetric: paths are traced from the camera, so
 * radiance crossing into a medium with relative index eta is scaled by 1/eta^2 (pbrt-v4,
 * TransportMode::Radiance; Veach 1997, sec. 5.2).
 *
 * GcBsdfSample holds float3: register-only, never put it in a buffer.
 */
#ifndef GC_BSDF_H
#define GC_BSDF_H

#include "gc_platform.h"
#include "gc_types.h"
#include "gc_sampling.h"

GC_NAMESPACE_BEGIN

#define GC_BSDF_REFLECTION 1u   /* wi on the same side as wo */
#define GC_BSDF_TRANSMISSION 2u /* wi on the other side */
#define GC_BSDF_SPECULAR 4u     /* delta lobe: f, pdf_w are delta coefficients; no MIS */

GC_STRUCT(GcBsdfSample) {
    float3 f;      /* BSDF value (cosine excluded); delta coefficient if SPECULAR */
    float3 wi;     /* sampled direction, local frame, unit length */
    float3 weight; /* f * |wi.z| / pdf_w: multiply the path throughput by this */
    float pdf_w;   /* solid-angle density; lobe probability if SPECULAR */
    uint flags;    /* GC_BSDF_*; 0 = no sample (terminate the path) */
} GC_STRUCT_END(GcBsdfSample)

GC_FUNC GcBsdfSample gc_bsdf_no_sample(void)
{
    GcBsdfSample s;
    s.f = make_float3(0.0f, 0.0f, 0.0f);
    s.wi = make_float3(0.0f, 0.0f, 1.0f);
    s.weight = make_float3(0.0f, 0.0f, 0.0f);
    s.pdf_w = 0.0f;
    s.flags = 0u;
    return s;
}

/* True when the material has only delta lobes: next-event estimation and MIS cannot help. */
GC_FUNC bool gc_bsdf_is_delta(GcMaterial m)
{
    return m.type == GC_MAT_DIELECTRIC;
}

/* ------------------------------------------------------------------ two-sided helpers */

/* +1 when wo is above the surface, -1 below (two-sided materials mirror everything into
 * the upper hemisphere by multiplying z with this). */
GC_FUNC float gc_bsdf_side(float3 wo)
{
    return wo.z < 0.0f ? -1.0f : 1.0f;
}

GC_FUNC float3 gc_bsdf_flip(float3 w, float side)
{
    return make_float3(w.x, w.y, w.z * side);
}

/* Probability of choosing the specular lobe over the diffuse one: proportional to the
 * luminance of each lobe's reflectance (its albedo at normal incidence), so a dim lobe is
 * rarely sampled. Returns -1 when both are black (nothing to sample). */
GC_FUNC float gc_bsdf_specular_prob(float3 kd, float3 ks)
{
    float ld = fmax(gc_luminance(kd), 0.0f);
    float ls = fmax(gc_luminance(ks), 0.0f);
    if (!(ld + ls > 0.0f)) return -1.0f;
    return ls / (ld + ls);
}

GC_FUNC float gc_phong_exponent(GcMaterial m)
{
    return fmax(m.specular.w, 0.0f);
}

/* ------------------------------------------------------------------ Fresnel */

/* Exact Fresnel reflectance of a smooth dielectric interface for unpolarised light (Born &
 * Wolf; pbrt-v4 FrDielectric). cos_i = |cos| of the incident angle, eta = n_transmitted /
 * n_incident. Returns 1 under total internal reflection. */
GC_FUNC float gc_fresnel_dielectric(float cos_i, float eta)
{
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    float r_s = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    float r_p = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5f * (r_s * r_s + r_p * r_p);
}

/* Relative index across the interface as seen from wo: outside is vacuum (1.0), the
 * material has index ior (emission.w); wo.z < 0 means wo is inside. A non-positive ior is
 * treated as 1 (index-matched: light passes straight through). */
GC_FUNC float gc_dielectric_eta(GcMaterial m, float3 wo)
{
    float ior = m.emission.w > 0.0f ? m.emission.w : 1.0f;
    return wo.z < 0.0f ? 1.0f / ior : ior;
}

/* ------------------------------------------------------------------ upper-hemisphere BRDFs
 * wo.z > 0 is assumed (the callers flip first). */

GC_FUNC float3 gc_phong_eval_upper(float3 kd, float3 ks, float exponent, float3 wo, float3 wi)
{
    /* Lafortune & Willems 1994: the (n+2)/(2 pi) factor makes the specular lobe's albedo
     * at normal incidence exactly ks, so kd + ks <= 1 conserves energy; the lobe is
     * symmetric in wo and wi, so the BRDF is reciprocal. */
    float3 f = kd * GC_INV_PI;
    float c = dot(wi, gc_reflect_z(wo));
    if (c > 0.0f) f = f + ks * ((exponent + 2.0f) * GC_INV_2PI * pow(c, exponent));
    return f;
}

GC_FUNC float gc_phong_pdf_upper(float p_spec, float exponent, float3 wo, float3 wi)
{
    float c = dot(wi, gc_reflect_z(wo));
    return (1.0f - p_spec) * gc_cosine_hemisphere_pdf(wi.z) + p_spec * gc_phong_lobe_pdf(c, exponent);
}

/* ------------------------------------------------------------------ public API */

/* Non-delta BSDF value f(wo, wi), cosine excluded. */
GC_FUNC float3 gc_bsdf_eval(GcMaterial m, float3 albedo, float3 wo, float3 wi)
{
    float3 zero = make_float3(0.0f, 0.0f, 0.0f);
    if (m.type == GC_MAT_DIELECTRIC) return zero;
    float side = gc_bsdf_side(wo);
    wo = gc_bsdf_flip(wo, side);
    wi = gc_bsdf_flip(wi, side);
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return zero;
    if (m.type == GC_MAT_PHONG)
        return gc_phong_eval_upper(albedo, GC_XYZ(m.specular), gc_phong_exponent(m), wo, wi);
    /* GC_MAT_LAMBERT, the diffuse part of GC_MAT_MIRROR, and GC_MAT_PBR.
     * TODO(GGX issue — glTF metallic-roughness BSDF, owned by a separate issue): GC_MAT_PBR
     * falls back to Lambert with the base colour until that issue replaces this branch.
     * Unknown types also get Lambert, the loaders' default material. */
    return albedo * GC_INV_PI;
}

/* Solid-angle density with which gc_bsdf_sample produces wi (its non-delta part). */
GC_FUNC float gc_bsdf_pdf(GcMaterial m, float3 albedo, float3 wo, float3 wi)
{
    if (m.type == GC_MAT_DIELECTRIC) return 0.0f;
    float side = gc_bsdf_side(wo);
    wo = gc_bsdf_flip(wo, side);
    wi = gc_bsdf_flip(wi, side);
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
    if (m.type == GC_MAT_PHONG) {
        float p_spec = gc_bsdf_specular_prob(albedo, GC_XYZ(m.specular));
        if (p_spec < 0.0f) return 0.0f;
        return gc_phong_pdf_upper(p_spec, gc_phong_exponent(m), wo, wi);
    }
    if (m.type == GC_MAT_MIRROR) {
        float p_spec = gc_bsdf_specular_prob(albedo, GC_XYZ(m.specular));
        if (p_spec < 0.0f) return 0.0f;
        return (1.0f - p_spec) * gc_cosine_hemisphere_pdf(wi.z);
    }
    return gc_cosine_hemisphere_pdf(wi.z); /* Lambert, PBR stub (see gc_bsdf_eval) */
}

/* Non-delta sample: f and pdf_w come from gc_bsdf_eval / gc_bsdf_pdf for the chosen wi, so
 * the three functions agree exactly (and the mixture pdf is what MIS needs). */
GC_FUNC GcBsdfSample gc_bsdf_finish_sample(GcMaterial m, float3 albedo, float3 wo, float3 wi)
{
    GcBsdfSample s;
    s.wi = wi;
    s.f = gc_bsdf_eval(m, albedo, wo, wi);
    s.pdf_w = gc_bsdf_pdf(m, albedo, wo, wi);
    if (!(s.pdf_w > 0.0f)) return gc_bsdf_no_sample();
    s.weight = s.f * (fabs(wi.z) / s.pdf_w);
    s.flags = GC_BSDF_REFLECTION;
    return s;
}

GC_FUNC GcBsdfSample gc_dielectric_sample(GcMaterial m, float3 wo, float u0)
{
    float cos_i = fabs(wo.z);
    if (!(cos_i > 0.0f)) return gc_bsdf_no_sample();
    float eta = gc_dielectric_eta(m, wo);
    float fr = gc_fresnel_dielectric(cos_i, eta);
    GcBsdfSample s;
    if (u0 < fr) {
        /* Reflection with probability F: weight F / F = 1. */
        s.wi = gc_reflect_z(wo);
        s.f = make_float3(fr, fr, fr) * (1.0f / cos_i);
        s.pdf_w = fr;
        s.weight = make_float3(1.0f, 1.0f, 1.0f);
        s.flags = GC_BSDF_REFLECTION | GC_BSDF_SPECULAR;
        return s;
    }
    /* Refraction with probability 1 - F (Snell): wi = -wo/eta + (cos_i/eta - cos_t) n, with
     * n the normal on wo's side. Radiance is scaled by 1/eta^2 (camera-to-light tracing), so
     * the weight is T / (1 - F) / eta^2 = 1/eta^2. */
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    if (!(cos_t > 0.0f)) return gc_bsdf_no_sample(); /* grazing exit: F == 1 chose reflection */
    float side = gc_bsdf_side(wo);
    float3 wi = wo * (-1.0f / eta) + make_float3(0.0f, 0.0f, side * (cos_i / eta - cos_t));
    float t = (1.0f - fr) / (eta * eta);
    s.wi = normalize(wi);
    s.f = make_float3(t, t, t) * (1.0f / cos_t);
    s.pdf_w = 1.0f - fr;
    s.weight = make_float3(1.0f, 1.0f, 1.0f) * (1.0f / (eta * eta));
    s.flags = GC_BSDF_TRANSMISSION | GC_BSDF_SPECULAR;
    return s;
}

/* Draws wi for wo; see the header comment for the meaning of the fields. */
GC_FUNC GcBsdfSample gc_bsdf_sample(GcMaterial m, float3 albedo, float3 wo, float u0, float u1, float u2)
{
    if (m.type == GC_MAT_DIELECTRIC) return gc_dielectric_sample(m, wo, u0);

    float side = gc_bsdf_side(wo);
    float3 wo_up = gc_bsdf_flip(wo, side);
    if (!(wo_up.z > 0.0f)) return gc_bsdf_no_sample();

    float3 wi_up;
    if (m.type == GC_MAT_PHONG || m.type == GC_MAT_MIRROR) {
        float3 ks = GC_XYZ(m.specular);
        float p_spec = gc_bsdf_specular_prob(albedo, ks);
        if (p_spec < 0.0f) return gc_bsdf_no_sample();
        if (u0 < p_spec) {
            if (m.type == GC_MAT_MIRROR) {
                /* Perfect mirror, reflectance ks, no Fresnel (MTL illum 3/5): delta
                 * coefficient ks / cos, chosen with probability p_spec. */
                GcBsdfSample s;
                s.wi = gc_bsdf_flip(gc_reflect_z(wo_up), side);
                s.f = ks * (1.0f / wo_up.z);
                s.pdf_w = p_spec;
                s.weight = ks * (1.0f / p_spec);
                s.flags = GC_BSDF_REFLECTION | GC_BSDF_SPECULAR;
                return s;
            }
            wi_up = gc_sample_phong_lobe(gc_reflect_z(wo_up), gc_phong_exponent(m), u1, u2);
            /* Lobe mass below the horizon is lost (the sample fails); gc_bsdf_pdf is zero
             * there, so the density stays consistent (Lafortune & Willems 1994). */
            if (!(wi_up.z > 0.0f)) return gc_bsdf_no_sample();
        } else {
            wi_up = gc_sample_cosine_hemisphere(u1, u2);
        }
    } else {
        wi_up = gc_sample_cosine_hemisphere(u1, u2); /* Lambert, PBR stub */
    }
    return gc_bsdf_finish_sample(m, albedo, wo, gc_bsdf_flip(wi_up, side));
}

GC_NAMESPACE_END

#endif /* GC_BSDF_H */
