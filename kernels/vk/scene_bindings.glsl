/*
 * scene_bindings.glsl — the scene buffers as std430 SSBOs, declared with the structs of
 * kernels/shared/gc_types.h (no second, hand-written copy), and the element accessors through
 * which the shared headers read them (the OpenCL ones are in gc_scene_buffers.h). The
 * buffers are those of gc_scene_buffers.h's list plus the params, film, positions and sRGB
 * table of the Vulkan passes.
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

/* The sRGB decoding and sheen albedo tables come from buffers the host fills from
 * gc_srgb_table.h and gc_sheen_table.h (the same numbers), not from the headers' GLSL arrays:
 * glslang gives every function that indexes a constant array at run time a private copy of it,
 * inlining multiplies those copies, and lavapipe's compiler then takes minutes
 * (docs/decisions/khr-material-layers.md). The macros keep the arrays out. */
#define GC_SRGB_TABLE_H 1
layout(std430, set = 0, binding = GC_VK_BINDING_SRGB) readonly buffer SrgbBuffer { float gc_srgb_to_linear_table[256]; };
#define GC_SHEEN_TABLE_IN_BUFFER 1
layout(std430, set = 0, binding = GC_VK_BINDING_SHEEN) readonly buffer SheenBuffer { float gc_sheen_albedo_table[]; };

/* Element accessors of the shared headers over the SSBOs above. The parameter lists are
 * dummies (GLSL has no pointers: every access is a global), defined with the OpenCL ones from
 * the one list of scene buffers in gc_scene_buffers.h. */
#define GC_BVH_NODE(i) bvh_nodes[i]
#define GC_BVH_TRI(i) bvh_tris[i]
#define GC_ATTRIB(i) attrib_data[i]
#define GC_MATERIAL(i) material_data[i]
#define GC_TEXTURE(i) texture_data[i]
#define GC_TEXEL(i) texel_data[i]
#define GC_EMITTER(i) emitter_data[i]
#define GC_POINT_LIGHT(i) point_light_data[i]
#define GC_ENV_PIXEL(i) env_pixel_data[i]
#define GC_ENV_MARGINAL(i) env_marginal_data[i]
#define GC_ENV_CONDITIONAL(i) env_conditional_data[i]
