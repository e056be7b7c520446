/*
 * gc_scene_buffers.h — the scene buffers the kernels read, declared once: every kernel
 * parameter list of scene buffers (GC_*_PARAMS), the argument lists that pass them down to
 * helper functions (GC_*_ARGS) and the host's kernel-argument tuples (DeviceScene::*_args(),
 * host/render/scene_buffers.h) are generated from GC_SCENE_BUFFERS below, so they cannot
 * disagree on order or membership.
 *
 * One row per buffer, in kernel argument order:
 *     X(g, name, element type, DeviceScene expression, bvh, alpha, shade, lights)
 * `g` is passed through untouched (the generator's group); `name` is the parameter's name in
 * OpenCL C and C++; the DeviceScene expression is what the host passes (kernels ignore it);
 * the last four columns say which groups take the buffer (1, or F for the group's first row)
 * or not (0):
 *     bvh     BVH traversal of opaque triangles (trace.cl, probes, host plain references)
 *     alpha   the alpha-MASK test (gc_alpha_solid)
 *     shade   shading a path vertex (gc_shade_vertex, the aov and whitted shading)
 *     lights  light sampling and the environment map (gc_lights.h)
 * and two groups are derived: trace (bvh or alpha: the traversal with the alpha test, which
 * every product kernel uses) and scene (every row: kernels that trace and shade).
 *
 * Groups and what they generate (OpenCL C and C++):
 *     GC_BVH_PARAMS / GC_BVH_ARGS       the traversal's buffers: group trace, or group bvh
 *                                       where the includer defines GC_TRACE_OPAQUE (a mode of
 *                                       the program, like GC_BVH_WIDE; see gc_traverse.h)
 *     GC_ALPHA_PARAMS / _ARGS           group alpha
 *     GC_SHADE_PARAMS / _ARGS / _UNUSED()   group shade
 *     GC_LIGHTS_PARAMS / _ARGS / _UNUSED()  group lights
 *     GC_SCENE_PARAMS / _ARGS           every row
 * Each group's rows are one contiguous run of the list, so a kernel that takes the scene
 * group passes its head to the traversal (GC_BVH_ARGS) and its tail to shading
 * (GC_SHADE_ARGS) by name.
 *
 * To add a buffer: add its row here (kernel parameters and the host tuples follow), its
 * DeviceScene member and upload, an element accessor below if the kernels want one, and for
 * the Vulkan reference an SSBO, binding and accessor in kernels/vk/scene_bindings.glsl.
 *
 * GLSL has no pointers: a shader's buffers are globals bound by
 * descriptor (kernels/vk/scene_bindings.glsl), so there every group's parameter list is one
 * dummy uint (a signature puts a comma after it, so it must name one parameter) and its
 * argument list 0u. The shared function bodies read buffers only through the element
 * accessors (GC_ATTRIB(i), ...), which each language defines over its own storage.
 */
#ifndef GC_SCENE_BUFFERS_H
#define GC_SCENE_BUFFERS_H

#include "gc_types.h"

/*                      name             element type         DeviceScene       bvh alpha shade lights */
#define GC_SCENE_BUFFERS(X, g)                                                                        \
    X(g, gc_bvh_nodes,    GcTraversalNode,     bvh.nodes(),      F, 0, 0, 0)                           \
    X(g, gc_bvh_tris,     GcTraversalTriangle, bvh.triangles(),  1, 0, 0, 0)                           \
    X(g, attribs,         GcTriangleAttribs,   attribs,          0, F, F, 0)                           \
    X(g, materials,       GcMaterial,          materials,        0, 1, 1, 0)                           \
    X(g, textures,        GcTexture,           textures,         0, 1, 1, 0)                           \
    X(g, texels,          uint,                texels,           0, 1, 1, 0)                           \
    X(g, emitters,        GcEmitter,           emitters,         0, 0, 1, 0)                           \
    X(g, point_lights,    GcPointLight,        point_lights,     0, 0, 1, F)                           \
    X(g, env_pixels,      float4,              env_pixels,       0, 0, 1, 1)                           \
    X(g, env_marginal,    float,               env_marginal,     0, 0, 1, 1)                           \
    X(g, env_conditional, float,               env_conditional,  0, 0, 1, 1)

/* GC_SCENE_IN_<group>(bvh, alpha, shade, lights): 0 where a row is not in the group, F for the
 * group's first row, 1 for the others. trace's first row is bvh's; scene's is the list's. */
#define GC_SCENE_IN_BVH(bvh, alpha, shade, lights) bvh
#define GC_SCENE_IN_ALPHA(bvh, alpha, shade, lights) alpha
#define GC_SCENE_IN_SHADE(bvh, alpha, shade, lights) shade
#define GC_SCENE_IN_LIGHTS(bvh, alpha, shade, lights) lights
#define GC_SCENE_IN_TRACE(bvh, alpha, shade, lights) GC_SCENE_OR_##bvh##alpha
#define GC_SCENE_IN_SCENE(bvh, alpha, shade, lights) GC_SCENE_ANY_##bvh
#define GC_SCENE_OR_00 0
#define GC_SCENE_OR_01 1
#define GC_SCENE_OR_0F 1
#define GC_SCENE_OR_10 1
#define GC_SCENE_OR_F0 F
#define GC_SCENE_ANY_0 1
#define GC_SCENE_ANY_1 1
#define GC_SCENE_ANY_F F

/* Pastes after expanding its arguments (a plain ## would paste the unexpanded tokens). */
#define GC_SCENE_CAT(a, b) GC_SCENE_CAT_(a, b)
#define GC_SCENE_CAT_(a, b) a##b

/* The rows texels and emitters on their own, for the helpers that read only them
 * (gc_texture_sample, gc_pick_emitter). The element types are restated here: a mismatch with
 * the rows above fails to compile where a group's parameter is passed to these. */
#if defined(GC_GLSL)
#define GC_TEXELS_PARAM uint gc_texels_unused
#define GC_TEXELS_ARG 0u
#define GC_EMITTERS_PARAM uint gc_emitters_unused
#define GC_EMITTERS_ARG 0u
#else
#define GC_TEXELS_PARAM GC_GLOBAL const uint *texels
#define GC_TEXELS_ARG texels
#define GC_EMITTERS_PARAM GC_GLOBAL const GcEmitter *emitters
#define GC_EMITTERS_ARG emitters
#endif

#if defined(GC_GLSL)

#define GC_BVH_PARAMS uint gc_bvh_unused
#define GC_BVH_ARGS 0u
#define GC_ALPHA_PARAMS uint gc_alpha_unused
#define GC_ALPHA_ARGS 0u
#define GC_SHADE_PARAMS uint gc_shade_unused
#define GC_SHADE_ARGS 0u
#define GC_SHADE_UNUSED()
#define GC_LIGHTS_PARAMS uint gc_lights_unused
#define GC_LIGHTS_ARGS 0u
#define GC_LIGHTS_UNUSED()
#define GC_SCENE_PARAMS uint gc_scene_unused
#define GC_SCENE_ARGS 0u

#else /* OpenCL C and C++ */

/* Each generator emits "item" for a group's first row and ", item" for its others. (OpenCL C
 * 1.2 has no variadic macros, so a leading comma cannot be dropped afterwards.) */
#define GC_SCENE_PICK(g, bvh, alpha, shade, lights, kind) \
    GC_SCENE_CAT(kind, GC_SCENE_IN_##g(bvh, alpha, shade, lights))

#define GC_SCENE_PARAM(g, name, type, host, bvh, alpha, shade, lights) \
    GC_SCENE_PICK(g, bvh, alpha, shade, lights, GC_SCENE_PARAM_)(type, name)
#define GC_SCENE_PARAM_0(type, name)
#define GC_SCENE_PARAM_F(type, name) GC_GLOBAL const type *name
#define GC_SCENE_PARAM_1(type, name) , GC_GLOBAL const type *name
#define GC_SCENE_ARG(g, name, type, host, bvh, alpha, shade, lights) \
    GC_SCENE_PICK(g, bvh, alpha, shade, lights, GC_SCENE_ARG_)(name)
#define GC_SCENE_ARG_0(name)
#define GC_SCENE_ARG_F(name) name
#define GC_SCENE_ARG_1(name) , name
#define GC_SCENE_VOID(g, name, type, host, bvh, alpha, shade, lights) \
    GC_SCENE_PICK(g, bvh, alpha, shade, lights, GC_SCENE_VOID_)(name)
#define GC_SCENE_VOID_0(name)
#define GC_SCENE_VOID_F(name) (void)name
#define GC_SCENE_VOID_1(name) , (void)name

/* A group's parameter list, argument list, and a statement marking its parameters used (for
 * helpers that read only some of them; C++ warns about unused parameters). */
#define GC_SCENE_GROUP_PARAMS(g) GC_SCENE_BUFFERS(GC_SCENE_PARAM, g)
#define GC_SCENE_GROUP_ARGS(g) GC_SCENE_BUFFERS(GC_SCENE_ARG, g)
#define GC_SCENE_GROUP_UNUSED(g) (GC_SCENE_BUFFERS(GC_SCENE_VOID, g))

#if defined(GC_TRACE_OPAQUE)
#define GC_BVH_PARAMS GC_SCENE_GROUP_PARAMS(BVH)
#define GC_BVH_ARGS GC_SCENE_GROUP_ARGS(BVH)
#else
#define GC_BVH_PARAMS GC_SCENE_GROUP_PARAMS(TRACE)
#define GC_BVH_ARGS GC_SCENE_GROUP_ARGS(TRACE)
#endif
#define GC_ALPHA_PARAMS GC_SCENE_GROUP_PARAMS(ALPHA)
#define GC_ALPHA_ARGS GC_SCENE_GROUP_ARGS(ALPHA)
#define GC_SHADE_PARAMS GC_SCENE_GROUP_PARAMS(SHADE)
#define GC_SHADE_ARGS GC_SCENE_GROUP_ARGS(SHADE)
#define GC_SHADE_UNUSED() GC_SCENE_GROUP_UNUSED(SHADE)
#define GC_LIGHTS_PARAMS GC_SCENE_GROUP_PARAMS(LIGHTS)
#define GC_LIGHTS_ARGS GC_SCENE_GROUP_ARGS(LIGHTS)
#define GC_LIGHTS_UNUSED() GC_SCENE_GROUP_UNUSED(LIGHTS)
#define GC_SCENE_PARAMS GC_SCENE_GROUP_PARAMS(SCENE)
#define GC_SCENE_ARGS GC_SCENE_GROUP_ARGS(SCENE)

/* Element accessors over the parameters above (GLSL's read SSBOs: scene_bindings.glsl). */
#define GC_BVH_NODE(i) gc_bvh_nodes[i]
#define GC_BVH_TRI(i) gc_bvh_tris[i]
#define GC_ATTRIB(i) attribs[i]
#define GC_MATERIAL(i) materials[i]
#define GC_TEXTURE(i) textures[i]
#define GC_TEXEL(i) texels[i]
#define GC_EMITTER(i) emitters[i]
#define GC_POINT_LIGHT(i) point_lights[i]
#define GC_ENV_PIXEL(i) env_pixels[i]
#define GC_ENV_MARGINAL(i) env_marginal[i]
#define GC_ENV_CONDITIONAL(i) env_conditional[i]

#endif /* GC_GLSL */

#endif /* GC_SCENE_BUFFERS_H */
