/*
 * gc_whitted.h — the pure pieces of the Whitted integrator (gc_whitted_tree.h walks the ray
 * tree with them for kernels/whitted.cl and kernels/vk/whitted.comp): local shading of one
 * light sample, the ambient term, and the split of a specular surface into its reflected and
 * refracted rays. Shared so host tests check exactly what the kernels do.
 *
 * Whitted 1980, "An Improved Illumination Model for Shaded Display" (CACM 23(6)):
 *     I = I_a + sum_lights (diffuse + specular) * visibility + k_s S + k_t T
 * written here in radiometric units so that it agrees with the path tracer where both are
 * exact: the local term uses the energy-normalised modified Phong BRDF of gc_bsdf.h
 * (f = kd/pi + ks (n+2)/(2 pi) cos^n alpha; Lafortune & Willems 1994), a point light gives
 * f |cos| I / d^2, an area light sample gives f |cos| Le |cos_light| / (d^2 pdf_area), and the
 * reflected / refracted rays carry the mirror reflectance or the Fresnel split.
 *
 * Directions are world space, unit length, pointing AWAY from the surface (wo towards the
 * viewer, wi towards the light). ns is the shading normal and ng the geometric one, each as
 * the mesh has it (they may face opposite ways on badly authored meshes: docs/design.md),
 * NOT flipped toward the viewer: opaque materials are two-sided and the functions below flip
 * as needed; a dielectric's inside is behind ns.
 *
 * GcWhittedSpecular holds float3: register-only, never put it in a buffer.
 */
#ifndef GC_WHITTED_H
#define GC_WHITTED_H

#include "gc_bsdf.h"
#include "gc_frame.h"

GC_NAMESPACE_BEGIN

/* Whether any channel of a radiance or weight is positive. */
GC_FUNC bool gc_whitted_nonzero(float3 v) { return v.x > 0.0f || v.y > 0.0f || v.z > 0.0f; }

/* How much a pending ray of the tree can still add: its largest weight channel (the ray-tree
 * stack drops the lowest when it overflows, gc_whitted_tree.h). */
GC_FUNC float gc_whitted_priority(float3 weight) { return fmax(weight.x, fmax(weight.y, weight.z)); }

/* f(wo, wi) * |cos theta_i| of the material's non-delta part (Lambert; Phong's kd and ks
 * lobes; the diffuse kd of a mirror; nothing for a dielectric). An opaque surface lets no
 * light through: when wo and wi lie on different sides of the geometric surface the result
 * is zero, even where interpolated shading normals would disagree. */
GC_FUNC float3 gc_whitted_brdf_cos(GcMaterial m, float3 albedo, float3 ns, float3 ng, float3 wo, float3 wi)
{
    if (!(gc_dot(ng, wo) * gc_dot(ng, wi) > 0.0f)) return make_float3(0.0f, 0.0f, 0.0f);
    GcFrame frame = gc_frame_from_normal(ns);
    float3 wo_l = gc_frame_to_local(frame, wo);
    float3 wi_l = gc_frame_to_local(frame, wi);
    return gc_bsdf_eval(m, albedo, wo_l, wi_l) * fabs(wi_l.z);
}

/* Radiance reflected towards wo from a point light of radiant intensity I at squared
 * distance dist2 (visibility is the caller's shadow ray). */
GC_FUNC float3 gc_whitted_point_light(float3 brdf_cos, float3 intensity, float dist2)
{
    if (!(dist2 > 0.0f)) return make_float3(0.0f, 0.0f, 0.0f);
    return brdf_cos * intensity * (1.0f / dist2);
}

/* One-sample area-light estimate: the point was drawn with density pdf_area (per unit area,
 * emitter selection included) on an emitter of radiance Le whose normal makes cos_light with
 * the direction back to the shaded point. Unbiased for the direct light from all emitters. */
GC_FUNC float3 gc_whitted_area_light(float3 brdf_cos, float3 radiance, float cos_light, float dist2, float pdf_area)
{
    if (!(dist2 > 0.0f) || !(pdf_area > 0.0f)) return make_float3(0.0f, 0.0f, 0.0f);
    return brdf_cos * radiance * (fabs(cos_light) / (dist2 * pdf_area));
}

/* Whitted's ambient term I_a k_a: the --env radiance doubles as the ambient light and k_a is
 * the diffuse albedo, which is exactly the light a diffuse surface reflects from an
 * unoccluded constant environment. Glossy and mirror lobes get none (the mirror sees the
 * environment through its reflected ray); dielectrics are purely specular. */
GC_FUNC float3 gc_whitted_ambient(GcMaterial m, float3 albedo, float3 env)
{
    if (m.type == GC_MAT_DIELECTRIC) return make_float3(0.0f, 0.0f, 0.0f);
    return env * albedo;
}

/* Mirror direction of wo about the unit normal n (either side). */
GC_FUNC float3 gc_whitted_reflect(float3 wo, float3 n)
{
    return n * (2.0f * gc_dot(n, wo)) - wo;
}

/* The secondary rays a surface spawns. A zero weight means "no such ray". */
GC_STRUCT(GcWhittedSpecular) {
    float3 reflect_dir;
    float3 reflect_weight;
    float3 refract_dir;
    float3 refract_weight;
} GC_STRUCT_END(GcWhittedSpecular)

/* GC_MAT_MIRROR: perfect reflection weighted by Ks (no Fresnel, as the MTL convention and the
 * references have it). GC_MAT_DIELECTRIC: reflection weighted by the exact Fresnel
 * reflectance R and refraction (Snell, index ior = emission.w inside, 1 outside; ns points
 * outside) weighted by (1 - R) / eta^2 — the 1/eta^2 is radiance compression across the
 * interface, as in gc_bsdf.h and Mitsuba, so closed objects (in then out) are unaffected;
 * total internal reflection sends everything into the reflection. Others: nothing. */
GC_FUNC GcWhittedSpecular gc_whitted_specular(GcMaterial m, float3 ns, float3 wo)
{
    GcWhittedSpecular s;
    float3 zero = make_float3(0.0f, 0.0f, 0.0f);
    s.reflect_dir = gc_whitted_reflect(wo, ns);
    s.reflect_weight = zero;
    s.refract_dir = -wo;
    s.refract_weight = zero;
    if (m.type == GC_MAT_MIRROR) {
        s.reflect_weight = GC_XYZ(m.specular);
        return s;
    }
    if (m.type != GC_MAT_DIELECTRIC) return s;

    float cos_o = gc_dot(ns, wo);
    /* n: the normal on wo's side; eta = n_transmitted / n_incident. */
    float3 n = cos_o >= 0.0f ? ns : -ns;
    float cos_i = fabs(cos_o);
    if (!(cos_i > 0.0f)) return s;
    float ior = m.emission.w > 0.0f ? m.emission.w : 1.0f;
    float eta = cos_o >= 0.0f ? ior : 1.0f / ior;
    float fr = gc_fresnel_dielectric(cos_i, eta);
    float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);
    float cos_t = sqrt(fmax(0.0f, 1.0f - sin2_t));
    if (fr >= 1.0f || !(cos_t > 0.0f)) {
        s.reflect_weight = make_float3(1.0f, 1.0f, 1.0f);
        return s;
    }
    s.reflect_weight = make_float3(fr, fr, fr);
    float t = (1.0f - fr) / (eta * eta);
    s.refract_weight = make_float3(t, t, t);
    s.refract_dir = gc_normalize(wo * (-1.0f / eta) + n * (cos_i / eta - cos_t));
    return s;
}

GC_NAMESPACE_END

#endif /* GC_WHITTED_H */
