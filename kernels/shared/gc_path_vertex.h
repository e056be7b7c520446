/*
 * gc_path_vertex.h — one vertex of the path integrator: emission seen by the incoming ray
 * (MIS-weighted against next-event estimation), one shadow ray towards an emitter chosen by
 * power, then Russian roulette and the next BSDF-sampled ray. The OpenCL wavefront
 * (kernels/shade.cl) and the Vulkan compute reference (kernels/vk/path.comp) both call
 * gc_shade_vertex, so the two make the same sampling decisions from the same random numbers
 * by construction, not by keeping two copies in sync.
 *
 * Materials are evaluated here, not in gc_bsdf.h: base colour and alpha, metallicRoughness,
 * normal and emissive textures at the hit's uv (gc_shade_base_color, gc_shade_material,
 * gc_shade_normal, gc_shade_emission), and glTF alpha BLEND as a pass-through (see
 * gc_shade_vertex). alpha MASK never reaches this code: the traversal drops cut-away hits
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
#include "gc_lights.h"
#include "gc_path.h"
#include "gc_spawn.h"
#include "gc_rng.h"
#include "gc_scene_buffers.h"
#include "gc_shading.h"
#include "gc_tangent.h"
#include "gc_texture.h"

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
 * G = roughness, linear), so gc_bsdf.h sees plain numbers. */
GC_FUNC GcMaterial gc_shade_material(GC_SHADE_PARAMS, GcMaterial m, float2 uv)
{
    GC_SHADE_UNUSED();
    if (GC_USE_TEXTURES != 0 && m.metallic_roughness_texture != GC_INVALID) {
        const float4 mr = gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.metallic_roughness_texture), uv.x, uv.y);
        m.pbr.x *= mr.z;
        m.pbr.y *= mr.y;
    }
    return m;
}

/* Shading normal with the material's tangent-space normal map applied, at barycentrics
 * bary = (u, v) of v1 and v2. The tangent is the file's per-vertex one interpolated, else the
 * host's per-triangle one (gc_triangle_tangent); it is re-orthogonalised against the
 * interpolated normal ns here (Gram-Schmidt), B = w * cross(ns, T). A perturbed normal that
 * would face away from ns's side (a texel at the grazing limit) keeps ns. */
GC_FUNC float3 gc_shade_normal(GC_SHADE_PARAMS, GcMaterial m, GcTriangleAttribs a, float2 bary, float3 ns, float2 uv)
{
    GC_SHADE_UNUSED();
    if (GC_USE_NORMAL_MAPS == 0 || m.normal_texture == GC_INVALID) return ns;
    const float4 tangent = gc_triangle_tangent(a, bary.x, bary.y);
    const float3 t_tri = GC_XYZ(tangent);
    const float3 t_raw = t_tri - ns * gc_dot(ns, t_tri);
    const float t_len = gc_length(t_raw);
    if (!(t_len > 1.0e-6f)) return ns;
    const float3 t = t_raw * (1.0f / t_len);
    const float3 b = gc_cross(ns, t) * tangent.w;
    const float4 tex = gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.normal_texture), uv.x, uv.y);
    /* glTF normalTexture.scale multiplies x and y only (then the result is renormalised). */
    const float xy_scale = m.normal_scale;
    const float3 n = t * ((2.0f * tex.x - 1.0f) * xy_scale) + b * ((2.0f * tex.y - 1.0f) * xy_scale) +
                     ns * (2.0f * tex.z - 1.0f);
    const float n_len = gc_length(n);
    if (!(n_len > 1.0e-6f)) return ns;
    const float3 nn = n * (1.0f / n_len);
    return gc_dot(nn, ns) > 0.0f ? nn : ns;
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

/* The geometric normal on the side that direction w leaves into. */
GC_FUNC float3 gc_side_normal(float3 ng, float3 w) { return gc_dot(ng, w) >= 0.0f ? ng : -ng; }

GC_FUNC float4 gc_with_w(float3 v, float w) { return make_float4(v.x, v.y, v.z, w); }

/* Radiance a path gathers when its ray leaves the scene in direction d: the environment,
 * MIS-weighted against environment-map sampling unless the last bounce was specular. */
GC_FUNC float3 gc_escaped_radiance(GC_SHADE_PARAMS, GcRenderParams params, GcPathState path, float3 d)
{
    GC_SHADE_UNUSED();
    const float3 Le = gc_env_radiance(GC_LIGHTS_ARGS, params, d);
    if (!gc_has_env_map(params) || (path.flags & GC_PATH_SPECULAR) != 0u) return Le;
    const float pdf_light = gc_light_group_pmf(params) * gc_env_pdf_w(GC_LIGHTS_ARGS, params, d);
    return Le * gc_power_heuristic(path.throughput.w, pdf_light);
}

/* Next-event estimation's light sample from the shading point p: r.x picks a light group
 * (emitters, point lights, environment map, in that order, uniformly among those present)
 * and, rescaled, the light within it; r.y, r.z pick the point on it. */
GC_FUNC GcLightSample gc_sample_light(GC_SHADE_PARAMS, GcRenderParams params, float3 p, float4 r)
{
    GC_SHADE_UNUSED();
    GcLightSample ls;
    ls.wi = make_float3(0.0f, 0.0f, 1.0f);
    ls.radiance = make_float3(0.0f, 0.0f, 0.0f);
    ls.target = p;
    ls.pdf_w = 0.0f;
    ls.dist = 0.0f;
    ls.kind = GC_LIGHT_NONE;
    const float group_pmf = gc_light_group_pmf(params);
    if (!(group_pmf > 0.0f)) return ls;
    const uint groups = gc_uint(1.0f / group_pmf + 0.5f);
    float u = r.x * gc_float(groups);
    uint group = gc_uint(u);
    if (group >= groups) group = groups - 1u;
    u = fmin(u - gc_float(group), 0.99999994f);
    if (params.num_emitters == 0u) group += 1u;                  /* no emitter group */
    if (group == 1u && !gc_has_point_lights(params)) group = 2u; /* no point-light group */

    if (group == 0u) {
        const GcEmitter e = GC_EMITTER(gc_pick_emitter(GC_EMITTERS_ARG, params.num_emitters, u));
        const float3 b = gc_sample_uniform_triangle(r.y, r.z);
        const float3 p_light = b.x * GC_XYZ(e.v0) + b.y * GC_XYZ(e.v1) + b.z * GC_XYZ(e.v2);
        const GcTriangleAttribs la = GC_ATTRIB(e.triangle);
        const GcMaterial lm = GC_MATERIAL(la.material);
        const float3 to_light = p_light - p;
        const float dist = gc_length(to_light);
        if (!(dist > 0.0f)) return ls;
        ls.wi = to_light / dist;
        const float cos_light = gc_dot(GC_XYZ(la.ng), -ls.wi);
        if (!gc_emits_toward(lm, cos_light)) return ls;
        ls.radiance = gc_shade_emission(GC_SHADE_ARGS, lm, gc_triangle_uv(la, b));
        ls.pdf_w = group_pmf * gc_light_pdf_w(GC_XYZ(lm.emission), params.emitter_power, dist, cos_light);
        /* The shadow ray from p must stop short of the light's own triangle: its t there carries
         * error in proportion to both ends' magnitudes. */
        ls.target = gc_offset_ray_origin(p_light, gc_side_normal(GC_XYZ(la.ng), -ls.wi), gc_spawn_scale(p, la.ng.w));
        ls.dist = dist;
        ls.kind = GC_LIGHT_AREA;
        return ls;
    }
    /* The constants drop each group's code from programs built for scenes without it. */
    if (GC_POINT_LIGHT_CODE != 0 && group == 1u) {
        uint i = gc_uint(u * gc_float(params.num_point_lights));
        if (i >= params.num_point_lights) i = params.num_point_lights - 1u;
        const GcPointLight light = GC_POINT_LIGHT(i);
        const float3 to_light = GC_XYZ(light.position) - p;
        const float dist = gc_length(to_light);
        if (!(dist > 0.0f)) return ls;
        ls.wi = to_light / dist;
        ls.radiance = GC_XYZ(light.intensity) * (1.0f / (dist * dist));
        ls.pdf_w = group_pmf / gc_float(params.num_point_lights);
        ls.target = GC_XYZ(light.position);
        ls.dist = dist;
        ls.kind = GC_LIGHT_POINT;
        return ls;
    }
    if (GC_ENV_MAP_CODE != 0) {
        /* Environment map: a row from the marginal cdf, a column from that row's conditional
         * cdf, continuous offsets inside the texel (pbrt's PiecewiseConstant2D). */
        const uint w = params.env_width;
        const uint h = params.env_height;
        const uint row = gc_env_search(GC_LIGHTS_ARGS, true, 0u, h, r.y);
        const float m0 = GC_ENV_MARGINAL(row);
        const float m1 = GC_ENV_MARGINAL(row + 1u);
        const float fy = m1 > m0 ? (r.y - m0) / (m1 - m0) : 0.5f;
        const uint base = row * (w + 1u);
        const uint col = gc_env_search(GC_LIGHTS_ARGS, false, base, w, r.z);
        const float c0 = GC_ENV_CONDITIONAL(base + col);
        const float c1 = GC_ENV_CONDITIONAL(base + col + 1u);
        const float fx = c1 > c0 ? (r.z - c0) / (c1 - c0) : 0.5f;
        ls.wi = gc_env_direction((gc_float(col) + fx) / gc_float(w), (gc_float(row) + fy) / gc_float(h));
        /* The density is re-evaluated from the direction, exactly as gc_escaped_radiance's
         * MIS weight will be, so the two strategies agree on every sample. */
        ls.pdf_w = group_pmf * gc_env_pdf_w(GC_LIGHTS_ARGS, params, ls.wi);
        ls.radiance = gc_env_radiance(GC_LIGHTS_ARGS, params, ls.wi);
        ls.dist = GC_FLOAT_MAX;
        ls.kind = GC_LIGHT_ENV;
    }
    return ls;
}

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
        path.radiance = gc_with_w(L + beta * gc_escaped_radiance(GC_SHADE_ARGS, params, path, -wo_world), path.radiance.w);
        res.path = path;
        return res;
    }

    /* The vertex's light and BSDF numbers, drawn first although they are used last. pcg4d is
     * a chain of dependent multiplies; issued here, the two chains run alongside each other
     * and alongside the loads and the surface interpolation below, instead of each stalling
     * the code that waits for it. Same numbers, same bits; at max depth both go unused, and the
     * light numbers where next-event estimation is skipped (a delta BSDF, no light).
     * Path samples against drawing each where it is used, interleaved rounds: 2-core VM, one
     * PoCL thread, Cornell box 1.104-1.114x, dragon 0.98-1.015x, bunny 1.018x; both cores,
     * 1.142x, 1.036x, 1.006x; H200 host, 16 cores, Cornell box 1.02-1.08x, dragon 0.92-0.99x
     * (two rounds), NVIDIA OpenCL 1.00x. Drawn after the max-depth return instead: Cornell box
     * 0.966x of this; drawn before the segment is traced, in the megakernel: 0.966x. */
    const float4 r_light = gc_rand4(path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_LIGHT), params.seed);
    const float4 r_bsdf = gc_rand4(path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_BSDF), params.seed);
    const GcTriangleAttribs tri = GC_ATTRIB(hit.prim);
    const GcSurface s = gc_surface_at(tri, ray, hit);
    const GcMaterial m = gc_shade_material(GC_SHADE_ARGS, GC_MATERIAL(s.material), s.uv);
    const float4 base = gc_shade_base_color(GC_SHADE_ARGS, m, s.uv);

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
        const float4 ra = gc_rand4(path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_EXTRA), params.seed);
        if (gc_alpha_transparent(m, base.w, ra.x)) {
            path.radiance = gc_with_w(L, path.radiance.w);
            if (path.depth < params.max_depth) {
                const float3 d = -wo_world;
                res.next = gc_make_ray(gc_offset_ray_origin(s.p, gc_side_normal(s.ng, d), s.spawn_scale), d, 0.0f, GC_RAY_UNBOUNDED);
                path.flags = GC_PATH_SPECULAR;
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
        float w = 1.0f;
        if ((path.flags & GC_PATH_SPECULAR) == 0u && params.num_emitters > 0u)
            w = gc_power_heuristic(path.throughput.w, gc_light_group_pmf(params) *
                                                          gc_light_pdf_w(GC_XYZ(m.emission), params.emitter_power, hit.t, cos_out));
        L += beta * Le * w;
    }
    if (path.depth >= params.max_depth) {
        path.radiance = gc_with_w(L, path.radiance.w);
        res.path = path;
        return res;
    }

    const float3 albedo = GC_XYZ(base);
    const GcFrame frame =
        gc_frame_from_normal(gc_shade_normal(GC_SHADE_ARGS, m, tri, make_float2(hit.u, hit.v), s.ns, s.uv));
    const float3 wo = gc_frame_to_local(frame, wo_world);

    /* Next-event estimation: one point on one light (gc_sample_light). */
    if (gc_light_group_pmf(params) > 0.0f && !gc_bsdf_is_delta(m)) {
        const GcLightSample ls = gc_sample_light(GC_SHADE_ARGS, params, s.p, r_light);
        if (ls.kind != GC_LIGHT_NONE && ls.pdf_w > 0.0f) {
            const float3 wi = gc_frame_to_local(frame, ls.wi);
            const float3 f = gc_bsdf_eval(m, albedo, wo, wi);
            /* A point light is a delta: no BSDF sample can reach it, so no MIS. */
            const float w = ls.kind == GC_LIGHT_POINT ? 1.0f : gc_power_heuristic(ls.pdf_w, gc_bsdf_pdf(m, albedo, wo, wi));
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
    }
    bool alive = bs.flags != 0u && (beta.x > 0.0f || beta.y > 0.0f || beta.z > 0.0f);
    if (alive && path.depth >= params.rr_depth) {
        /* Russian roulette on the throughput's largest channel, capped so bright paths
         * still end sometimes (as Mitsuba's path integrator does). */
        const float survive = fmin(fmax(beta.x, fmax(beta.y, beta.z)) * eta_scale, 0.95f);
        const float4 rr = gc_rand4(path.pixel, path.sample, gc_rng_block(bounce, GC_RNG_BLOCK_ROULETTE), params.seed);
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
    path.flags = (bs.flags & GC_BSDF_SPECULAR) != 0u ? GC_PATH_SPECULAR : 0u;
    res.path = path;
    res.flags |= GC_VERTEX_CONTINUE;
    return res;
}

GC_NAMESPACE_END

#endif /* GC_PATH_VERTEX_H */
