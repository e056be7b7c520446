/*
 * gc_scene_trace.h — tracing the scene a program was built for: a flat scene's BVH, or an
 * instanced scene's two-level BVH (-D GC_SCENE_INSTANCED, which the host sets for a scene
 * uploaded by DeviceScene::upload_instanced). The kernels that render either (megakernel.cl,
 * whitted.cl and the wavefront's extend, shade and shadow stages) take GC_INSTANCES_FIRST_PARAMS
 * before their scene buffers and trace and shade through the names below, so one body serves
 * both:
 *
 *   GcSceneHit            a closest hit: GcHit, or GcInstanceHit (its hit and its instance)
 *   gc_scene_closest(r)   the closest hit of ray r
 *   gc_scene_occluded(r)  whether anything blocks ray r
 *   gc_scene_hit(h)       the GcHit of a GcSceneHit (prim GC_INVALID: a miss)
 *   gc_scene_attribs(h)   the hit triangle's attributes in world space (an instance's through
 *                         gc_instance_attribs.h)
 *   gc_shade_scene_vertex(params, path, ray, h)
 *                         gc_shade_vertex (gc_path_vertex.h, which the user includes) for h
 *   GC_INSTANCES_FIRST_UNUSED()  marks the instance buffers used, in a kernel that only shades
 *
 * Like the element accessors (GC_ATTRIB, gc_scene_buffers.h), these read the enclosing
 * function's buffer parameters by name (GLSL: the SSBOs of kernels/vk/scene_bindings.glsl and,
 * instanced, instances.glsl). A flat program's code is the plain traversal's.
 */
#ifndef GC_SCENE_TRACE_H
#define GC_SCENE_TRACE_H

#if defined(GC_SCENE_INSTANCED)

#include "gc_instance_attribs.h"
#include "gc_traverse_instances.h"

#define GC_INSTANCES_FIRST_PARAMS GC_INSTANCE_PARAMS,
#define GC_INSTANCES_FIRST_ARGS GC_INSTANCE_ARGS,
#define GcSceneHit GcInstanceHit
#define gc_scene_closest(r) gc_trace_instances(GC_INSTANCE_ARGS, GC_BVH_ARGS, r, false)
#define gc_scene_occluded(r) (gc_trace_instances(GC_INSTANCE_ARGS, GC_BVH_ARGS, r, true).instance != GC_INVALID)
#define gc_scene_hit(h) ((h).hit)
#define gc_scene_attribs(h) gc_instance_attribs(gc_instances[(h).slot], GC_ATTRIB((h).hit.prim))
#define GC_INSTANCES_FIRST_UNUSED() (void)gc_tlas_nodes

#else

#include "gc_traverse.h"

#define GC_INSTANCES_FIRST_PARAMS
#define GC_INSTANCES_FIRST_ARGS
#define GcSceneHit GcHit
#define gc_scene_closest(r) gc_trace_closest(GC_BVH_ARGS, r)
#define gc_scene_occluded(r) gc_trace_any(GC_BVH_ARGS, r)
#define gc_scene_hit(h) (h)
#define gc_scene_attribs(h) GC_ATTRIB((h).prim)
#define GC_INSTANCES_FIRST_UNUSED()

#endif

/* h (a variable) evaluated once per use; the ternary runs one of the two calls. */
#define gc_shade_scene_vertex(params, path, ray, h)                                                   \
    (gc_scene_hit(h).prim == GC_INVALID                                                                \
         ? gc_shade_escape(GC_SHADE_ARGS, params, path, ray)                                           \
         : gc_shade_surface(GC_SHADE_ARGS, params, path, ray, gc_scene_hit(h), gc_scene_attribs(h)))

#endif /* GC_SCENE_TRACE_H */
