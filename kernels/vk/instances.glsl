/*
 * instances.glsl — the two-level BVH of an instanced scene for the Vulkan passes that trace
 * one (aov.comp, path.comp and whitted.comp built with GC_SCENE_INSTANCED): the
 * top level's nodes and the instances (gc_instance.h), and the accessors through which the
 * bottom traversal (gc_traverse_instances.h) reads every mesh's tree from the shared NODES and
 * TRIS bindings. GLSL has no pointers to offset, so the accessors add the bases of the hit
 * instance's mesh, which gc_use_mesh sets before each descent.
 * Include after scene_bindings.glsl and before the traversal headers.
 */
#include "gc_instance.h"

layout(std430, set = 0, binding = GC_VK_BINDING_TLAS) readonly buffer TlasBuffer { GcBvhNode gc_tlas_nodes[]; };
layout(std430, set = 0, binding = GC_VK_BINDING_INSTANCES) readonly buffer InstanceBuffer { GcInstance gc_instances[]; };

uint gc_mesh_node_base = 0u;
uint gc_mesh_tri_base = 0u;
#undef GC_BVH_NODE
#undef GC_BVH_TRI
#define GC_BVH_NODE(i) bvh_nodes[gc_mesh_node_base + (i)]
#define GC_BVH_TRI(i) bvh_tris[gc_mesh_tri_base + (i)]

uint gc_use_mesh(GcInstance inst)
{
    gc_mesh_node_base = inst.node_base;
    gc_mesh_tri_base = inst.tri_base;
    return 0u;
}
