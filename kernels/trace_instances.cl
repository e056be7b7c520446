/*
 * trace_instances.cl — the two-level traversal (gc_traverse_instances.h) for a buffer of rays,
 * every triangle opaque: used by tests/render/instance_device_test.cpp and tools/stress/instanced_mesh.cpp. Built with
 * the layout's options (program_options(BvhLayout)), like trace.cl.
 */
#define GC_TRACE_OPAQUE 1
#include "gc_traverse_instances.h"

__kernel void trace_instances_closest(__global const GcBvhNode* gc_tlas_nodes,
                                      __global const GcInstance* gc_instances,
                                      __global const GcTraversalNode* gc_bvh_nodes,
                                      __global const GcTraversalTriangle* gc_bvh_tris,
                                      __global const GcRay* rays,
                                      __global GcInstanceHit* hits,
                                      __global uint* occluded,
                                      const uint count)
{
    const uint i = get_global_id(0);
    if (i >= count) return;
    hits[i] = gc_trace_instances(GC_INSTANCE_ARGS, GC_BVH_ARGS, rays[i], false);
    occluded[i] = gc_trace_instances(GC_INSTANCE_ARGS, GC_BVH_ARGS, rays[i], true).instance != GC_INVALID ? 1u : 0u;
}
