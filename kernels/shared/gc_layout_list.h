/*
 * gc_layout_list.h — every field of every struct in gc_types.h, as an X-macro list.
 *
 * Deliberately no include guard: the includer defines GC_LAYOUT_SIZE(Struct) and
 * GC_LAYOUT_FIELD(Struct, field), includes this file, and gets one expansion per entry in
 * this order. kernels/layout_probe.cl expands it into device offsets (pointer differences),
 * host/cl/layout_probe.cpp into offsetof/sizeof; tests compare the two on every device.
 * OpenCL C and C++ only (GLSL has no pointers to measure with).
 *
 * When a struct or field is added to gc_types.h, add it here too.
 */
#if !defined(GC_LAYOUT_SIZE) || !defined(GC_LAYOUT_FIELD)
#error "define GC_LAYOUT_SIZE(S) and GC_LAYOUT_FIELD(S, f) before including gc_layout_list.h"
#endif

GC_LAYOUT_SIZE(GcRay)
GC_LAYOUT_FIELD(GcRay, org_tmin)
GC_LAYOUT_FIELD(GcRay, dir_tmax)

GC_LAYOUT_SIZE(GcHit)
GC_LAYOUT_FIELD(GcHit, t)
GC_LAYOUT_FIELD(GcHit, u)
GC_LAYOUT_FIELD(GcHit, v)
GC_LAYOUT_FIELD(GcHit, prim)

GC_LAYOUT_SIZE(GcBvhNode)
GC_LAYOUT_FIELD(GcBvhNode, lo)
GC_LAYOUT_FIELD(GcBvhNode, hi)

GC_LAYOUT_SIZE(GcTriangle)
GC_LAYOUT_FIELD(GcTriangle, v0)
GC_LAYOUT_FIELD(GcTriangle, v1)
GC_LAYOUT_FIELD(GcTriangle, v2)

GC_LAYOUT_SIZE(GcTriangleAttribs)
GC_LAYOUT_FIELD(GcTriangleAttribs, n0)
GC_LAYOUT_FIELD(GcTriangleAttribs, n1)
GC_LAYOUT_FIELD(GcTriangleAttribs, n2)
GC_LAYOUT_FIELD(GcTriangleAttribs, ng)
GC_LAYOUT_FIELD(GcTriangleAttribs, uv01)
GC_LAYOUT_FIELD(GcTriangleAttribs, uv2_u)
GC_LAYOUT_FIELD(GcTriangleAttribs, uv2_v)
GC_LAYOUT_FIELD(GcTriangleAttribs, material)
GC_LAYOUT_FIELD(GcTriangleAttribs, flags)
GC_LAYOUT_FIELD(GcTriangleAttribs, tangent)

GC_LAYOUT_SIZE(GcMaterial)
GC_LAYOUT_FIELD(GcMaterial, albedo)
GC_LAYOUT_FIELD(GcMaterial, specular)
GC_LAYOUT_FIELD(GcMaterial, emission)
GC_LAYOUT_FIELD(GcMaterial, pbr)
GC_LAYOUT_FIELD(GcMaterial, type)
GC_LAYOUT_FIELD(GcMaterial, albedo_texture)
GC_LAYOUT_FIELD(GcMaterial, metallic_roughness_texture)
GC_LAYOUT_FIELD(GcMaterial, normal_texture)
GC_LAYOUT_FIELD(GcMaterial, emission_texture)
GC_LAYOUT_FIELD(GcMaterial, flags)
GC_LAYOUT_FIELD(GcMaterial, normal_scale)
GC_LAYOUT_FIELD(GcMaterial, pad1)

GC_LAYOUT_SIZE(GcTexture)
GC_LAYOUT_FIELD(GcTexture, offset)
GC_LAYOUT_FIELD(GcTexture, width)
GC_LAYOUT_FIELD(GcTexture, height)
GC_LAYOUT_FIELD(GcTexture, flags)

GC_LAYOUT_SIZE(GcEmitter)
GC_LAYOUT_FIELD(GcEmitter, v0)
GC_LAYOUT_FIELD(GcEmitter, v1)
GC_LAYOUT_FIELD(GcEmitter, v2)
GC_LAYOUT_FIELD(GcEmitter, triangle)
GC_LAYOUT_FIELD(GcEmitter, area)
GC_LAYOUT_FIELD(GcEmitter, pmf)
GC_LAYOUT_FIELD(GcEmitter, cdf)

GC_LAYOUT_SIZE(GcPointLight)
GC_LAYOUT_FIELD(GcPointLight, position)
GC_LAYOUT_FIELD(GcPointLight, intensity)

GC_LAYOUT_SIZE(GcCamera)
GC_LAYOUT_FIELD(GcCamera, origin)
GC_LAYOUT_FIELD(GcCamera, forward)
GC_LAYOUT_FIELD(GcCamera, right)
GC_LAYOUT_FIELD(GcCamera, up)

GC_LAYOUT_SIZE(GcRenderParams)
GC_LAYOUT_FIELD(GcRenderParams, camera)
GC_LAYOUT_FIELD(GcRenderParams, env_radiance)
GC_LAYOUT_FIELD(GcRenderParams, width)
GC_LAYOUT_FIELD(GcRenderParams, height)
GC_LAYOUT_FIELD(GcRenderParams, sample_index)
GC_LAYOUT_FIELD(GcRenderParams, seed)
GC_LAYOUT_FIELD(GcRenderParams, max_depth)
GC_LAYOUT_FIELD(GcRenderParams, integrator)
GC_LAYOUT_FIELD(GcRenderParams, aov)
GC_LAYOUT_FIELD(GcRenderParams, num_triangles)
GC_LAYOUT_FIELD(GcRenderParams, num_emitters)
GC_LAYOUT_FIELD(GcRenderParams, num_point_lights)
GC_LAYOUT_FIELD(GcRenderParams, num_textures)
GC_LAYOUT_FIELD(GcRenderParams, flags)
GC_LAYOUT_FIELD(GcRenderParams, pixel_offset)
GC_LAYOUT_FIELD(GcRenderParams, pixel_count)
GC_LAYOUT_FIELD(GcRenderParams, rr_depth)
GC_LAYOUT_FIELD(GcRenderParams, emitter_power)
GC_LAYOUT_FIELD(GcRenderParams, env_width)
GC_LAYOUT_FIELD(GcRenderParams, env_height)
GC_LAYOUT_FIELD(GcRenderParams, samples_in_pass)
GC_LAYOUT_FIELD(GcRenderParams, pad2)

GC_LAYOUT_SIZE(GcPathState)
GC_LAYOUT_FIELD(GcPathState, throughput)
GC_LAYOUT_FIELD(GcPathState, radiance)
GC_LAYOUT_FIELD(GcPathState, pixel)
GC_LAYOUT_FIELD(GcPathState, depth)
GC_LAYOUT_FIELD(GcPathState, flags)
GC_LAYOUT_FIELD(GcPathState, sample)

GC_LAYOUT_SIZE(GcShadowRay)
GC_LAYOUT_FIELD(GcShadowRay, ray)
GC_LAYOUT_FIELD(GcShadowRay, contribution)
GC_LAYOUT_FIELD(GcShadowRay, slot)
GC_LAYOUT_FIELD(GcShadowRay, pad0)
GC_LAYOUT_FIELD(GcShadowRay, pad1)
GC_LAYOUT_FIELD(GcShadowRay, pad2)
