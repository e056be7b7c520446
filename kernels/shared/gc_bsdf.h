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
 * (/work/shared/refs/README.md). Lambert, Phong, mirror and PBR therefore mirror wo
 * and wi through the tangent plane when wo.z < 0, evaluate the upper-hemisphere BRDF, and
 * mirror the sampled wi back: the surface reflects on whichever side wo is, never transmits.
 * eval, pdf and sample all go through the same gc_bsdf_side / gc_bsdf_flip, so they agree.
 * (PBR's KHR_materials_transmission lobe is the one exception: a delta lobe straight through.)
 *
 * GC_MAT_PBR is glTF 2.0's metallic-roughness model (spec appendix B): GGX microfacets, see
 * the section below. The caller passes the textured base colour as `albedo` and folds the
 * metallicRoughness texture into m.pbr (x metallic, y roughness) before calling.
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
#include "gc_frame.h"
#include "gc_types.h"
#include "gc_vecmath.h"
#include "gc_sampling.h"
#include "gc_pow.h"
#include "gc_trig.h"
#include "gc_sheen_table.h"

GC_NAMESPACE_BEGIN

/* m is of type `type` (a GC_MAT_* constant); constant false where the program was built for
 * a scene without that type (gc_features.h), so its code drops out. */
GC_FUNC bool gc_material_is(GcMaterial m, uint type) { return gc_uses_material(type) && m.type == type; }

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
    return gc_material_is(m, GC_MAT_DIELECTRIC);
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
    float c = gc_dot(wi, gc_reflect_z(wo));
    if (c > 0.0f) f = f + ks * ((exponent + 2.0f) * GC_INV_2PI * gc_pow(c, exponent));
    return f;
}

GC_FUNC float gc_phong_pdf_upper(float p_spec, float exponent, float3 wo, float3 wi)
{
    float c = gc_dot(wi, gc_reflect_z(wo));
    return (1.0f - p_spec) * gc_cosine_hemisphere_pdf(wi.z) + p_spec * gc_phong_lobe_pdf(c, exponent);
}

/* ------------------------------------------------------------------ glTF metallic-roughness
 *
 * glTF 2.0 spec, appendix B (BRDF implementation), written as one BSDF:
 *
 *   f = (1 - metallic) * [ (1 - F_d) * ((1 - transmission) * base / pi  +  transmission * btdf)
 *                          + F_d * spec ]
 *     + metallic * F_m * spec
 *   spec = D(h) G2(wo, wi) / (4 |n.wo| |n.wi|)                 (Cook & Torrance 1982)
 *   F_d  = F0 + (1 - F0) (1 - |wo.h|)^5,  F0 = ((ior - 1) / (ior + 1))^2   (Schlick 1994;
 *          0.04 for the default ior 1.5; KHR_materials_ior changes it)
 *   F_m  = base + (1 - base) (1 - |wo.h|)^5                    (the metal's F0 is base colour)
 *
 * i.e. the spec's mix(dielectric_brdf, metal_brdf, metallic) with its fresnel_mix layering
 * evaluated exactly (not the "c_diff = mix(base, 0, metallic)" shortcut). D is
 * Trowbridge-Reitz / GGX with alpha = roughness^2 (Walter et al. 2007), G2 Smith's
 * height-correlated masking-shadowing (Heitz 2014, "Understanding the Masking-Shadowing
 * Function in Microfacet-Based BRDFs"). Every factor is symmetric in wo and wi (F uses
 * wo.h = wi.h), so f is reciprocal. Single scattering: rough metals lose the energy of
 * multiple bounces between microfacets (tests/bsdf/pbr_test.cpp states the figure).
 *
 * alpha is clamped to GC_PBR_MIN_ALPHA so that roughness 0 stays a (very sharp) non-delta
 * lobe that next-event estimation and MIS still handle.
 *
 * KHR_materials_specular (GC_MATF_SPECULAR) replaces the dielectric's F_d by the spec's
 * colour-weighted fresnel_mix: F_s = min(F0 specularColor, 1) + (1 - min(...)) (1 - |wo.h|)^5
 * per channel, the specular lobe weighted by specular * F_s and the base by
 * 1 - specular * max(F_s). Without the extension the three channels are F_d.
 *
 * KHR_materials_sheen (GC_MATF_SHEEN) adds a sheen lobe over the base, with the spec's
 * albedo scaling of what lies beneath:
 *   f_sheened = sheenColor D_s V_s + f * min(1 - max(sheenColor) E(|n.wo|), 1 - max(sheenColor) E(|n.wi|))
 * D_s the "Charlie" distribution (2 + 1/a) sin(theta_h)^(1/a) / (2 pi) with a = sheenRoughness^2
 * (roughness clamped to GC_SHEEN_MIN_ROUGHNESS), V_s = 1 / ((1 + Lambda(wo) + Lambda(wi)) 4 |n.wo| |n.wi|)
 * with Estevez & Kulla's fitted Lambda (2017, "Production Friendly Microfacet Sheen BRDF"), and E
 * the lobe's directional albedo for a white colour, tabulated (gc_sheen_table.h). Sampled
 * uniformly over the hemisphere.
 *
 * KHR_materials_clearcoat (GC_MATF_CLEARCOAT) puts a GGX coat (ior 1.5, alpha =
 * clearcoatRoughness^2) over all of the above, as the spec's fresnel_coat:
 *   f_coated = f * (1 - c F_c) + c F_c D_c G2_c / (4 |n.wo| |n.wi|),  F_c = 0.04 + 0.96 (1 - |n.wo|)^5
 * with c the clearcoat factor. F_c is taken at wo alone, so a coated f is not reciprocal (the
 * spec's choice). With clearcoatNormalTexture the coat has its own normal n_c
 * (GC_MATF_COAT_NORMAL: m.coat_normal, in the shading frame), and F_c, D_c and G2_c are taken in
 * n_c's frame; the coat reflects only where wo and wi are both above n_c. The coat lies over
 * the sheen.
 *
 * KHR_materials_transmission at roughness 0 is thin-walled: a DELTA lobe straight through the
 * surface (wi = -wo), weight (1 - metallic) * transmission * (1 - F_d(|wo.z|)) * base, the
 * smooth limit of the spec's btdf. With roughness > 0 (GC_MATF_ROUGH_TRANSMISSION) the btdf is
 * a GGX microfacet refraction (Walter et al. 2007, "Microfacet Models for Refraction through
 * Rough Surfaces") with the relative index eta = ior going in (wo outside), 1/ior coming out:
 *   btdf = D(h) G2(wo, wi) |wi.h| |wo.h| / (|n.wo| |n.wi| (eta wi.h + wo.h)^2),  h ~ wo + eta wi
 * weighted as the diffuse lobe it replaces, (1 - metallic) * transmission * (1 - F_d(|wo.h|)) *
 * base; the reflection off the same facets is the specular lobe above. The Walter factor eta^2
 * cancels against the 1/eta^2 of radiance crossing into the denser side (camera paths, as the
 * dielectric below). So a closed rough mesh refracts like glass (the thin-walled smooth case
 * does not: the two limits differ, docs/decisions/khr-material-layers.md). Schlick at wo.h
 * makes the pair not reciprocal (as the spec's mix); Schlick knows no total internal
 * reflection, so from inside the facets beyond the critical angle lose their share.
 *
 * Sampling: the lobe is chosen with probabilities proportional to estimates of each lobe's
 * weight at wo (Fresnel at cos = wo.z, see gc_pbr_lobe_probs); the specular lobe samples the
 * distribution of visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
 * Normals", JCGT 7(4)), the diffuse lobe the cosine. The density is the mixture of both. */

#define GC_PBR_MIN_ALPHA 1.0e-3f

GC_FUNC float gc_pbr_alpha(GcMaterial m)
{
    const float r = clamp(m.pbr.y, 0.0f, 1.0f);
    return fmax(r * r, GC_PBR_MIN_ALPHA);
}

/* The index of refraction from KHR_materials_ior (emission.w); anything below 1 (or NaN)
 * means the glTF default 1.5. */
GC_FUNC float gc_pbr_ior(GcMaterial m) { return m.emission.w >= 1.0f ? m.emission.w : 1.5f; }

/* Dielectric F0 for gc_pbr_ior. */
GC_FUNC float gc_pbr_f0(GcMaterial m)
{
    const float ior = gc_pbr_ior(m);
    const float q = (ior - 1.0f) / (ior + 1.0f);
    return q * q;
}

/* Schlick's (1 - cos)^5. */
GC_FUNC float gc_schlick_weight(float cos_theta)
{
    const float x = clamp(1.0f - cos_theta, 0.0f, 1.0f);
    const float x2 = x * x;
    return x2 * x2 * x;
}

/* GGX normal distribution for a unit microfacet normal wm (wm.z > 0). Written with the
 * tangential components (x^2 + y^2)/alpha^2 + z^2 rather than cos^2 (alpha^2 - 1) + 1, which
 * cancels catastrophically near the peak when alpha is small. */
GC_FUNC float gc_ggx_d(float3 wm, float alpha)
{
    const float a2 = alpha * alpha;
    const float e = (wm.x * wm.x + wm.y * wm.y) / a2 + wm.z * wm.z;
    return 1.0f / (GC_PI * a2 * e * e);
}

/* Smith's Lambda for GGX: (sqrt(1 + alpha^2 tan^2) - 1) / 2. */
GC_FUNC float gc_ggx_lambda(float3 w, float alpha)
{
    const float z2 = w.z * w.z;
    if (!(z2 > 0.0f)) return GC_FLOAT_MAX;
    const float t2 = (w.x * w.x + w.y * w.y) / z2;
    return 0.5f * (sqrt(1.0f + alpha * alpha * t2) - 1.0f);
}

GC_FUNC float gc_ggx_g1(float3 w, float alpha) { return 1.0f / (1.0f + gc_ggx_lambda(w, alpha)); }

/* Height-correlated masking-shadowing. */
GC_FUNC float gc_ggx_g2(float3 wo, float3 wi, float alpha)
{
    return 1.0f / (1.0f + gc_ggx_lambda(wo, alpha) + gc_ggx_lambda(wi, alpha));
}

/* A microfacet normal distributed as the normals visible from wo (wo.z > 0): density
 * D_wo(wm) = G1(wo) max(0, wo.wm) D(wm) / wo.z (Heitz 2018). Stretch wo to the hemisphere
 * configuration, sample the projected disk (the half facing away from wo squeezed towards
 * the horizon), lift to the hemisphere and unstretch. */
GC_FUNC float3 gc_ggx_sample_visible_normal(float3 wo, float alpha, float u1, float u2)
{
    const float3 vh = gc_normalize(make_float3(alpha * wo.x, alpha * wo.y, wo.z));
    const float len2 = vh.x * vh.x + vh.y * vh.y;
    const float3 t1 = len2 > 0.0f ? make_float3(-vh.y, vh.x, 0.0f) * (1.0f / sqrt(len2)) : make_float3(1.0f, 0.0f, 0.0f);
    const float3 t2 = gc_cross(vh, t1);
    const float r = sqrt(u1);
    const float2 cs = gc_cos_sin_turns(u2);
    const float p1 = r * cs.x;
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - p1 * p1)) + s * (r * cs.y);
    const float3 nh = t1 * p1 + t2 * p2 + vh * sqrt(fmax(0.0f, 1.0f - p1 * p1 - p2 * p2));
    return gc_normalize(make_float3(alpha * nh.x, alpha * nh.y, fmax(nh.z, 0.0f)));
}

/* Density of a reflected direction wi whose half vector was drawn by
 * gc_ggx_sample_visible_normal: D_wo(wm) / (4 wo.wm) = G1(wo) D(wm) / (4 wo.z). */
GC_FUNC float gc_ggx_reflection_pdf(float3 wo, float3 wi, float alpha)
{
    const float3 wm = gc_normalize(wo + wi);
    return gc_ggx_g1(wo, alpha) * gc_ggx_d(wm, alpha) / (4.0f * wo.z);
}

/* Whether m has the KHR_materials_* layer `flag` (GC_MATF_*); constant false where the program
 * was built without the layer's feature (`used`, a GC_USE_* define), so its code drops out. */
#define gc_pbr_has(m, used, flag) ((used) != 0 && ((m).flags & (flag)) != 0u)

GC_FUNC float gc_max_component(float3 v) { return fmax(v.x, fmax(v.y, v.z)); }

/* The cosine at which the dielectric's Schlick Fresnel is taken for an incident cosine cos_i.
 * From inside a rough-transmission mesh, Schlick at cos_i knows no total internal reflection
 * (the light that cannot leave would be lost), so there it is taken at the transmitted cosine
 * (Snell from ior to 1): F rises to 1 at the critical angle and stays there beyond it. */
GC_FUNC float gc_pbr_fresnel_cos(GcMaterial m, float cos_i)
{
    if (!gc_pbr_has(m, GC_USE_ROUGH_TRANSMISSION, GC_MATF_SEEN_FROM_INSIDE)) return cos_i;
    const float ior = gc_pbr_ior(m);
    const float sin2_t = ior * ior * (1.0f - cos_i * cos_i);
    return sin2_t < 1.0f ? sqrt(1.0f - sin2_t) : 0.0f;
}

/* The dielectric's weighted Fresnel, per channel, at Schlick weight sw: F_d in all three
 * channels, or specular * F_s with KHR_materials_specular (see above). */
GC_FUNC float3 gc_pbr_dielectric_fresnel(GcMaterial m, float sw)
{
    const float f0 = gc_pbr_f0(m);
    if (!gc_pbr_has(m, GC_USE_SPECULAR, GC_MATF_SPECULAR)) {
        const float fd = f0 + (1.0f - f0) * sw;
        return make_float3(fd, fd, fd);
    }
    const float3 one = make_float3(1.0f, 1.0f, 1.0f);
    const float3 f0c = fmin(fmax(GC_XYZ(m.specular), make_float3(0.0f, 0.0f, 0.0f)) * f0, one);
    return (f0c + (one - f0c) * sw) * clamp(m.coat.w, 0.0f, 1.0f);
}

/* Unnormalised weights (specular, diffuse, transmission) of the base lobes for wo.z = cos_o,
 * with the Fresnel terms taken at cos_o (the half vector is unknown before sampling):
 * specular (1 - metallic) F_d + metallic lum(F_m), diffuse and transmission
 * (1 - metallic)(1 - F_d) lum(base), split by `transmission` (F_d: the largest channel). */
GC_FUNC float3 gc_pbr_lobe_weights(GcMaterial m, float3 base, float cos_o)
{
    const float metallic = clamp(m.pbr.x, 0.0f, 1.0f);
    const float trans = clamp(m.pbr.w, 0.0f, 1.0f);
    const float sw = gc_schlick_weight(cos_o);
    const float fd = gc_max_component(gc_pbr_dielectric_fresnel(m, gc_schlick_weight(gc_pbr_fresnel_cos(m, cos_o))));
    const float3 fm = base + (make_float3(1.0f, 1.0f, 1.0f) - base) * sw;
    const float w_spec = (1.0f - metallic) * fd + metallic * fmax(gc_luminance(fm), 0.0f);
    const float w_base = (1.0f - metallic) * (1.0f - fd) * fmax(gc_luminance(base), 0.0f);
    return make_float3(w_spec, w_base * (1.0f - trans), w_base * trans);
}

/* Probabilities (specular, diffuse, transmission) of choosing each base lobe for wo.z = cos_o,
 * proportional to gc_pbr_lobe_weights. */
GC_FUNC float3 gc_pbr_lobe_probs(GcMaterial m, float3 base, float cos_o)
{
    const float3 w = gc_pbr_lobe_weights(m, base, cos_o);
    const float sum = w.x + w.y + w.z;
    if (!(sum > 0.0f)) return make_float3(1.0f, 0.0f, 0.0f);
    return make_float3(w.x / sum, w.y / sum, w.z / sum);
}

/* ---- KHR_materials_clearcoat */

GC_FUNC float gc_pbr_coat_alpha(GcMaterial m)
{
    const float r = clamp(m.coat.y, 0.0f, 1.0f);
    return fmax(r * r, GC_PBR_MIN_ALPHA);
}

/* c F_c at cos_o = |n.wo|: the share of the coat in the mix (0 without a coat). */
GC_FUNC float gc_pbr_coat_weight(GcMaterial m, float cos_o)
{
    if (!gc_pbr_has(m, GC_USE_CLEARCOAT, GC_MATF_CLEARCOAT)) return 0.0f;
    return clamp(m.coat.x, 0.0f, 1.0f) * (0.04f + 0.96f * gc_schlick_weight(cos_o));
}

/* Whether the coat has its own normal (gc_with_coat_normal); constant false without normal
 * maps or coats in the program. */
#define gc_pbr_coat_tilted(m) (GC_USE_NORMAL_MAPS * GC_USE_CLEARCOAT != 0 && ((m).flags & GC_MATF_COAT_NORMAL) != 0u)

/* w (in the shading frame) in the coat's frame, and back: the identity for an untilted coat. */
GC_FUNC float3 gc_pbr_to_coat(GcMaterial m, float3 w)
{
    if (!gc_pbr_coat_tilted(m)) return w;
    return gc_frame_to_local(gc_frame_from_normal(GC_XYZ(m.coat_normal)), w);
}

GC_FUNC float3 gc_pbr_from_coat(GcMaterial m, float3 w)
{
    if (!gc_pbr_coat_tilted(m)) return w;
    return gc_frame_to_world(gc_frame_from_normal(GC_XYZ(m.coat_normal)), w);
}

/* The coat's weight for wo (upper hemisphere of the shading frame): c F_c at n_c.wo, which is
 * wo.z for an untilted coat; a wo below a tilted coat's horizon sees the coat at grazing. */
GC_FUNC float gc_pbr_coat_weight_for(GcMaterial m, float3 wo)
{
    return gc_pbr_coat_weight(m, gc_pbr_coat_tilted(m) ? fmax(gc_pbr_to_coat(m, wo).z, 0.0f) : wo.z);
}

/* The coat's GGX lobe, D_c G2_c / (4 |n_c.wo| |n_c.wi|), and the density of sampling it. */
GC_FUNC float gc_pbr_coat_lobe(GcMaterial m, float3 wo, float3 wi)
{
    const float3 o = gc_pbr_to_coat(m, wo);
    const float3 i = gc_pbr_to_coat(m, wi);
    if (gc_pbr_coat_tilted(m) && (!(o.z > 0.0f) || !(i.z > 0.0f))) return 0.0f;
    const float alpha = gc_pbr_coat_alpha(m);
    return gc_ggx_d(gc_normalize(o + i), alpha) * gc_ggx_g2(o, i, alpha) / (4.0f * o.z * i.z);
}

GC_FUNC float gc_pbr_coat_pdf(GcMaterial m, float3 wo, float3 wi)
{
    const float3 o = gc_pbr_to_coat(m, wo);
    const float3 i = gc_pbr_to_coat(m, wi);
    if (gc_pbr_coat_tilted(m) && (!(o.z > 0.0f) || !(i.z > 0.0f))) return 0.0f;
    return gc_ggx_reflection_pdf(o, i, gc_pbr_coat_alpha(m));
}

/* ---- KHR_materials_sheen */

#define GC_SHEEN_MIN_ROUGHNESS 0.07f

GC_FUNC float gc_sheen_roughness(GcMaterial m) { return clamp(m.sheen.w, GC_SHEEN_MIN_ROUGHNESS, 1.0f); }

/* Charlie distribution at the half vector's cosine, alpha = roughness^2. */
GC_FUNC float gc_sheen_d(float cos_h, float alpha)
{
    const float inv = 1.0f / alpha;
    const float sin2 = fmax(0.0f, 1.0f - cos_h * cos_h);
    return (2.0f + inv) * gc_pow(sin2, 0.5f * inv) * GC_INV_2PI;
}

/* Estevez & Kulla's fit L(x) = a / (1 + b x^c) + d x + e, its coefficients interpolated between
 * the fits for roughness 1 and 0 by (1 - alpha)^2. */
GC_FUNC float gc_sheen_fit(float x, float alpha)
{
    const float t = (1.0f - alpha) * (1.0f - alpha);
    const float a = 21.5473f + (25.3245f - 21.5473f) * t;
    const float b = 3.82987f + (3.32435f - 3.82987f) * t;
    const float c = 0.19823f + (0.16801f - 0.19823f) * t;
    const float d = -1.97760f + (-1.27393f + 1.97760f) * t;
    const float e = -4.32054f + (-4.85967f + 4.32054f) * t;
    return a / (1.0f + b * gc_pow(x, c)) + d * x + e;
}

/* Lambda(theta) = exp(L(cos)) below cos 1/2, mirrored as exp(2 L(1/2) - L(1 - cos)) above. */
GC_FUNC float gc_sheen_lambda(float cos_theta, float alpha)
{
    const float x = fabs(cos_theta);
    const float l = x < 0.5f ? gc_sheen_fit(x, alpha) : 2.0f * gc_sheen_fit(0.5f, alpha) - gc_sheen_fit(1.0f - x, alpha);
    return gc_exp2(l * 1.44269504f);
}

/* The sheen lobe for a white colour, wo and wi in the upper hemisphere. */
GC_FUNC float gc_sheen_eval_white(float3 wo, float3 wi, float roughness)
{
    const float alpha = roughness * roughness;
    const float3 wm = gc_normalize(wo + wi);
    const float v = 1.0f / ((1.0f + gc_sheen_lambda(wo.z, alpha) + gc_sheen_lambda(wi.z, alpha)) * 4.0f * wo.z * wi.z);
    return gc_sheen_d(wm.z, alpha) * v;
}

/* E(cos, roughness) from gc_sheen_table.h, bilinear. */
GC_FUNC float gc_sheen_albedo(float cos_theta, float roughness)
{
    const float x = clamp(fabs(cos_theta), 0.0f, 1.0f) * gc_float(GC_SHEEN_TABLE_COS - 1);
    const float y = clamp(roughness, 0.0f, 1.0f) * gc_float(GC_SHEEN_TABLE_ROUGH - 1);
    const int x0 = gc_int(fmin(x, gc_float(GC_SHEEN_TABLE_COS - 2)));
    const int y0 = gc_int(fmin(y, gc_float(GC_SHEEN_TABLE_ROUGH - 2)));
    const float fx = x - gc_float(x0);
    const float fy = y - gc_float(y0);
    const int i = y0 * GC_SHEEN_TABLE_COS + x0;
    const float e0 = gc_sheen_albedo_table[i] * (1.0f - fx) + gc_sheen_albedo_table[i + 1] * fx;
    const float e1 = gc_sheen_albedo_table[i + GC_SHEEN_TABLE_COS] * (1.0f - fx) + gc_sheen_albedo_table[i + GC_SHEEN_TABLE_COS + 1] * fx;
    return e0 * (1.0f - fy) + e1 * fy;
}

/* max(sheenColor) E(cos): the share the sheen takes from the layers beneath (0 without sheen). */
GC_FUNC float gc_pbr_sheen_weight(GcMaterial m, float cos_theta)
{
    if (!gc_pbr_has(m, GC_USE_SHEEN, GC_MATF_SHEEN)) return 0.0f;
    const float c = fmax(gc_max_component(GC_XYZ(m.sheen)), 0.0f);
    return clamp(c * gc_sheen_albedo(cos_theta, gc_sheen_roughness(m)), 0.0f, 1.0f);
}

/* Probabilities (coat, sheen) of sampling each layer for wo (upper hemisphere): each layer's
 * weight against what lies beneath, scaled by what the layer lets through. */
GC_FUNC float2 gc_pbr_layer_probs(GcMaterial m, float3 base, float3 wo)
{
    const float cos_o = wo.z;
    const float wc = gc_pbr_coat_weight_for(m, wo);
    const float ws = gc_pbr_sheen_weight(m, cos_o);
    if (!(wc > 0.0f) && !(ws > 0.0f)) return make_float2(0.0f, 0.0f);
    const float3 w = gc_pbr_lobe_weights(m, base, cos_o);
    const float below_sheen = w.x + w.y + w.z;
    const float ps = ws > 0.0f ? ws / (ws + (1.0f - ws) * below_sheen) : 0.0f;
    const float below_coat = ws > 0.0f ? ws + (1.0f - ws) * below_sheen : below_sheen;
    const float pc = wc > 0.0f ? wc / (wc + (1.0f - wc) * below_coat) : 0.0f;
    return make_float2(pc, ps);
}

/* Non-delta part of the base (everything below the coat) for wo, wi in the upper hemisphere. */
GC_FUNC float3 gc_pbr_base_eval_upper(GcMaterial m, float3 base, float3 wo, float3 wi)
{
    const float metallic = clamp(m.pbr.x, 0.0f, 1.0f);
    const float trans = clamp(m.pbr.w, 0.0f, 1.0f);
    const float alpha = gc_pbr_alpha(m);
    const float3 wm = gc_normalize(wo + wi);
    const float cos_h = gc_dot(wo, wm);
    const float sw = gc_schlick_weight(cos_h);
    const float3 fd = gc_pbr_dielectric_fresnel(m, gc_schlick_weight(gc_pbr_fresnel_cos(m, cos_h)));
    const float3 fm = base + (make_float3(1.0f, 1.0f, 1.0f) - base) * sw;
    const float3 fresnel = fd * (1.0f - metallic) + fm * metallic;
    const float spec = gc_ggx_d(wm, alpha) * gc_ggx_g2(wo, wi, alpha) / (4.0f * wo.z * wi.z);
    const float3 diffuse = base * ((1.0f - metallic) * (1.0f - trans) * (1.0f - gc_max_component(fd)) * GC_INV_PI);
    return diffuse + fresnel * spec;
}

/* Non-delta part of f for wo, wi both in the upper hemisphere. */
GC_FUNC float3 gc_pbr_eval_upper(GcMaterial m, float3 base, float3 wo, float3 wi)
{
    float3 f = gc_pbr_base_eval_upper(m, base, wo, wi);
    if (gc_pbr_has(m, GC_USE_SHEEN, GC_MATF_SHEEN)) {
        const float scale = fmin(1.0f - gc_pbr_sheen_weight(m, wo.z), 1.0f - gc_pbr_sheen_weight(m, wi.z));
        const float3 colour = fmax(GC_XYZ(m.sheen), make_float3(0.0f, 0.0f, 0.0f));
        f = f * scale + colour * gc_sheen_eval_white(wo, wi, gc_sheen_roughness(m));
    }
    const float wc = gc_pbr_coat_weight_for(m, wo);
    if (!(wc > 0.0f)) return f;
    const float coat = gc_pbr_coat_lobe(m, wo, wi);
    return f * (1.0f - wc) + make_float3(coat, coat, coat) * wc;
}

GC_FUNC float gc_pbr_pdf_upper(GcMaterial m, float3 base, float3 wo, float3 wi)
{
    const float3 p = gc_pbr_lobe_probs(m, base, wo.z);
    float pdf = p.x * gc_ggx_reflection_pdf(wo, wi, gc_pbr_alpha(m)) + p.y * gc_cosine_hemisphere_pdf(wi.z);
    const float2 layers = gc_pbr_layer_probs(m, base, wo);
    if (layers.y > 0.0f) pdf = layers.y * GC_INV_2PI + (1.0f - layers.y) * pdf;
    if (layers.x > 0.0f) pdf = layers.x * gc_pbr_coat_pdf(m, wo, wi) + (1.0f - layers.x) * pdf;
    return pdf;
}

/* ---- KHR_materials_transmission with roughness (GC_MATF_ROUGH_TRANSMISSION) */

GC_FUNC bool gc_pbr_rough_transmission(GcMaterial m)
{
    return gc_pbr_has(m, GC_USE_ROUGH_TRANSMISSION, GC_MATF_ROUGH_TRANSMISSION);
}

/* m as the functions below see it from wo's side (`side` as gc_bsdf_side(wo)): a rough-
 * transmission material seen from inside is marked, for gc_pbr_fresnel_cos. */
GC_FUNC GcMaterial gc_pbr_from_side(GcMaterial m, float side)
{
    if (side < 0.0f && gc_material_is(m, GC_MAT_PBR) && gc_pbr_rough_transmission(m)) m.flags |= GC_MATF_SEEN_FROM_INSIDE;
    /* Seen from below, the surface is its own front with the normal -n: the coat's normal is
     * -n_c, which in the flipped frame (z mirrored, gc_bsdf_flip) is n_c with x and y negated;
     * an untilted coat (0, 0, 1) stays as it is, as the coat of the flat model does. Applied
     * once per eval, pdf or sample (gc_bsdf_finish_sample is given the material unturned). */
    if (side < 0.0f && gc_pbr_coat_tilted(m))
        m.coat_normal = make_float4(-m.coat_normal.x, -m.coat_normal.y, m.coat_normal.z, 0.0f);
    return m;
}

/* Relative index n(wi's side) / n(wo's side) for a refraction from wo's side, `side` as
 * gc_bsdf_side(wo): +1 outside. gc_pbr_ior, at least GC_PBR_MIN_TRANSMISSION_IOR, because at 1
 * the generalised half vector of a straight-through pair vanishes. */
#define GC_PBR_MIN_TRANSMISSION_IOR 1.001f
GC_FUNC float gc_pbr_transmission_eta(GcMaterial m, float side)
{
    const float ior = fmax(gc_pbr_ior(m), GC_PBR_MIN_TRANSMISSION_IOR);
    return side > 0.0f ? ior : 1.0f / ior;
}

/* The transmission facets' roughness. At an ior of 1 they bend no light, whatever their
 * slopes, so they are smooth: the transmitted image stays sharp and, unlike a rough lobe at
 * eta 1.001, loses nothing to masking (Khronos' TransmissionRoughnessTest, row "1.0 - Air";
 * pbrt-v4's dielectric passes straight through at eta 1 likewise). */
GC_FUNC float gc_pbr_transmission_alpha(GcMaterial m)
{
    return gc_pbr_ior(m) < GC_PBR_MIN_TRANSMISSION_IOR ? GC_PBR_MIN_ALPHA : gc_pbr_alpha(m);
}

/* The rough btdf for wo above (wo.z > 0) and wi below (wi.z < 0), eta from
 * gc_pbr_transmission_eta. */
GC_FUNC float3 gc_pbr_rough_transmission_eval_lower(GcMaterial m, float3 base, float3 wo, float3 wi, float eta)
{
    const float3 zero = make_float3(0.0f, 0.0f, 0.0f);
    float3 wm = wo + wi * eta;
    const float len = gc_length(wm);
    if (!(len > 0.0f)) return zero;
    wm = wm * ((wm.z < 0.0f ? -1.0f : 1.0f) / len);
    const float dot_o = gc_dot(wo, wm);
    const float dot_i = gc_dot(wi, wm);
    /* The facet must face wo and be crossed by wi (else the pair is not a refraction). */
    if (!(dot_o > 0.0f) || !(dot_i < 0.0f)) return zero;
    const float alpha = gc_pbr_transmission_alpha(m);
    const float denom = eta * dot_i + dot_o;
    const float btdf = gc_ggx_d(wm, alpha) * gc_ggx_g2(wo, wi, alpha) * (-dot_i) * dot_o /
                       (wo.z * (-wi.z) * denom * denom);
    const float metallic = clamp(m.pbr.x, 0.0f, 1.0f);
    const float trans = clamp(m.pbr.w, 0.0f, 1.0f);
    const float fd = gc_max_component(gc_pbr_dielectric_fresnel(m, gc_schlick_weight(gc_pbr_fresnel_cos(m, dot_o))));
    const float wc = gc_pbr_coat_weight_for(m, wo);
    const float ws = gc_pbr_sheen_weight(m, wo.z);
    return base * ((1.0f - metallic) * trans * (1.0f - fd) * (1.0f - wc) * (1.0f - ws) * btdf);
}

/* Density of gc_pbr_sample_rough_transmission's wi, given the lobe was chosen: the visible
 * normal density D_wo(h) times the Jacobian |dh/dwi| = eta^2 |wi.h| / (eta wi.h + wo.h)^2. */
GC_FUNC float gc_pbr_rough_transmission_pdf_lower(GcMaterial m, float3 wo, float3 wi, float eta)
{
    float3 wm = wo + wi * eta;
    const float len = gc_length(wm);
    if (!(len > 0.0f)) return 0.0f;
    wm = wm * ((wm.z < 0.0f ? -1.0f : 1.0f) / len);
    const float dot_o = gc_dot(wo, wm);
    const float dot_i = gc_dot(wi, wm);
    if (!(dot_o > 0.0f) || !(dot_i < 0.0f)) return 0.0f;
    const float alpha = gc_pbr_transmission_alpha(m);
    const float denom = eta * dot_i + dot_o;
    const float d_visible = gc_ggx_g1(wo, alpha) * dot_o * gc_ggx_d(wm, alpha) / wo.z;
    return d_visible * eta * eta * (-dot_i) / (denom * denom);
}

/* Refracts wo (wo.z > 0) through a visible facet; wi.z >= 0 (total internal reflection at the
 * facet, or a refraction that stays above the surface) means no sample. */
GC_FUNC float3 gc_pbr_sample_rough_transmission(GcMaterial m, float3 wo, float eta, float u1, float u2)
{
    const float3 wm = gc_ggx_sample_visible_normal(wo, gc_pbr_transmission_alpha(m), u1, u2);
    const float cos_o = gc_dot(wo, wm);
    const float sin2_t = (1.0f - cos_o * cos_o) / (eta * eta);
    if (!(sin2_t < 1.0f) || !(cos_o > 0.0f)) return make_float3(0.0f, 0.0f, 1.0f);
    const float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    return gc_normalize(wo * (-1.0f / eta) + wm * (cos_o / eta - cos_t));
}

/* ------------------------------------------------------------------ public API */

/* Non-delta BSDF value f(wo, wi), cosine excluded. */
GC_FUNC float3 gc_bsdf_eval(GcMaterial m, float3 albedo, float3 wo, float3 wi)
{
    float3 zero = make_float3(0.0f, 0.0f, 0.0f);
    if (gc_material_is(m, GC_MAT_DIELECTRIC)) return zero;
    float side = gc_bsdf_side(wo);
    m = gc_pbr_from_side(m, side);
    wo = gc_bsdf_flip(wo, side);
    wi = gc_bsdf_flip(wi, side);
    if (gc_material_is(m, GC_MAT_PBR) && gc_pbr_rough_transmission(m) && wo.z > 0.0f && wi.z < 0.0f)
        return gc_pbr_rough_transmission_eval_lower(m, albedo, wo, wi, gc_pbr_transmission_eta(m, side));
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return zero;
    if (gc_material_is(m, GC_MAT_PHONG))
        return gc_phong_eval_upper(albedo, GC_XYZ(m.specular), gc_phong_exponent(m), wo, wi);
    if (gc_material_is(m, GC_MAT_PBR)) return gc_pbr_eval_upper(m, albedo, wo, wi);
    /* GC_MAT_LAMBERT and the diffuse part of GC_MAT_MIRROR. Unknown types also get Lambert,
     * the loaders' default material. */
    return albedo * GC_INV_PI;
}

/* Solid-angle density with which gc_bsdf_sample produces wi (its non-delta part). */
GC_FUNC float gc_bsdf_pdf(GcMaterial m, float3 albedo, float3 wo, float3 wi)
{
    if (gc_material_is(m, GC_MAT_DIELECTRIC)) return 0.0f;
    float side = gc_bsdf_side(wo);
    m = gc_pbr_from_side(m, side);
    wo = gc_bsdf_flip(wo, side);
    wi = gc_bsdf_flip(wi, side);
    if (gc_material_is(m, GC_MAT_PBR) && gc_pbr_rough_transmission(m) && wo.z > 0.0f && wi.z < 0.0f) {
        const float2 layers = gc_pbr_layer_probs(m, albedo, wo);
        const float p_trans = (1.0f - layers.x) * (1.0f - layers.y) * gc_pbr_lobe_probs(m, albedo, wo.z).z;
        return p_trans * gc_pbr_rough_transmission_pdf_lower(m, wo, wi, gc_pbr_transmission_eta(m, side));
    }
    if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
    if (gc_material_is(m, GC_MAT_PHONG)) {
        float p_spec = gc_bsdf_specular_prob(albedo, GC_XYZ(m.specular));
        if (p_spec < 0.0f) return 0.0f;
        return gc_phong_pdf_upper(p_spec, gc_phong_exponent(m), wo, wi);
    }
    if (gc_material_is(m, GC_MAT_MIRROR)) {
        float p_spec = gc_bsdf_specular_prob(albedo, GC_XYZ(m.specular));
        if (p_spec < 0.0f) return 0.0f;
        return (1.0f - p_spec) * gc_cosine_hemisphere_pdf(wi.z);
    }
    if (gc_material_is(m, GC_MAT_PBR)) return gc_pbr_pdf_upper(m, albedo, wo, wi);
    return gc_cosine_hemisphere_pdf(wi.z); /* Lambert */
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
    s.flags = wi.z * wo.z < 0.0f ? GC_BSDF_TRANSMISSION : GC_BSDF_REFLECTION;
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
    s.wi = gc_normalize(wi);
    s.f = make_float3(t, t, t) * (1.0f / cos_t);
    s.pdf_w = 1.0f - fr;
    s.weight = make_float3(1.0f, 1.0f, 1.0f) * (1.0f / (eta * eta));
    s.flags = GC_BSDF_TRANSMISSION | GC_BSDF_SPECULAR;
    return s;
}

/* The thin-walled transmission lobe of GC_MAT_PBR, chosen with probability p_trans: a delta
 * straight through the surface (see the PBR section), dimmed by a coat's weight. */
GC_FUNC GcBsdfSample gc_pbr_sample_transmission(GcMaterial m, float3 base, float3 wo, float p_trans)
{
    const float cos_o = fabs(wo.z);
    if (!(cos_o > 0.0f)) return gc_bsdf_no_sample();
    const float metallic = clamp(m.pbr.x, 0.0f, 1.0f);
    const float trans = clamp(m.pbr.w, 0.0f, 1.0f);
    const float fd = gc_max_component(gc_pbr_dielectric_fresnel(m, gc_schlick_weight(cos_o)));
    float3 t = base * ((1.0f - metallic) * trans * (1.0f - fd));
    const float wc = gc_pbr_coat_weight_for(m, gc_bsdf_flip(wo, gc_bsdf_side(wo)));
    if (wc > 0.0f) t = t * (1.0f - wc);
    const float ws = gc_pbr_sheen_weight(m, cos_o);
    if (ws > 0.0f) t = t * (1.0f - ws);
    GcBsdfSample s;
    s.wi = -wo;
    s.f = t * (1.0f / cos_o);
    s.pdf_w = p_trans;
    s.weight = t * (1.0f / p_trans);
    s.flags = GC_BSDF_TRANSMISSION | GC_BSDF_SPECULAR;
    return s;
}

/* Draws wi for wo; see the header comment for the meaning of the fields. */
GC_FUNC GcBsdfSample gc_bsdf_sample(GcMaterial m, float3 albedo, float3 wo, float u0, float u1, float u2)
{
    if (gc_material_is(m, GC_MAT_DIELECTRIC)) return gc_dielectric_sample(m, wo, u0);

    float side = gc_bsdf_side(wo);
    const GcMaterial given = m; /* for gc_bsdf_finish_sample, which turns it itself */
    m = gc_pbr_from_side(m, side);
    float3 wo_up = gc_bsdf_flip(wo, side);
    if (!(wo_up.z > 0.0f)) return gc_bsdf_no_sample();

    float3 wi_up;
    if (gc_material_is(m, GC_MAT_PHONG) || gc_material_is(m, GC_MAT_MIRROR)) {
        float3 ks = GC_XYZ(m.specular);
        float p_spec = gc_bsdf_specular_prob(albedo, ks);
        if (p_spec < 0.0f) return gc_bsdf_no_sample();
        if (u0 < p_spec) {
            if (gc_material_is(m, GC_MAT_MIRROR)) {
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
    } else if (gc_material_is(m, GC_MAT_PBR)) {
        /* The coat first, then the sheen, each with its probability; else u0 is rescaled to
         * pick the next layer down. */
        const float2 layers = gc_pbr_layer_probs(m, albedo, wo_up);
        const float pc = layers.x;
        const float ps = layers.y;
        const bool coat = pc > 0.0f && u0 < pc;
        if (pc > 0.0f && !coat) u0 = fmin((u0 - pc) / (1.0f - pc), 0.99999994f);
        const bool sheen = !coat && ps > 0.0f && u0 < ps;
        if (ps > 0.0f && !coat && !sheen) u0 = fmin((u0 - ps) / (1.0f - ps), 0.99999994f);
        const float3 p = gc_pbr_lobe_probs(m, albedo, wo_up.z);
        if (sheen) {
            const float3 w = gc_sample_uniform_sphere(u1, u2);
            wi_up = make_float3(w.x, w.y, fabs(w.z));
        } else if (coat && gc_pbr_coat_tilted(m)) {
            /* In the coat's frame, then back; below either horizon the sample fails, where
             * gc_bsdf_pdf's coat term is zero too. */
            const float3 wo_c = gc_pbr_to_coat(m, wo_up);
            if (!(wo_c.z > 0.0f)) return gc_bsdf_no_sample();
            const float3 wm = gc_ggx_sample_visible_normal(wo_c, gc_pbr_coat_alpha(m), u1, u2);
            wi_up = gc_pbr_from_coat(m, wm * (2.0f * gc_dot(wo_c, wm)) - wo_c);
            if (!(wi_up.z > 0.0f)) return gc_bsdf_no_sample();
        } else if (coat || u0 < p.x) {
            const float alpha = coat ? gc_pbr_coat_alpha(m) : gc_pbr_alpha(m);
            const float3 wm = gc_ggx_sample_visible_normal(wo_up, alpha, u1, u2);
            wi_up = wm * (2.0f * gc_dot(wo_up, wm)) - wo_up;
            /* Reflections off visible facets can still leave below the horizon: the sample
             * fails, and gc_bsdf_pdf is zero there, so the density stays consistent. */
            if (!(wi_up.z > 0.0f)) return gc_bsdf_no_sample();
        } else if (p.z > 0.0f && u0 >= p.x + p.y) {
            if (gc_pbr_rough_transmission(m)) {
                wi_up = gc_pbr_sample_rough_transmission(m, wo_up, gc_pbr_transmission_eta(m, side), u1, u2);
                if (!(wi_up.z < 0.0f)) return gc_bsdf_no_sample();
                return gc_bsdf_finish_sample(given, albedo, wo, gc_bsdf_flip(wi_up, side));
            }
            return gc_pbr_sample_transmission(m, albedo, wo, (1.0f - pc) * (1.0f - ps) * p.z);
        } else {
            wi_up = gc_sample_cosine_hemisphere(u1, u2);
        }
    } else {
        wi_up = gc_sample_cosine_hemisphere(u1, u2); /* Lambert */
    }
    return gc_bsdf_finish_sample(given, albedo, wo, gc_bsdf_flip(wi_up, side));
}

GC_NAMESPACE_END

#endif /* GC_BSDF_H */
