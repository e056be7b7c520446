/*
 * aov_instances.comp — Vulkan compute reference of kernels/aov_instances.cl: first-hit AOVs
 * of an instanced scene through the two-level BVH (gc_traverse_instances.h). The bottom
 * trees of every mesh share the NODES and TRIS bindings; GLSL has no pointers to offset, so
 * the accessors add the hit instance's bases, which gc_use_mesh sets before each descent.
 */
#version 450
#define GC_VK_COMPUTE 1
#include "scene_bindings.glsl"
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

#include "gc_aov_instance.h"
#include "gc_traverse_instances.h"

layout(local_size_x = GC_VK_LOCAL_SIZE) in;
layout(push_constant) uniform Push { uint sample_index; } push;

void main()
{
    GcRenderParams params = params_data;
    params.sample_index = push.sample_index;
    const uint i = gl_GlobalInvocationID.x;
    if (i >= params.pixel_count) return;
    const uint pixel = params.pixel_offset + i;
    const GcRay ray = gc_aov_camera_ray(params, pixel);
    const GcInstanceHit h = gc_trace_instances(GC_INSTANCE_ARGS, GC_BVH_ARGS, ray, false);
    vec3 value;
    if (h.instance == GC_INVALID) {
        value = gc_aov_value(GC_SHADE_ARGS, params, ray, h.hit);
    } else {
        value = gc_aov_instance_value(GC_SHADE_ARGS, params, gc_instances[h.slot], ray, h.hit);
    }
    film[pixel] += vec4(value, 1.0f);
}
