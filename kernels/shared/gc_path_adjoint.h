/*
 * gc_path_adjoint.h — one vertex of the path integrator's adjoint (path replay
 * backpropagation; Vicini, Speierer & Jakob 2021). kernels/adjoint.cl replays each path with
 * the primal's random numbers through gc_shade_vertex itself, so it makes the same decisions;
 * at each vertex this adds, to the parameters' slots (gc_grad_slots.h), the derivative of what
 * the vertex contributes to the sample's radiance, times the loss's derivative `delta` with
 * respect to that radiance:
 *     emission seen by the incoming ray   beta * w * Le                   (d / d emission)
 *     next-event estimation               beta * f * |cos| w / pdf * Li   (d / d f's parameters, d / d the light's emission)
 *     the BSDF sample                     weight * L_rem                   (d / d f's parameters)
 * where L_rem is the radiance the rest of the path brought (the sample's total minus what the
 * path had gathered up to and including this vertex), so d(weight * L_rem) = L_rem * df / f.
 * f's parameters: the albedo (base colour, its texels), Phong's Ks and exponent, the mirror's
 * reflectance, glTF metallic and roughness (gc_bsdf_grad.h).
 * Sampling densities, MIS weights and Russian roulette are held fixed, as the primal drew
 * them: the estimate of the derivative stays unbiased, and no vertex is stored, so memory does
 * not grow with depth.
 *
 * What is not differentiated: the alpha of glTF BLEND, transmission, normal maps, and the
 * emission of a material that emits nothing (it is no light for next-event estimation).
 *
 * OpenCL C only (atomics).
 */
#ifndef GC_PATH_ADJOINT_H
#define GC_PATH_ADJOINT_H

#include "gc_bsdf_grad.h"
#include "gc_grad_slots.h"
#include "gc_path_vertex.h"

/* x / y where y is not 0, else 0: a channel the parameter does not reach. */
static inline float3 gc_safe_div3(float3 x, float3 y)
{
    return (float3)(y.x != 0.0f ? x.x / y.x : 0.0f, y.y != 0.0f ? x.y / y.y : 0.0f, y.z != 0.0f ? x.z / y.z : 0.0f);
}

/* The texture factor of a material slot at uv: 1 without a texture. */
static inline float3 gc_texture_factor(GC_SHADE_PARAMS, uint texture, float2 uv)
{
    GC_SHADE_UNUSED();
    if (GC_USE_TEXTURES == 0 || texture == GC_INVALID) return (float3)(1.0f);
    return GC_XYZ(gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(texture), uv.x, uv.y));
}

/* Adds the gradient g (per channel, with respect to the texture's value at the lookup) to the
 * texels the lookup at uv read through `view`, by their bilinear weights, if the view's
 * texels are asked for. The gradient is with respect to the linear (decoded) texel values. */
static inline void gc_scatter_texels(GC_SHADE_PARAMS, GcGradTarget g, uint view, float2 uv, float3 grad)
{
    GC_SHADE_UNUSED();
    if (GC_USE_TEXTURES == 0 || view == GC_INVALID) return;
    if (view >= g.view_count) {
        gc_grad_flag_out_of_range(g);
        return;
    }
    const uint first = g.view_slots[view];
    if (first == GC_INVALID) return;
    const GcTexelFootprint fp = gc_texture_footprint(GC_TEXTURE(view), uv.x, uv.y);
    if (fp.nearest != 0u) {
        gc_grad_add3(g, first + 4u * fp.index.x, grad);
        return;
    }
    const float fx = fp.frac.x;
    const float fy = fp.frac.y;
    gc_grad_add3(g, first + 4u * fp.index.x, grad * ((1.0f - fx) * (1.0f - fy)));
    gc_grad_add3(g, first + 4u * fp.index.y, grad * (fx * (1.0f - fy)));
    gc_grad_add3(g, first + 4u * fp.index.z, grad * ((1.0f - fx) * fy));
    gc_grad_add3(g, first + 4u * fp.index.w, grad * (fx * fy));
}

/* The derivative of the vertex where `ray` (the path's last segment) ended with `hit`. `path`
 * is the state gc_shade_vertex was given, `res` what it returned, `shadow_visible` whether
 * its shadow ray (if any) reached the light, `L_rem` the radiance the path gathers after this
 * vertex, `delta` d loss / d (this sample's radiance). */
static inline void gc_vertex_adjoint(GC_SHADE_PARAMS, GcRenderParams params, GcGradTarget g, GcPathState path,
                                     GcRay ray, GcHit hit, GcVertexResult res, bool shadow_visible, float3 L_rem,
                                     float3 delta)
{
    path.depth += 1u;
    const uint bounce = path.depth - 1u;
    const float3 beta = GC_XYZ(path.throughput);
    const float3 wo_world = -GC_XYZ(ray.dir_tmax);
    const float3 env_scale = GC_XYZ(params.env_radiance);

    if (hit.prim == GC_INVALID) {
        /* The environment's radiance is its constant, or the map's texel times the constant:
         * either way Le / constant, channel by channel. */
        const float3 Le = gc_escaped_radiance(GC_SHADE_ARGS, params, path, -wo_world);
        const float3 dLe = gc_has_env_map(params) ? gc_safe_div3(Le, env_scale) : (float3)(1.0f);
        gc_grad_add3(g, g.env_slot, delta * beta * dLe);
        return;
    }

    const float4 r_light = gc_sample4(params, path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_LIGHT));
    const float4 r_bsdf = gc_sample4(params, path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_BSDF));
    const GcTriangleAttribs tri = GC_ATTRIB(hit.prim);
    const GcSurface s = gc_surface_at(tri, ray, hit);
    GcMaterial m = gc_shade_material(GC_SHADE_ARGS, GC_MATERIAL(s.material), s.uv);
    const float4 base = gc_shade_base_color(GC_SHADE_ARGS, m, s.uv);

    if (GC_USE_ALPHA_BLEND != 0 && (m.flags & GC_MATF_ALPHA_BLEND) != 0u) {
        const float4 ra = gc_sample4(params, path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_EXTRA));
        if (gc_alpha_transparent(m, base.w, ra.x)) return; /* passed through: nothing here depends on a parameter */
    }

    /* Emission: Le = emission factor * texture. */
    const float3 Le = gc_shade_emission(GC_SHADE_ARGS, m, s.uv);
    const float cos_out = gc_dot(s.ng, wo_world);
    if ((Le.x > 0.0f || Le.y > 0.0f || Le.z > 0.0f) && gc_emits_toward(m, cos_out)) {
        const float3 d_le = delta * beta * gc_emission_mis_weight(params, path, m, hit.t, cos_out);
        gc_grad_add3(g, gc_grad_material_slot(s.material, GC_GRAD_FIELD_EMISSION),
                     d_le * gc_texture_factor(GC_SHADE_ARGS, m.emission_texture, s.uv));
        gc_scatter_texels(GC_SHADE_ARGS, g, m.emission_texture, s.uv, d_le * GC_XYZ(m.emission));
    }
    if (path.depth >= params.max_depth) return;

    const float3 albedo = GC_XYZ(base);
    const GcFrame frame =
        gc_frame_from_normal(gc_shade_normal(GC_SHADE_ARGS, m, tri, make_float2(hit.u, hit.v), s.ns, s.uv));
    m = gc_with_coat_normal(GC_SHADE_ARGS, m, tri, make_float2(hit.u, hit.v), s.ns, s.uv, frame);
    const float3 wo = gc_frame_to_local(frame, wo_world);
    /* A vertex's value f enters its two terms as nee * f(wi_light) and bsdf * f(wi_sampled),
     * so d loss / d theta = nee . df(wi_light) + bsdf . df(wi_sampled) for each parameter
     * theta of f: nee = delta * beta * |cos| w / pdf * Li, bsdf = delta * L_rem / f (f's
     * own factor in the sample weight cancels against L_rem's). */
    float3 nee = (float3)(0.0f);
    float3 nee_wi = (float3)(0.0f, 0.0f, 1.0f);
    if ((res.flags & GC_VERTEX_SHADOW) != 0u && shadow_visible) {
        const GcLightSample ls = gc_sample_light(GC_SHADE_ARGS, params, s.p, r_light);
        nee_wi = gc_frame_to_local(frame, ls.wi);
        const float w = gc_nee_mis_weight(ls, m, albedo, wo, nee_wi);
        const float3 k = beta * (fabs(nee_wi.z) * w / ls.pdf_w);
        nee = delta * k * ls.radiance;
        const float3 f = gc_bsdf_eval(m, albedo, wo, nee_wi);
        if (ls.kind == GC_LIGHT_AREA) {
            const GcMaterial lm = GC_MATERIAL(ls.material);
            const float3 d_le = delta * k * f;
            gc_grad_add3(g, gc_grad_material_slot(ls.material, GC_GRAD_FIELD_EMISSION),
                         d_le * gc_texture_factor(GC_SHADE_ARGS, lm.emission_texture, ls.uv));
            gc_scatter_texels(GC_SHADE_ARGS, g, lm.emission_texture, ls.uv, d_le * GC_XYZ(lm.emission));
        } else if (ls.kind == GC_LIGHT_ENV) {
            gc_grad_add3(g, g.env_slot, delta * k * f * gc_safe_div3(ls.radiance, env_scale));
        }
    }
    float3 bsdf = (float3)(0.0f);
    GcBsdfSample bs;
    bs.flags = 0u;
    if ((res.flags & GC_VERTEX_CONTINUE) != 0u) {
        bs = gc_bsdf_sample(m, albedo, wo, r_bsdf.x, r_bsdf.y, r_bsdf.z);
        bsdf = gc_safe_div3(delta * L_rem, bs.f);
    }
    const bool has_nee = nee.x != 0.0f || nee.y != 0.0f || nee.z != 0.0f;
    const bool has_bsdf = bsdf.x != 0.0f || bsdf.y != 0.0f || bsdf.z != 0.0f;
    if (!has_nee && !has_bsdf) return;

    /* d loss / d albedo (the textured base colour). */
    float3 d_albedo = (float3)(0.0f);
    if (has_nee) d_albedo += nee * gc_bsdf_eval_dalbedo(m, wo, nee_wi);
    if (has_bsdf) d_albedo += bsdf * gc_bsdf_sample_f_dalbedo(m, wo, bs);

    /* Phong's Ks and the mirror's reflectance. */
    if (gc_material_is(m, GC_MAT_PHONG) || gc_material_is(m, GC_MAT_MIRROR)) {
        float3 d_spec = (float3)(0.0f);
        if (has_nee) d_spec += nee * gc_bsdf_eval_dspecular(m, albedo, wo, nee_wi);
        if (has_bsdf) d_spec += bsdf * gc_bsdf_sample_f_dspecular(m, albedo, wo, bs);
        gc_grad_add3(g, gc_grad_material_slot(s.material, GC_GRAD_FIELD_SPECULAR), d_spec);
    }
    /* The Phong exponent, and glTF metallic and roughness: the latter are the factors times
     * the metallicRoughness texture (B, G), so d / d factor = texture * d / d effective. */
    const float3 mr = gc_texture_factor(GC_SHADE_ARGS, m.metallic_roughness_texture, s.uv);
    const GcMaterial factors = GC_MATERIAL(s.material);
    float3 d_mr = (float3)(0.0f); /* d loss / d the metallicRoughness texture's (R, G, B) at uv */
    for (uint param = 0u; param < 3u; ++param) {
        if (!gc_bsdf_has_param(m, param)) continue;
        float3 d = (float3)(0.0f);
        if (has_nee) d += nee * gc_bsdf_eval_dparam(m, albedo, wo, nee_wi, param);
        if (has_bsdf) d += bsdf * gc_bsdf_sample_f_dparam(m, albedo, wo, bs, param);
        float sum = d.x + d.y + d.z;
        uint field = GC_GRAD_FIELD_PHONG_EXPONENT;
        if (param == GC_BSDF_PARAM_METALLIC) {
            field = GC_GRAD_FIELD_METALLIC;
            d_mr.z = sum * factors.pbr.x;
            sum *= mr.z;
        } else if (param == GC_BSDF_PARAM_ROUGHNESS) {
            field = GC_GRAD_FIELD_ROUGHNESS;
            d_mr.y = sum * factors.pbr.y;
            sum *= mr.y;
        }
        gc_grad_add(g, gc_grad_material_slot(s.material, field), sum);
    }
    if (gc_material_is(m, GC_MAT_PBR)) gc_scatter_texels(GC_SHADE_ARGS, g, m.metallic_roughness_texture, s.uv, d_mr);

    /* albedo = base colour factor * texture: d / d factor = texture * d / d albedo, and
     * d / d texture = factor * d / d albedo. */
    gc_grad_add3(g, gc_grad_material_slot(s.material, GC_GRAD_FIELD_BASE_COLOR),
                 d_albedo * gc_texture_factor(GC_SHADE_ARGS, m.albedo_texture, s.uv));
    gc_scatter_texels(GC_SHADE_ARGS, g, m.albedo_texture, s.uv, d_albedo * GC_XYZ(m.albedo));
}

#endif /* GC_PATH_ADJOINT_H */
