/*
 * gc_traverse_instances.h — two-level traversal: a top-level BVH2 over instances, each an
 * affine copy of a mesh whose own bottom-level BVH is traversed in the device's layout
 * (gc_traverse.h picks BVH2, BVH4 or BVH8 by the program's options). Shared dialect of gc_platform.h for OpenCL C
 * and C++, and GLSL, where the bottom trees are offset by bases in the accessors instead of
 * by pointer arithmetic (kernels/vk/instances.glsl).
 *
 * Buffers (host/bvh/instance_bvh.h builds them):
 *   - gc_tlas_nodes: GcBvhNode[] over the instances' world bounds; a leaf's first/count index
 *     gc_instances, which are stored in leaf order;
 *   - gc_instances: GcInstance[], each with its world-to-object transform and where its mesh's
 *     bottom-level tree starts in the layout's node and triangle arrays;
 *   - the usual GC_BVH_PARAMS: every mesh's bottom-level tree, concatenated. Each tree keeps
 *     its own node 0 as root and its own in-tree indices, so the bottom traversal runs
 *     unchanged on the arrays offset by node_base and tri_base.
 * Triangles carry their index in the scene of meshes (all meshes' triangles, mesh by mesh),
 * which is what shading and the alpha test index by.
 *
 * The ray enters object space by the affine map alone: the direction is not renormalised, so
 * a point at parameter t in object space is the world point at the same t, and t_min, t_max
 * and hit distances compare across instances without conversion.
 *
 * Tie rule: the closest hit is the minimum of (t, instance id, triangle index) in
 * lexicographic order. The bottom traversal already returns its mesh's minimum of
 * (t, triangle) with t <= the best so far (inclusive), so an instance's hit replaces the best
 * when its t is smaller or, at equal t, when its instance id is smaller. That is the order of
 * a flattened scene that lists instances in id order, each instance's triangles in mesh order,
 * so both agree wherever the transforms round alike (host/scene/instances.h says when).
 *
 * Misses: instance == GC_INVALID and the hit is gc_no_hit().
 */
#ifndef GC_TRAVERSE_INSTANCES_H
#define GC_TRAVERSE_INSTANCES_H

#include "gc_instance.h"
#include "gc_traverse.h"

GC_NAMESPACE_BEGIN

/* The bottom traversal over one mesh's tree, whose arrays the caller passes offset. */
GC_FUNC GcHit gc_trace_mesh(GC_BVH_PARAMS, GcRay ray, bool any_hit)
{
    return GC_TRACE_BODY(ray, any_hit);
}

#if defined(GC_GLSL)
/* GLSL: the buffers are the SSBOs gc_tlas_nodes and gc_instances, and the shader's
 * GC_BVH_NODE / GC_BVH_TRI add the bases that gc_use_mesh(inst) sets (kernels/vk/instances.glsl). */
#define GC_MESH_ARGS(inst) gc_use_mesh(inst)
#define GC_INSTANCE_PARAMS uint gc_instance_unused
#define GC_INSTANCE_ARGS 0u
#else
#if defined(GC_TRACE_OPAQUE)
#define GC_MESH_ARGS(inst) gc_bvh_nodes + (inst).node_base, gc_bvh_tris + (inst).tri_base
#else
#define GC_MESH_ARGS(inst) gc_bvh_nodes + (inst).node_base, gc_bvh_tris + (inst).tri_base, GC_ALPHA_ARGS
#endif
#define GC_INSTANCE_PARAMS GC_GLOBAL const GcBvhNode *gc_tlas_nodes, GC_GLOBAL const GcInstance *gc_instances
#define GC_INSTANCE_ARGS gc_tlas_nodes, gc_instances
#endif

/* The top level is gc_trace_impl's ordered BVH2 walk with instances in place of triangles. */
GC_FUNC GcInstanceHit gc_trace_instances(GC_INSTANCE_PARAMS, GC_BVH_PARAMS, GcRay ray, bool any_hit)
{
    GcInstanceHit best = gc_no_instance_hit();
    if (!gc_ray_is_valid(ray)) return best;

    GcRayPre r = gc_ray_precompute(ray);
    float t_best = gc_ray_tmax(ray);

    uint stack_node[GC_BVH_STACK_SIZE];
    float stack_entry[GC_BVH_STACK_SIZE];
    uint sp = 0u;

    GcBvhNode node = gc_tlas_nodes[0];
    r = gc_ray_with_margin(r, GC_XYZ(node.lo), GC_XYZ(node.hi));
    if (!(gc_intersect_aabb_pre(r, t_best, GC_XYZ(node.lo), GC_XYZ(node.hi)) < GC_AABB_MISS)) return best;

    for (;;) {
        if (gc_node_is_leaf(node)) {
            uint first = gc_node_first(node);
            uint end = first + gc_node_count(node);
            for (uint i = first; i < end; ++i) {
                GcInstance inst = gc_instances[i];
                GcRay object_ray = gc_instance_ray(inst, ray);
                object_ray.dir_tmax.w = t_best;
                GcHit h = gc_trace_mesh(GC_MESH_ARGS(inst), object_ray, any_hit);
                if (h.prim == GC_INVALID) continue;
                /* h.t <= t_best: lexicographic (t, instance id); the mesh settled the triangle. */
                if (h.t < t_best || inst.id < best.instance) {
                    best.hit = h;
                    best.instance = inst.id;
                    best.slot = i;
                    t_best = h.t;
                    if (any_hit) return best;
                }
            }
        } else {
            uint first = gc_node_first(node);
            GcBvhNode c0 = gc_tlas_nodes[first];
            GcBvhNode c1 = gc_tlas_nodes[first + 1u];
            float e0 = gc_intersect_aabb_pre(r, t_best, GC_XYZ(c0.lo), GC_XYZ(c0.hi));
            float e1 = gc_intersect_aabb_pre(r, t_best, GC_XYZ(c1.lo), GC_XYZ(c1.hi));
            bool hit0 = e0 < GC_AABB_MISS;
            bool hit1 = e1 < GC_AABB_MISS;
            if (hit0 && hit1) {
                bool swap = e1 < e0;
                node = swap ? c1 : c0;
                if (sp < GC_BVH_STACK_SIZE) {
                    stack_node[sp] = swap ? first : first + 1u;
                    stack_entry[sp] = swap ? e0 : e1;
                    ++sp;
                }
                continue;
            }
            if (hit0 || hit1) {
                node = hit0 ? c0 : c1;
                continue;
            }
        }
        bool found = false;
        while (sp > 0u && !found) {
            --sp;
            found = gc_aabb_entry_within(stack_entry[sp], t_best);
        }
        if (!found) break;
        node = gc_tlas_nodes[stack_node[sp]];
    }
    return best;
}

GC_NAMESPACE_END

#endif /* GC_TRAVERSE_INSTANCES_H */
