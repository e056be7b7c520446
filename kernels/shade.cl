/*
 * shade.cl — one path vertex: emission (MIS-weighted against next-event estimation), a
 * shadow ray towards a sampled emitter, Russian roulette, and the next BSDF-sampled ray.
 *
 * Depth follows Mitsuba's convention: path.depth counts the segments traced so far, so the
 * camera ray's hit is shaded at depth 1, emission is counted up to max_depth segments, and
 * a vertex at depth d may add segment d + 1 (a shadow ray or a continuation) only when
 * d < max_depth.
 */
#include "gc_bsdf.h"
#include "gc_frame.h"
#include "gc_path.h"
#include "gc_rng.h"
#include "gc_shading.h"
#include "gc_texture.h"

static float3 gc_shade_albedo(GC_TEXELS_PARAM, __global const GcTexture* textures, GcMaterial m, float2 uv)
{
    float3 albedo = m.albedo.xyz;
    if (m.albedo_texture != GC_INVALID)
        albedo *= gc_texture_sample(GC_TEXELS_ARG, textures[m.albedo_texture], uv.x, uv.y).xyz;
    return albedo;
}

/* The geometric normal on the side that direction w leaves into. */
static float3 gc_side_normal(float3 ng, float3 w) { return dot(ng, w) >= 0.0f ? ng : -ng; }

__kernel void shade(const GcRenderParams params,
                    __global const GcTriangleAttribs* attribs,
                    __global const GcMaterial* materials,
                    __global const GcTexture* textures,
                    __global const uint* texels,
                    __global const GcEmitter* emitters,
                    __global GcRay* rays,
                    __global const GcHit* hits,
                    __global GcPathState* paths,
                    __global const uint* queue_in,
                    __global uint* queue_out,
                    __global GcShadowRay* shadow_rays,
                    __global uint* counters,
                    const uint counter_in,
                    const uint counter_out)
{
    const uint q = get_global_id(0);
    if (q >= counters[counter_in] || q >= params.pixel_count) return;
    const uint slot = queue_in[q];
    GcPathState path = paths[slot];
    const GcRay ray = rays[slot];
    const GcHit hit = hits[slot];
    path.depth += 1u;
    const uint bounce = path.depth - 1u;
    float3 beta = path.throughput.xyz;
    float3 L = path.radiance.xyz;
    const float3 wo_world = -ray.dir_tmax.xyz;

    if (hit.prim == GC_INVALID) {
        paths[slot].radiance.xyz = L + beta * params.env_radiance.xyz;
        return;
    }

    const GcSurface s = gc_surface_at(attribs[hit.prim], ray, hit);
    const GcMaterial m = materials[s.material];

    /* Emission seen by this ray. */
    const float3 Le = m.emission.xyz;
    const float cos_out = dot(s.ng, wo_world);
    if ((Le.x > 0.0f || Le.y > 0.0f || Le.z > 0.0f) && gc_emits_toward(m, cos_out)) {
        float w = 1.0f;
        if ((path.flags & GC_PATH_SPECULAR) == 0u && params.num_emitters > 0u)
            w = gc_power_heuristic(path.throughput.w, gc_light_pdf_w(Le, params.emitter_power, hit.t, cos_out));
        L += beta * Le * w;
    }
    if (path.depth >= params.max_depth) {
        paths[slot].radiance.xyz = L;
        return;
    }

    const float3 albedo = gc_shade_albedo(texels, textures, m, s.uv);
    const GcFrame frame = gc_frame_from_normal(s.ns);
    const float3 wo = gc_frame_to_local(frame, wo_world);

    /* Next-event estimation: one point on one emitter, chosen by power. */
    if (params.num_emitters > 0u && !gc_bsdf_is_delta(m)) {
        const float4 r = gc_rand4(path.pixel, params.sample_index, gc_rng_block(bounce, GC_RNG_BLOCK_LIGHT), params.seed);
        const GcEmitter e = emitters[gc_pick_emitter(emitters, params.num_emitters, r.x)];
        const float3 b = gc_sample_uniform_triangle(r.y, r.z);
        const float3 p_light = b.x * e.v0.xyz + b.y * e.v1.xyz + b.z * e.v2.xyz;
        const GcTriangleAttribs la = attribs[e.triangle];
        const GcMaterial lm = materials[la.material];
        const float3 to_light = p_light - s.p;
        const float dist = length(to_light);
        if (dist > 0.0f) {
            const float3 wi_world = to_light / dist;
            const float cos_light = dot(la.ng.xyz, -wi_world);
            if (gc_emits_toward(lm, cos_light)) {
                const float3 wi = gc_frame_to_local(frame, wi_world);
                const float3 f = gc_bsdf_eval(m, albedo, wo, wi);
                const float pdf_light = gc_light_pdf_w(lm.emission.xyz, params.emitter_power, dist, cos_light);
                const float w = gc_power_heuristic(pdf_light, gc_bsdf_pdf(m, albedo, wo, wi));
                const float3 contribution = beta * f * (fabs(wi.z) * w / pdf_light) * lm.emission.xyz;
                if (pdf_light > 0.0f && (contribution.x > 0.0f || contribution.y > 0.0f || contribution.z > 0.0f)) {
                    const float3 origin = gc_offset_ray_origin(s.p, gc_side_normal(s.ng, wi_world));
                    const float3 target = gc_offset_ray_origin(p_light, gc_side_normal(la.ng.xyz, -wi_world));
                    const float3 d = target - origin;
                    const float len = length(d);
                    GcShadowRay sr;
                    sr.ray = gc_make_ray(origin, d / len, 0.0f, len);
                    sr.contribution = (float4)(contribution, 0.0f);
                    sr.slot = slot;
                    sr.pad0 = 0u;
                    sr.pad1 = 0u;
                    sr.pad2 = 0u;
                    shadow_rays[atomic_inc(&counters[GC_COUNTER_SHADOW])] = sr;
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
    path.radiance = (float4)(L, 0.0f);
    if (!alive) {
        paths[slot] = path;
        return;
    }
    const float3 wi_world = gc_frame_to_world(frame, bs.wi);
    rays[slot] = gc_make_ray(gc_offset_ray_origin(s.p, gc_side_normal(s.ng, wi_world)), wi_world, 0.0f, GC_FLOAT_MAX);
    path.throughput = (float4)(beta, bs.pdf_w);
    path.flags = (bs.flags & GC_BSDF_SPECULAR) != 0u ? GC_PATH_SPECULAR : 0u;
    paths[slot] = path;
    queue_out[atomic_inc(&counters[counter_out])] = slot;
}
