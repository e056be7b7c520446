/*
 * gc_lights.h — next-event estimation over every kind of light: emissive triangles (area
 * sampled, chosen by power), point lights (delta, chosen uniformly) and a lat-long
 * environment map (importance sampled by luminance * sin(theta), a piecewise-constant 2D
 * distribution as in pbrt's PiecewiseConstant2D). One light *group* is chosen uniformly among
 * the groups the scene has; gc_light_group_pmf gives that probability so the MIS weights of
 * BSDF-sampled hits on emitters and on the environment use the same density NEE sampled with.
 *
 * Environment directions: +Y is up; u = phi / 2pi with phi = atan2(x, -z) (u = 0 looks down
 * -Z, u increases toward +X), v = theta / pi from the zenith. Texel lookups are nearest, so
 * the radiance and the sampling density are constant over the same texels.
 *
 * Buffers come in as the scene-buffer group lights (gc_scene_buffers.h): GC_LIGHTS_PARAMS /
 * GC_LIGHTS_ARGS, read through GC_POINT_LIGHT(i), GC_ENV_PIXEL(i), GC_ENV_MARGINAL(i) and
 * GC_ENV_CONDITIONAL(i) (the Vulkan reference defines those over its SSBOs in
 * kernels/vk/scene_bindings.glsl).
 */
#ifndef GC_LIGHTS_H
#define GC_LIGHTS_H

#include "gc_path.h"
#include "gc_scene_buffers.h"
#include "gc_trig.h"

/* Whether this program can meet each light group at all: it was built for a scene with such
 * lights (gc_features.h). One constant each, so that clang's warning about a constant
 * right-hand operand of && stays quiet. */
#if GC_USE_ENV_MAP
#define GC_ENV_MAP_CODE 1
#else
#define GC_ENV_MAP_CODE 0
#endif
#if GC_USE_POINT_LIGHTS
#define GC_POINT_LIGHT_CODE 1
#else
#define GC_POINT_LIGHT_CODE 0
#endif

GC_NAMESPACE_BEGIN

GC_FUNC bool gc_has_env_map(GcRenderParams p) { return GC_ENV_MAP_CODE != 0 && p.env_width > 0u; }
GC_FUNC bool gc_has_point_lights(GcRenderParams p) { return GC_POINT_LIGHT_CODE != 0 && p.num_point_lights > 0u; }

/* Probability of choosing any one light group (emitters, point lights, environment map). */
GC_FUNC float gc_light_group_pmf(GcRenderParams p)
{
    const uint groups = (p.num_emitters > 0u ? 1u : 0u) + (gc_has_point_lights(p) ? 1u : 0u) +
                        (gc_has_env_map(p) ? 1u : 0u);
    return groups > 0u ? 1.0f / gc_float(groups) : 0.0f;
}

/* Lat-long mapping (see the header comment). theta = acos(y), as atan2 of sin and cos: gc_atan2
 * gives every device the same bits (gc_trig.h). */
GC_FUNC float2 gc_env_uv(float3 d)
{
    const float theta = gc_atan2(sqrt(d.x * d.x + d.z * d.z), d.y);
    float phi = gc_atan2(d.x, -d.z);
    if (phi < 0.0f) phi += 2.0f * GC_PI;
    return make_float2(phi * GC_INV_2PI, theta * GC_INV_PI);
}

GC_FUNC float3 gc_env_direction(float u, float v)
{
    /* theta = pi v is half a turn times v. */
    const float2 theta = gc_cos_sin_turns(0.5f * v);
    const float2 phi = gc_cos_sin_turns(u);
    return make_float3(theta.y * phi.y, theta.x, -theta.y * phi.x);
}

GC_FUNC uint gc_env_texel_x(GcRenderParams p, float u) { return gc_uint(fmin(fmax(u, 0.0f) * gc_float(p.env_width), gc_float(p.env_width - 1u))); }
GC_FUNC uint gc_env_texel_y(GcRenderParams p, float v) { return gc_uint(fmin(fmax(v, 0.0f) * gc_float(p.env_height), gc_float(p.env_height - 1u))); }

/* First index i in [0, n) with u < cdf[base + i + 1] (cdf[base] = 0, cdf[base + n] = 1). */
GC_FUNC uint gc_env_search(GC_LIGHTS_PARAMS, bool marginal, uint base, uint n, float u)
{
    GC_LIGHTS_UNUSED();
    uint lo = 0u;
    uint hi = n - 1u;
    while (lo < hi) {
        const uint mid = (lo + hi) / 2u;
        const float c = marginal ? GC_ENV_MARGINAL(base + mid + 1u) : GC_ENV_CONDITIONAL(base + mid + 1u);
        if (u < c) hi = mid;
        else lo = mid + 1u;
    }
    return lo;
}

/* Density per unit solid angle with which the map is sampled toward direction d. */
GC_FUNC float gc_env_pdf_w(GC_LIGHTS_PARAMS, GcRenderParams p, float3 d)
{
    GC_LIGHTS_UNUSED();
    const float2 uv = gc_env_uv(d);
    const uint x = gc_env_texel_x(p, uv.x);
    const uint y = gc_env_texel_y(p, uv.y);
    const float sin_theta = gc_cos_sin_turns(0.5f * uv.y).y; /* sin(pi v) */
    if (!(sin_theta > 0.0f)) return 0.0f;
    const uint row = y * (p.env_width + 1u);
    const float p_row = GC_ENV_MARGINAL(y + 1u) - GC_ENV_MARGINAL(y);
    const float p_col = GC_ENV_CONDITIONAL(row + x + 1u) - GC_ENV_CONDITIONAL(row + x);
    const float pdf_uv = p_row * gc_float(p.env_height) * p_col * gc_float(p.env_width);
    return pdf_uv / (2.0f * GC_PI * GC_PI * sin_theta);
}

/* Radiance the environment sends along -d (seen looking in direction d). */
GC_FUNC float3 gc_env_radiance(GC_LIGHTS_PARAMS, GcRenderParams p, float3 d)
{
    GC_LIGHTS_UNUSED();
    if (!gc_has_env_map(p)) return GC_XYZ(p.env_radiance);
    const float2 uv = gc_env_uv(d);
    const uint index = gc_env_texel_y(p, uv.y) * p.env_width + gc_env_texel_x(p, uv.x);
    return GC_XYZ(GC_ENV_PIXEL(index)) * GC_XYZ(p.env_radiance);
}

/* A sampled light point as seen from the shading point. */
GC_STRUCT(GcLightSample) {
    float3 wi;       /* unit direction toward the light */
    float3 radiance; /* radiance (area, env) or intensity / d^2 (point) arriving along -wi */
    float3 target;   /* where the shadow ray ends (offset off an emitter's surface) */
    float pdf_w;     /* solid-angle density including the group choice; delta: the pmf */
    float dist;      /* GC_FLOAT_MAX for the environment */
    uint kind;       /* 0 none, 1 area, 2 point (delta), 3 environment */
    uint material;   /* an area light's material (its emission's gradient slot); else GC_INVALID */
    float2 uv;       /* an area light's texture coordinates at the point (its emission's texels) */
} GC_STRUCT_END(GcLightSample)

#define GC_LIGHT_NONE 0u
#define GC_LIGHT_AREA 1u
#define GC_LIGHT_POINT 2u
#define GC_LIGHT_ENV 3u

GC_NAMESPACE_END

#endif /* GC_LIGHTS_H */
