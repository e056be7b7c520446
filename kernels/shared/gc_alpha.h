/*
 * gc_alpha.h — the glTF alphaMode MASK test that BVH traversal applies: gc_traverse.h
 * compiles it in as its GC_ALPHA_TEST hook (unless the program traces opaque triangles only,
 * GC_TRACE_OPAQUE), so that closest and any hit both skip a candidate hit where the base
 * colour's alpha is below the material's alphaCutoff. Only triangles flagged
 * GC_TRI_ALPHA_TESTED (the host sets it in GcTriangle, host/bvh/flatten.cpp) reach the hook;
 * every other candidate costs one flag test. The raster pass (kernels/vk/raster.frag) calls
 * gc_alpha_solid directly to discard the same fragments.
 *
 * alphaMode BLEND is not tested here: it is stochastic transparency and would need a random
 * number per candidate triangle, keyed by the path (pixel, sample, bounce) that the traversal
 * kernels do not carry, and the closest-hit/brute-force equality would then depend on that
 * key. It stays a shading-level pass-through (gc_alpha_transparent, gc_material_eval.h).
 *
 * The buffers it reads (triangle attributes, materials, textures, texels) come in as the
 * scene-buffer group alpha, GC_ALPHA_PARAMS / GC_ALPHA_ARGS (gc_scene_buffers.h).
 */
#ifndef GC_ALPHA_H
#define GC_ALPHA_H

#include "gc_accessors.h"
#include "gc_scene_buffers.h"
#include "gc_texture.h"

GC_NAMESPACE_BEGIN

/* True where the triangle is solid at barycentrics (u, v) of v1 and v2: alpha (baseColor
 * factor times texture) >= alphaCutoff (pbr.z), as glTF defines MASK. The uv is formed by the
 * same expression as gc_surface_at's, so the shading sees the texel this test saw. */
GC_FUNC bool gc_alpha_solid(GC_ALPHA_PARAMS, uint scene_tri, float u, float v)
{
    /* A program built for a scene without alpha MASK (gc_features.h): every triangle is solid,
     * and the traversal's test folds away (the buffers stay parameters, so that the kernels'
     * signatures do not depend on the scene). */
    if (GC_USE_ALPHA_MASK == 0) return true;
    const GcTriangleAttribs a = GC_ATTRIB(scene_tri);
    const GcMaterial m = GC_MATERIAL(a.material);
    float alpha = m.albedo.w;
    if (GC_USE_TEXTURES != 0 && m.albedo_texture != GC_INVALID) {
        const float b0 = 1.0f - u - v;
        const float tu = b0 * a.uv01.x + u * a.uv01.z + v * a.uv2_u;
        const float tv = b0 * a.uv01.y + u * a.uv01.w + v * a.uv2_v;
        alpha *= gc_texture_sample(GC_TEXELS_ARG, GC_TEXTURE(m.albedo_texture), tu, tv).w;
    }
    return !(alpha < m.pbr.z);
}

GC_NAMESPACE_END

#endif /* GC_ALPHA_H */
