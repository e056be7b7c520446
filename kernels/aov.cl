/*
 * aov.cl — the `aov` integrator: one camera ray per pixel and sample, and the primary
 * hit's albedo, shading normal, depth, primitive id or a simple shaded preview
 * (the seed's "mesh render pass" outputs). One work-item per pixel of the batch; each
 * work-item owns its film slot, so the sum needs no atomics.
 */
#include "gc_camera.h"
#include "gc_rng.h"
#include "gc_shading.h"
#include "gc_texture.h"
#include "gc_traverse.h"

static float3 gc_material_albedo(GC_TEXELS_PARAM, __global const GcMaterial* materials,
                                 __global const GcTexture* textures, GcSurface s)
{
    const GcMaterial m = materials[s.material];
    float3 albedo = m.albedo.xyz;
    if (m.albedo_texture != GC_INVALID)
        albedo *= gc_texture_sample(GC_TEXELS_ARG, textures[m.albedo_texture], s.uv.x, s.uv.y).xyz;
    return albedo;
}

__kernel void aov_render(const GcRenderParams params,
                         __global const GcBvhNode* nodes,
                         __global const GcTriangle* tris,
                         __global const GcTriangleAttribs* attribs,
                         __global const GcMaterial* materials,
                         __global const GcTexture* textures,
                         __global const uint* texels,
                         __global float4* film)
{
    const uint i = get_global_id(0);
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    const uint px = pixel % params.width;
    const uint py = pixel / params.width;

    /* Depth, normal and primitive id are per-pixel facts: sample the pixel centre. */
    float2 jitter = (float2)(0.5f, 0.5f);
    if (params.aov == GC_AOV_PREVIEW || params.aov == GC_AOV_ALBEDO) {
        const float4 r = gc_rand4(pixel, params.sample_index, GC_RNG_BLOCK_CAMERA, params.seed);
        jitter = r.xy;
    }
    const GcRay ray = gc_camera_ray(params.camera, params.width, params.height, px, py, jitter.x, jitter.y);
    const GcHit hit = gc_trace_closest(nodes, tris, ray);

    float3 value = params.env_radiance.xyz;
    if (params.aov == GC_AOV_PRIMID) value = (float3)(-1.0f);
    if (params.aov == GC_AOV_DEPTH || params.aov == GC_AOV_NORMAL || params.aov == GC_AOV_ALBEDO)
        value = (float3)(0.0f);
    if (hit.prim != GC_INVALID) {
        const GcSurface s = gc_surface_at(attribs[hit.prim], ray, hit);
        switch (params.aov) {
        case GC_AOV_ALBEDO:
            value = gc_material_albedo(texels, materials, textures, s);
            break;
        case GC_AOV_NORMAL:
            value = s.ns;
            break;
        case GC_AOV_DEPTH:
            value = (float3)(hit.t);
            break;
        case GC_AOV_PRIMID:
            value = (float3)((float)hit.prim);
            break;
        default: {
            /* Preview: albedo under a headlight, plus emitters shown at (clamped) full
             * brightness. Recognisable, not physically based. */
            const float3 albedo = gc_material_albedo(texels, materials, textures, s);
            const float cosine = fabs(dot(s.ns, ray.dir_tmax.xyz));
            value = albedo * (0.15f + 0.85f * cosine) + fmin(materials[s.material].emission.xyz, (float3)(1.0f));
        }
        }
    }
    film[pixel] += (float4)(value, 1.0f);
}
