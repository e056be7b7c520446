/*
 * gc_path_vertex.h — one vertex of the path integrator: emission seen by the incoming ray
 * (MIS-weighted against next-event estimation), one shadow ray towards an emitter chosen by
 * power, then Russian roulette and the next BSDF-sampled ray. The OpenCL wavefront
 * (kernels/shade.cl) and the Vulkan compute reference (kernels/vk/path.comp) both call
 * gc_shade_vertex, so the two make the same sampling decisions from the same random numbers
 * by construction, not by keeping two copies in sync.
 *
 * The pieces it strings together in the integrator's order live beside it: the material at
 * the hit, textures folded in, and the glTF alpha BLEND decision (gc_material_eval.h); the
 * light sample for next-event estimation and the radiance of an escaped path
 * (gc_light_sample.h); the BSDF (gc_bsdf.h). BLEND is applied here as a pass-through (see
 * gc_shade_vertex); alpha MASK never reaches this code: the traversal drops cut-away hits
 * (gc_alpha.h), so a MASK hit that is shaded is solid.
 *
 * Depth follows Mitsuba's convention: path.depth counts the segments traced so far, so the
 * camera ray's hit is shaded at depth 1, emission is counted up to max_depth segments, and
 * a vertex at depth d may add segment d + 1 (a shadow ray or a continuation) only when
 * d < max_depth. A path starts with throughput (1, 1, 1, 0), radiance (0, 0, 0, 1), depth 0 and
 * GC_PATH_SPECULAR (a camera ray sees emitters with full weight).
 *
 * Scene buffers come in as the scene-buffer group shade (gc_scene_buffers.h): GC_SHADE_PARAMS
 * / GC_SHADE_ARGS, read through GC_ATTRIB(i), GC_MATERIAL(i), GC_TEXTURE(i) and the texel,
 * emitter and light accessors; GC_SHADE_UNUSED() marks them all used in helpers that read
 * only some. The Vulkan reference reads its SSBOs instead (kernels/vk/scene_bindings.glsl).
 */
#ifndef GC_PATH_VERTEX_H
#define GC_PATH_VERTEX_H

#include "gc_bsdf.h"
#include "gc_frame.h"
#include "gc_light_sample.h"
#include "gc_material_eval.h"
#include "gc_path.h"
#include "gc_rng.h"
#include "gc_scene_buffers.h"
#include "gc_shading.h"
#include "gc_spawn.h"

/* GcVertexResult.flags */
#define GC_VERTEX_CONTINUE 1u /* `next` is the path's next ray */
#define GC_VERTEX_SHADOW 2u   /* `shadow` must be traced; if unoccluded add its contribution */

GC_NAMESPACE_BEGIN

/* What shading one vertex produces. Register-only (never stored in a buffer). */
GC_STRUCT(GcVertexResult) {
    GcPathState path;   /* depth advanced; radiance without the shadow ray's contribution */
    GcRay next;
    GcShadowRay shadow; /* slot is left 0: the caller owns slots */
    uint flags;         /* GC_VERTEX_* */
} GC_STRUCT_END(GcVertexResult)

/* v with a w component (the path state's packed float4s). */
GC_FUNC float4 gc_with_w(float3 v, float w) { return make_float4(v.x, v.y, v.z, w); }

/* The MIS weight of emission that `path`'s last segment hit at distance t with cos_out to the
 * emitter's geometric normal, against next-event estimation of the same point. Shared with
 * the adjoint (gc_path_adjoint.h), which must weight exactly as the primal did. */
GC_FUNC float gc_emission_mis_weight(GcRenderParams params, GcPathState path, GcMaterial m, float t, float cos_out)
{
    if ((path.flags & GC_PATH_SPECULAR) != 0u || params.num_emitters == 0u) return 1.0f;
    return gc_power_heuristic(path.throughput.w,
                              gc_light_group_pmf(params) * gc_light_pdf_w(GC_XYZ(m.emission), params.emitter_power, t, cos_out));
}

/* Next-event estimation's MIS weight for the light sample ls seen in local direction wi. A
 * point light is a delta: no BSDF sample can reach it, so no MIS. */
GC_FUNC float gc_nee_mis_weight(GcLightSample ls, GcMaterial m, float3 albedo, float3 wo, float3 wi)
{
    return ls.kind == GC_LIGHT_POINT ? 1.0f : gc_power_heuristic(ls.pdf_w, gc_bsdf_pdf(m, albedo, wo, wi));
}

/* A result that ends the path with nothing added: no next ray, no shadow ray. */
GC_FUNC GcVertexResult gc_vertex_result_none(GcRay ray)
{
    GcVertexResult res;
    res.flags = 0u;
    res.next = ray;
    res.shadow.ray = ray;
    res.shadow.contribution = make_float4(0.0f, 0.0f, 0.0f, 0.0f);
    res.shadow.slot = 0u;
    res.shadow.pad0 = 0u;
    res.shadow.pad1 = 0u;
    res.shadow.pad2 = 0u;
    return res;
}

/* The vertex of a path whose last segment, `ray`, left the scene: the environment's radiance. */
GC_FUNC GcVertexResult gc_shade_escape(GC_SHADE_PARAMS, GcRenderParams params, GcPathState path, GcRay ray)
{
    GcVertexResult res = gc_vertex_result_none(ray);
    path.depth += 1u;
    const float3 L = GC_XYZ(path.radiance) +
                     GC_XYZ(path.throughput) * gc_escaped_radiance(GC_SHADE_ARGS, params, path, GC_XYZ(ray.dir_tmax));
    path.radiance = gc_with_w(L, path.radiance.w);
    res.path = path;
    return res;
}

/* The vertex where `ray` hit a surface (hit.prim valid) whose attributes are `tri`, in the
 * ray's space: the scene's own for a flat scene (gc_shade_vertex), an instance's taken to
 * world space for an instanced one (gc_instance_attribs.h). */
GC_FUNC GcVertexResult gc_shade_surface(GC_SHADE_PARAMS, GcRenderParams params, GcPathState path, GcRay ray, GcHit hit,
                                        GcTriangleAttribs tri)
{
    GcVertexResult res = gc_vertex_result_none(ray);
    path.depth += 1u;
    const uint bounce = path.depth - 1u;
    float3 beta = GC_XYZ(path.throughput);
    float3 L = GC_XYZ(path.radiance);
    const float3 wo_world = -GC_XYZ(ray.dir_tmax);

    /* The vertex's light and BSDF numbers, drawn first although they are used last. pcg4d is
     * a chain of dependent multiplies; issued here, the two chains run alongside each other
     * and alongside the loads and the surface interpolation below, instead of each stalling
     * the code that waits for it. Same numbers, same bits; at max depth both go unused, and the
     * light numbers where next-event estimation is skipped (a delta BSDF, no light). Figures:
     * docs/decisions/random-numbers.md. */
    const float4 r_light = gc_sample4(params, path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_LIGHT));
    const float4 r_bsdf = gc_sample4(params, path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_BSDF));
    const GcSurface s = gc_surface_at(tri, ray, hit);
    GcMaterial m = gc_shade_material(GC_SHADE_ARGS, GC_MATERIAL(s.material), s.uv);
    const float4 base = gc_shade_base_color(GC_SHADE_ARGS, m, s.uv);

    /* KHR_materials_volume, Beer-Lambert: a segment that ran inside a volume mesh ends on that
     * mesh's far side (closed, not nested), so this hit's material holds the medium's sigma_a
     * and hit.t is the length travelled through it. */
    if (GC_USE_VOLUME != 0 && (path.flags & GC_PATH_IN_VOLUME) != 0u && (m.flags & GC_MATF_VOLUME) != 0u) {
        /* e^-x as 2^(-x / ln 2): gc_exp2 gives the same bits on every device (exp does not). */
        const float k = -1.44269504f * hit.t;
        beta = beta * make_float3(gc_exp2(k * m.absorption_r), gc_exp2(k * m.absorption_g), gc_exp2(k * m.absorption_b));
        path.throughput = gc_with_w(beta, path.throughput.w);
    }

    /* Stochastic transparency (glTF BLEND), at the shading level: a transparent hit
     * continues the ray unchanged through the surface (throughput kept, no emission, no
     * light sample). The pass counts as a path segment, as a null interaction does in
     * Mitsuba 3's path integrator: the wavefront host runs max_depth extend/shade rounds,
     * and the Vulkan reference must make the same decisions. BLEND's number comes from this
     * bounce's own block (GC_RNG_BLOCK_EXTRA). Shadow rays treat BLEND surfaces as opaque
     * (only MASK is tested in traversal, see gc_alpha.h), so next-event estimation cannot
     * reach a light through them; the continued path is therefore flagged specular, which
     * gives its emitter or environment hit full weight instead of an MIS weight whose
     * complement NEE never supplies: unbiased, only noisier behind BLEND surfaces. MASK
     * cut-outs cost no segment and are seen through by shadow rays. */
    if (GC_USE_ALPHA_BLEND != 0 && (m.flags & GC_MATF_ALPHA_BLEND) != 0u) {
        const float4 ra = gc_sample4(params, path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_EXTRA));
        if (gc_alpha_transparent(m, base.w, ra.x)) {
            path.radiance = gc_with_w(L, path.radiance.w);
            if (path.depth < params.max_depth) {
                const float3 d = -wo_world;
                res.next = gc_make_ray(gc_offset_ray_origin(s.p, gc_side_normal(s.ng, d), s.spawn_scale), d, 0.0f, GC_RAY_UNBOUNDED);
                path.flags = GC_PATH_SPECULAR | (path.flags & GC_PATH_IN_VOLUME);
                res.flags = GC_VERTEX_CONTINUE;
            }
            res.path = path;
            return res;
        }
    }

    /* Emission seen by this ray. */
    const float3 Le = gc_shade_emission(GC_SHADE_ARGS, m, s.uv);
    const float cos_out = gc_dot(s.ng, wo_world);
    if ((Le.x > 0.0f || Le.y > 0.0f || Le.z > 0.0f) && gc_emits_toward(m, cos_out)) {
        L += beta * Le * gc_emission_mis_weight(params, path, m, hit.t, cos_out);
    }
    if (path.depth >= params.max_depth) {
        path.radiance = gc_with_w(L, path.radiance.w);
        res.path = path;
        return res;
    }

    const float3 albedo = GC_XYZ(base);
    const GcFrame frame =
        gc_frame_from_normal(gc_shade_normal(GC_SHADE_ARGS, m, tri, make_float2(hit.u, hit.v), s.ns, s.uv));
    m = gc_with_coat_normal(GC_SHADE_ARGS, m, tri, make_float2(hit.u, hit.v), s.ns, s.uv, frame);
    const float3 wo = gc_frame_to_local(frame, wo_world);

    /* Next-event estimation: one point on one light (gc_sample_light). */
    if (gc_light_group_pmf(params) > 0.0f && !gc_bsdf_is_delta(m)) {
        const GcLightSample ls = gc_sample_light(GC_SHADE_ARGS, params, s.p, r_light);
        if (ls.kind != GC_LIGHT_NONE && ls.pdf_w > 0.0f) {
            const float3 wi = gc_frame_to_local(frame, ls.wi);
            const float3 f = gc_bsdf_eval(m, albedo, wo, wi);
            const float w = gc_nee_mis_weight(ls, m, albedo, wo, wi);
            const float3 contribution = beta * f * (fabs(wi.z) * w / ls.pdf_w) * ls.radiance;
            if (contribution.x > 0.0f || contribution.y > 0.0f || contribution.z > 0.0f) {
                const float3 origin = gc_offset_ray_origin(s.p, gc_side_normal(s.ng, ls.wi), s.spawn_scale);
                if (ls.kind == GC_LIGHT_ENV) {
                    res.shadow.ray = gc_make_ray(origin, ls.wi, 0.0f, GC_RAY_UNBOUNDED);
                } else {
                    const float3 d = ls.target - origin;
                    const float len = gc_length(d);
                    res.shadow.ray = gc_make_ray(origin, d / len, 0.0f, len);
                }
                res.shadow.contribution = gc_with_w(contribution, 0.0f);
                res.flags |= GC_VERTEX_SHADOW;
            }
        }
    }

    /* Continue the path by sampling the BSDF. */
    const GcBsdfSample bs = gc_bsdf_sample(m, albedo, wo, r_bsdf.x, r_bsdf.y, r_bsdf.z);
    beta *= bs.weight;
    /* Refraction scales radiance by 1/eta^2 (gc_bsdf.h); eta_scale undoes that for Russian
     * roulette only, so a path inside glass is not killed for a factor that leaving the glass
     * will restore (Mitsuba's path integrator and pbrt-v4 do the same). */
    float eta_scale = path.radiance.w;
    if ((bs.flags & GC_BSDF_TRANSMISSION) != 0u && gc_material_is(m, GC_MAT_DIELECTRIC)) {
        const float eta = gc_dielectric_eta(m, wo);
        eta_scale *= eta * eta;
    } else if ((bs.flags & GC_BSDF_TRANSMISSION) != 0u && (bs.flags & GC_BSDF_SPECULAR) == 0u &&
               gc_material_is(m, GC_MAT_PBR) && gc_pbr_rough_transmission(m)) {
        const float eta = gc_pbr_transmission_eta(m, gc_bsdf_side(wo));
        eta_scale *= eta * eta;
    }
    bool alive = bs.flags != 0u && (beta.x > 0.0f || beta.y > 0.0f || beta.z > 0.0f);
    if (alive && path.depth >= params.rr_depth) {
        /* Russian roulette on the throughput's largest channel, capped so bright paths
         * still end sometimes (as Mitsuba's path integrator does). */
        const float survive = fmin(fmax(beta.x, fmax(beta.y, beta.z)) * eta_scale, 0.95f);
        const float4 rr = gc_sample4(params, path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_ROULETTE));
        if (rr.x >= survive) alive = false;
        else beta = beta / survive;
    }
    path.radiance = gc_with_w(L, eta_scale);
    if (!alive) {
        res.path = path;
        return res;
    }
    const float3 wi_world = gc_frame_to_world(frame, bs.wi);
    res.next = gc_make_ray(gc_offset_ray_origin(s.p, gc_side_normal(s.ng, wi_world), s.spawn_scale), wi_world, 0.0f, GC_RAY_UNBOUNDED);
    path.throughput = gc_with_w(beta, bs.pdf_w);
    /* Inside a volume after refracting in against the outward geometric normal; out after
     * refracting out; a reflection stays on its side. */
    uint in_volume = path.flags & GC_PATH_IN_VOLUME;
    if (GC_USE_VOLUME != 0 && (m.flags & GC_MATF_VOLUME) != 0u && (bs.flags & GC_BSDF_TRANSMISSION) != 0u)
        in_volume = gc_dot(wi_world, s.ng) < 0.0f ? GC_PATH_IN_VOLUME : 0u;
    path.flags = ((bs.flags & GC_BSDF_SPECULAR) != 0u ? GC_PATH_SPECULAR : 0u) | in_volume;
    res.path = path;
    res.flags |= GC_VERTEX_CONTINUE;
    return res;
}

/* Shades the vertex where `ray` (the path's last segment) ended with `hit`, in a flat scene. */
GC_FUNC GcVertexResult gc_shade_vertex(GC_SHADE_PARAMS, GcRenderParams params, GcPathState path, GcRay ray, GcHit hit)
{
    if (hit.prim == GC_INVALID) return gc_shade_escape(GC_SHADE_ARGS, params, path, ray);
    return gc_shade_surface(GC_SHADE_ARGS, params, path, ray, hit, GC_ATTRIB(hit.prim));
}

GC_NAMESPACE_END

#endif /* GC_PATH_VERTEX_H */
