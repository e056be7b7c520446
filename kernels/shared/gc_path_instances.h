/*
 * gc_path_instances.h — the path integrator's steps on an instanced scene (a program built
 * with -D GC_SCENE_INSTANCED, kernels/megakernel.cl): rays go through the two-level BVH
 * (gc_traverse_instances.h), and a hit is shaded by the flat scene's gc_shade_surface with its
 * triangle's attributes taken to world space (gc_instance_attribs.h). Emitters need nothing:
 * the host lists every emissive (instance, triangle) pair in world space, with world-space
 * attributes of their own after the meshes' (host/render/instanced_scene_upload.h), so light
 * sampling reads them as it reads a flat scene's. OpenCL C and C++ (no GLSL: the Vulkan
 * reference renders instanced scenes flattened).
 */
#ifndef GC_PATH_INSTANCES_H
#define GC_PATH_INSTANCES_H

#include "gc_instance_attribs.h"
#include "gc_path_vertex.h"
#include "gc_traverse_instances.h"

GC_NAMESPACE_BEGIN

GC_FUNC GcVertexResult gc_shade_instance_vertex(GC_SHADE_PARAMS, GC_GLOBAL const GcInstance* instances,
                                                GcRenderParams params, GcPathState path, GcRay ray, GcInstanceHit h)
{
    if (h.instance == GC_INVALID) return gc_shade_escape(GC_SHADE_ARGS, params, path, ray);
    return gc_shade_surface(GC_SHADE_ARGS, params, path, ray, h.hit,
                            gc_instance_attribs(instances[h.slot], GC_ATTRIB(h.hit.prim)));
}

GC_NAMESPACE_END

#endif /* GC_PATH_INSTANCES_H */
