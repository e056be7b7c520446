/*
 * bindings.h — descriptor bindings of the Vulkan passes, included by the GLSL shaders and by
 * host/vk. Every pass uses one descriptor set (set 0) of storage buffers with these bindings.
 */
#ifndef GC_VK_BINDINGS_H
#define GC_VK_BINDINGS_H

#define GC_VK_BINDING_PARAMS 0    /* GcRenderParams (one) */
#define GC_VK_BINDING_NODES 1     /* GcBvhNode[] */
#define GC_VK_BINDING_TRIS 2      /* GcTriangle[] in BVH leaf order */
#define GC_VK_BINDING_ATTRIBS 3   /* GcTriangleAttribs[] by scene triangle */
#define GC_VK_BINDING_MATERIALS 4 /* GcMaterial[] */
#define GC_VK_BINDING_TEXTURES 5  /* GcTexture[] */
#define GC_VK_BINDING_TEXELS 6    /* uint[] RGBA8 */
#define GC_VK_BINDING_EMITTERS 7  /* GcEmitter[] */
#define GC_VK_BINDING_FILM 8      /* vec4[] per pixel: sum of samples (compute only) */
#define GC_VK_BINDING_POSITIONS 9 /* vec4[] three per scene triangle (raster only) */
#define GC_VK_BINDING_SRGB 10     /* float[256]: gc_srgb_to_linear_table (gc_srgb_table.h) */
#define GC_VK_BINDING_POINT_LIGHTS 11    /* GcPointLight[] */
#define GC_VK_BINDING_ENV_PIXELS 12      /* vec4[] lat-long environment map, row 0 at the zenith */
#define GC_VK_BINDING_ENV_MARGINAL 13    /* float[] its rows' cdf (environment.h) */
#define GC_VK_BINDING_ENV_CONDITIONAL 14 /* float[] each row's texels' cdf */
#define GC_VK_BINDING_SHEEN 15           /* float[]: gc_sheen_albedo_table (gc_sheen_table.h) */
#define GC_VK_BINDING_COUNT 16
/* Instanced passes (the shaders built with GC_SCENE_INSTANCED) add the two-level BVH's top
 * level and instances (gc_instance.h); NODES and TRIS then hold every mesh's bottom-level tree. */
#define GC_VK_BINDING_TLAS 16            /* GcBvhNode[] over the instances */
#define GC_VK_BINDING_INSTANCES 17       /* GcInstance[] in the top level's leaf order */
#define GC_VK_INSTANCED_BINDING_COUNT 18

#define GC_VK_LOCAL_SIZE 64 /* compute work-group size */

#endif /* GC_VK_BINDINGS_H */
