/*
 * scene_bindings.glsl — the scene buffers as std430 SSBOs, declared with the structs of
 * kernels/shared/gc_types.h (no second, hand-written copy), and the macros through which
 * the shared headers (gc_traverse.h, gc_texture.h, gc_path.h, gc_lights.h, gc_path_vertex.h,
 * gc_whitted_tree.h) read them.
 * Include after #version; define GC_VK_COMPUTE first in compute shaders (the film is
 * writable there and absent elsewhere).
 */
#extension GL_GOOGLE_include_directive : require

/* `sample` is a GLSL keyword (an interpolation qualifier) and gc_rng.h uses it as a
 * parameter name: rename it for this compilation only. */
#define sample gc_sample_

#include "bindings.h"
#include "gc_types.h"

layout(std430, set = 0, binding = GC_VK_BINDING_PARAMS) readonly buffer ParamsBuffer { GcRenderParams params_data; };
layout(std430, set = 0, binding = GC_VK_BINDING_NODES) readonly buffer NodeBuffer { GcBvhNode bvh_nodes[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_TRIS) readonly buffer TriBuffer { GcTriangle bvh_tris[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_ATTRIBS) readonly buffer AttribBuffer { GcTriangleAttribs attrib_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_MATERIALS) readonly buffer MaterialBuffer { GcMaterial material_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_TEXTURES) readonly buffer TextureBuffer { GcTexture texture_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_TEXELS) readonly buffer TexelBuffer { uint texel_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_EMITTERS) readonly buffer EmitterBuffer { GcEmitter emitter_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_POINT_LIGHTS) readonly buffer PointLightBuffer { GcPointLight point_light_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_ENV_PIXELS) readonly buffer EnvPixelBuffer { vec4 env_pixel_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_ENV_MARGINAL) readonly buffer EnvMarginalBuffer { float env_marginal_data[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_ENV_CONDITIONAL) readonly buffer EnvConditionalBuffer { float env_conditional_data[]; };
#ifdef GC_VK_COMPUTE
layout(std430, set = 0, binding = GC_VK_BINDING_FILM) buffer FilmBuffer { vec4 film[]; };
#endif
layout(std430, set = 0, binding = GC_VK_BINDING_POSITIONS) readonly buffer PositionBuffer { vec4 positions[]; };

/* The sRGB decoding table comes from a buffer the host fills from gc_srgb_table.h (the same
 * numbers), not from the header's GLSL branch: a 256-entry constant array indexed at run time
 * makes lavapipe's shader compiler take seconds to minutes. The guard keeps the header out. */
#define GC_SRGB_TABLE_H 1
layout(std430, set = 0, binding = GC_VK_BINDING_SRGB) readonly buffer SrgbBuffer { float gc_srgb_to_linear_table[256]; };

/* GLSL has no pointers: every buffer "parameter" is a dummy uint, every access a global. */
#define GC_BVH_PARAMS uint gc_bvh_unused
#define GC_BVH_ARGS 0u
#define GC_BVH_NODE(i) bvh_nodes[i]
#define GC_BVH_TRI(i) bvh_tris[i]
#define GC_TEXELS_PARAM uint gc_texels_unused
#define GC_TEXELS_ARG 0u
#define GC_TEXEL(i) texel_data[i]
#define GC_EMITTERS_PARAM uint gc_emitters_unused
#define GC_EMITTERS_ARG 0u
#define GC_EMITTER(i) emitter_data[i]
#define GC_SHADE_PARAMS uint gc_shade_unused
#define GC_SHADE_ARGS 0u
#define GC_ATTRIB(i) attrib_data[i]
#define GC_MATERIAL(i) material_data[i]
#define GC_TEXTURE(i) texture_data[i]
#define GC_ALPHA_PARAMS uint gc_alpha_unused
#define GC_ALPHA_ARGS 0u
#define GC_LIGHTS_PARAMS uint gc_lights_unused
#define GC_LIGHTS_ARGS 0u
#define GC_LIGHTS_UNUSED()
#define GC_POINT_LIGHT(i) point_light_data[i]
#define GC_ENV_PIXEL(i) env_pixel_data[i]
#define GC_ENV_MARGINAL(i) env_marginal_data[i]
#define GC_ENV_CONDITIONAL(i) env_conditional_data[i]
#define GC_SCENE_PARAMS uint gc_scene_unused
#define GC_SCENE_ARGS 0u
