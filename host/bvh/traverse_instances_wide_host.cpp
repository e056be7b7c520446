// The two-level reference over the InstancedBvh4 layout (traverse_instances_host.h).
#define GC_BVH_WIDE 1
#define GC_TRACE_OPAQUE 1
#include "gc_traverse_instances.h"
#include "host/bvh/traverse_instances_host.h"
#include "host/math/to_device.h"

namespace gc {

dev::GcInstanceHit trace_closest(const InstancedBvh4& bvh, const Ray& ray)
{
    return dev::gc_trace_instances(bvh.tlas.data(), bvh.instances.data(), bvh.nodes.data(), bvh.tris.data(),
                                   to_device(ray), false);
}

bool trace_any(const InstancedBvh4& bvh, const Ray& ray)
{
    return dev::gc_trace_instances(bvh.tlas.data(), bvh.instances.data(), bvh.nodes.data(), bvh.tris.data(),
                                   to_device(ray), true)
               .instance != GC_INVALID;
}

}  // namespace gc
