/*
 * gc_path_vertex.h — one vertex of the path integrator: emission seen by the incoming ray
 * (MIS-weighted against next-event estimation), one shadow ray towards an emitter chosen by
 * power, then Russian roulette and the next BSDF-sampled ray. The OpenCL wavefront
 * (kernels/shade.cl) and the Vulkan compute reference (kernels/vk/path.comp) both call
 * gc_shade_vertex, so the two make the same sampling decisions from the same random numbers
 * by construction, not by keeping two copies in sync.
 *
 * Depth follows Mitsuba's convention: path.depth counts the segments traced so far, so the
 * camera ray's hit is shaded at depth 1, emission is counted up to max_depth segments, and
 * a vertex at depth d may add segment d + 1 (a shadow ray or a continuation) only when
 * d < max_depth. A path starts with throughput (1, 1, 1, 0), radiance 0, depth 0 and
 * GC_PATH_SPECULAR (a camera ray sees emitters with full weight).
 *
 * Scene buffers come in through macros, as in gc_traverse.h. Defaults (OpenCL C and C++):
 *     GC_SHADE_PARAMS  attribs, materials, textures pointers, then GC_TEXELS_PARAM, GC_EMITTERS_PARAM
 *     GC_SHADE_ARGS    attribs, materials, textures, GC_TEXELS_ARG, GC_EMITTERS_ARG
 *     GC_ATTRIB(i), GC_MATERIAL(i), GC_TEXTURE(i)
 *     GC_SHADE_UNUSED()  a statement marking all of them used (empty in GLSL)
 * GLSL declares SSBOs and defines all of them (and those of gc_texture.h / gc_path.h) first;
 * see kernels/vk/scene_bindings.glsl.
 */
#ifndef GC_PATH_VERTEX_H
#define GC_PATH_VERTEX_H

#include "gc_bsdf.h"
#include "gc_frame.h"
#include "gc_path.h"
#include "gc_rng.h"
#include "gc_shading.h"
#include "gc_texture.h"

#ifndef GC_SHADE_PARAMS
#define GC_SHADE_PARAMS                                                                           \
    GC_GLOBAL const GcTriangleAttribs *attribs, GC_GLOBAL const GcMaterial *materials,            \
        GC_GLOBAL const GcTexture *textures, GC_TEXELS_PARAM, GC_EMITTERS_PARAM
#define GC_SHADE_ARGS attribs, materials, textures, GC_TEXELS_ARG, GC_EMITTERS_ARG
#define GC_ATTRIB(i) attribs[i]
#define GC_MATERIAL(i) materials[i]
#define GC_TEXTURE(i) textures[i]
/* For functions that read only some of the buffers (C++ warns about unused parameters). */
#define GC_SHADE_UNUSED() ((void)attribs, (void)materials, (void)textures, (void)GC_TEXELS_ARG, (void)GC_EMITTERS_ARG)
#endif
#ifndef GC_SHADE_UNUSED
#define GC_SHADE_UNUSED()
#endif

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

/* Diffuse reflectance at uv: the material's albedo times its texture, if any. */
GC_FUNC float3 gc_shade_albedo(GC_SHADE_PARAMS, GcMaterial m, float2 uv)
{
    GC_SHADE_UNUSED();
    float3 albedo = GC_XYZ(m.albedo);
    if (m.albedo_texture != GC_INVALID)
        albedo *= GC_XYZ(gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.albedo_texture), uv.x, uv.y));
    return albedo;
}

/* The geometric normal on the side that direction w leaves into. */
GC_FUNC float3 gc_side_normal(float3 ng, float3 w) { return dot(ng, w) >= 0.0f ? ng : -ng; }

GC_FUNC float4 gc_with_w(float3 v, float w) { return make_float4(v.x, v.y, v.z, w); }

/* Shades the vertex where `ray` (the path's last segment) ended with `hit`. */
GC_FUNC GcVertexResult gc_shade_vertex(GC_SHADE_PARAMS, GcRenderParams params, GcPathState path, GcRay ray, GcHit hit)
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

    path.depth += 1u;
    const uint bounce = path.depth - 1u;
    float3 beta = GC_XYZ(path.throughput);
    float3 L = GC_XYZ(path.radiance);
    const float3 wo_world = -GC_XYZ(ray.dir_tmax);

    if (hit.prim == GC_INVALID) {
        path.radiance = gc_with_w(L + beta * GC_XYZ(params.env_radiance), path.radiance.w);
        res.path = path;
        return res;
    }

    const GcSurface s = gc_surface_at(GC_ATTRIB(hit.prim), ray, hit);
    const GcMaterial m = GC_MATERIAL(s.material);

    /* Emission seen by this ray. */
    const float3 Le = GC_XYZ(m.emission);
    const float cos_out = dot(s.ng, wo_world);
    if ((Le.x > 0.0f || Le.y > 0.0f || Le.z > 0.0f) && gc_emits_toward(m, cos_out)) {
        float w = 1.0f;
        if ((path.flags & GC_PATH_SPECULAR) == 0u && params.num_emitters > 0u)
            w = gc_power_heuristic(path.throughput.w, gc_light_pdf_w(Le, params.emitter_power, hit.t, cos_out));
        L += beta * Le * w;
    }
    if (path.depth >= params.max_depth) {
        path.radiance = gc_with_w(L, path.radiance.w);
        res.path = path;
        return res;
    }

    const float3 albedo = gc_shade_albedo(GC_SHADE_ARGS, m, s.uv);
    const GcFrame frame = gc_frame_from_normal(s.ns);
    const float3 wo = gc_frame_to_local(frame, wo_world);

    /* Next-event estimation: one point on one emitter, chosen by power. */
    if (params.num_emitters > 0u && !gc_bsdf_is_delta(m)) {
        const float4 r = gc_rand4(path.pixel, params.sample_index, gc_rng_block(bounce, GC_RNG_BLOCK_LIGHT), params.seed);
        const GcEmitter e = GC_EMITTER(gc_pick_emitter(GC_EMITTERS_ARG, params.num_emitters, r.x));
        const float3 b = gc_sample_uniform_triangle(r.y, r.z);
        const float3 p_light = b.x * GC_XYZ(e.v0) + b.y * GC_XYZ(e.v1) + b.z * GC_XYZ(e.v2);
        const GcTriangleAttribs la = GC_ATTRIB(e.triangle);
        const GcMaterial lm = GC_MATERIAL(la.material);
        const float3 to_light = p_light - s.p;
        const float dist = length(to_light);
        if (dist > 0.0f) {
            const float3 wi_world = to_light / dist;
            const float cos_light = dot(GC_XYZ(la.ng), -wi_world);
            if (gc_emits_toward(lm, cos_light)) {
                const float3 wi = gc_frame_to_local(frame, wi_world);
                const float3 f = gc_bsdf_eval(m, albedo, wo, wi);
                const float pdf_light = gc_light_pdf_w(GC_XYZ(lm.emission), params.emitter_power, dist, cos_light);
                const float w = gc_power_heuristic(pdf_light, gc_bsdf_pdf(m, albedo, wo, wi));
                const float3 contribution = beta * f * (fabs(wi.z) * w / pdf_light) * GC_XYZ(lm.emission);
                if (pdf_light > 0.0f && (contribution.x > 0.0f || contribution.y > 0.0f || contribution.z > 0.0f)) {
                    const float3 origin = gc_offset_ray_origin(s.p, gc_side_normal(s.ng, wi_world));
                    const float3 target = gc_offset_ray_origin(p_light, gc_side_normal(GC_XYZ(la.ng), -wi_world));
                    const float3 d = target - origin;
                    const float len = length(d);
                    res.shadow.ray = gc_make_ray(origin, d / len, 0.0f, len);
                    res.shadow.contribution = gc_with_w(contribution, 0.0f);
                    res.flags |= GC_VERTEX_SHADOW;
                }
            }
        }
    }

    /* Continue the path by sampling the BSDF. */
    const float4 r = gc_rand4(path.pixel, params.sample_index, gc_rng_block(bounce, GC_RNG_BLOCK_BSDF), params.seed);
    const GcBsdfSample bs = gc_bsdf_sample(m, albedo, wo, r.x, r.y, r.z);
    beta *= bs.weight;
    bool alive = bs.flags != 0u && (beta.x > 0.0f || beta.y > 0.0f || beta.z > 0.0f);
    if (alive && path.depth >= params.rr_depth) {
        /* Russian roulette on the throughput's largest channel, capped so bright paths
         * still end sometimes (as Mitsuba's path integrator does). */
        const float survive = fmin(fmax(beta.x, fmax(beta.y, beta.z)), 0.95f);
        const float4 rr = gc_rand4(path.pixel, params.sample_index, gc_rng_block(bounce, GC_RNG_BLOCK_ROULETTE), params.seed);
        if (rr.x >= survive) alive = false;
        else beta = beta / survive;
    }
    path.radiance = gc_with_w(L, 0.0f);
    if (!alive) {
        res.path = path;
        return res;
    }
    const float3 wi_world = gc_frame_to_world(frame, bs.wi);
    res.next = gc_make_ray(gc_offset_ray_origin(s.p, gc_side_normal(s.ng, wi_world)), wi_world, 0.0f, GC_FLOAT_MAX);
    path.throughput = gc_with_w(beta, bs.pdf_w);
    path.flags = (bs.flags & GC_BSDF_SPECULAR) != 0u ? GC_PATH_SPECULAR : 0u;
    res.path = path;
    res.flags |= GC_VERTEX_CONTINUE;
    return res;
}

GC_NAMESPACE_END

#endif /* GC_PATH_VERTEX_H */
