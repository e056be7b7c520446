/*
 * gc_alpha.h — the glTF alphaMode MASK test inside BVH traversal. Include it BEFORE
 * gc_traverse.h: it widens the traversal's buffer parameters by the four buffers the test
 * reads (triangle attributes, materials, textures, texels) and defines GC_ALPHA_TEST, so
 * that closest and any hit both skip a candidate hit where the base colour's alpha is below
 * the material's alphaCutoff. Only triangles flagged GC_TRI_ALPHA_TESTED (the host sets it in
 * GcTriangle, host/bvh/flatten.cpp) reach the hook; every other candidate costs one flag test.
 *
 * alphaMode BLEND is not tested here: it is stochastic transparency and would need a random
 * number per candidate triangle, keyed by the path (pixel, sample, bounce) that the traversal
 * kernels do not carry, and the closest-hit/brute-force equality would then depend on that
 * key. It stays a shading-level pass-through (gc_path_vertex.h).
 *
 * Buffers come in through macros, as in gc_traverse.h. Defaults (OpenCL C and C++), named
 * like gc_path_vertex.h's so the same GC_ATTRIB / GC_MATERIAL / GC_TEXTURE work for both:
 *     GC_ALPHA_PARAMS  attribs, materials, textures pointers, then GC_TEXELS_PARAM
 *     GC_ALPHA_ARGS    attribs, materials, textures, GC_TEXELS_ARG
 * GLSL defines them (dummy uint parameter, global SSBOs) in kernels/vk/scene_bindings.glsl.
 * The GC_BVH_PARAMS widened here (nodes, triangles, then GC_ALPHA_PARAMS) is also the leading
 * scene group of the tracing kernels' signatures (extend.cl, shadow.cl, whitted.cl), so the
 * list is written once; the host sets it with DeviceScene::bvh_args(), in this order.
 */
#ifndef GC_ALPHA_H
#define GC_ALPHA_H

#include "gc_accessors.h"
#include "gc_texture.h"

#ifndef GC_ALPHA_PARAMS
#define GC_ALPHA_PARAMS                                                                           \
    GC_GLOBAL const GcTriangleAttribs *attribs, GC_GLOBAL const GcMaterial *materials,            \
        GC_GLOBAL const GcTexture *textures, GC_TEXELS_PARAM
#define GC_ALPHA_ARGS attribs, materials, textures, GC_TEXELS_ARG
#endif
#ifndef GC_ATTRIB
#define GC_ATTRIB(i) attribs[i]
#define GC_MATERIAL(i) materials[i]
#define GC_TEXTURE(i) textures[i]
#endif

#ifndef GC_BVH_PARAMS
#define GC_BVH_PARAMS                                                                             \
    GC_GLOBAL const GcTraversalNode *gc_bvh_nodes, GC_GLOBAL const GcTraversalTriangle *gc_bvh_tris, GC_ALPHA_PARAMS
#define GC_BVH_ARGS gc_bvh_nodes, gc_bvh_tris, GC_ALPHA_ARGS
#define GC_BVH_NODE(i) gc_bvh_nodes[i]
#define GC_BVH_TRI(i) gc_bvh_tris[i]
#endif

#define GC_ALPHA_TEST(scene_tri, u, v) gc_alpha_solid(GC_ALPHA_ARGS, scene_tri, u, v)

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
