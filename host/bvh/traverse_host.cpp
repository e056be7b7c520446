// The plain reference: every triangle opaque, the BVH's buffers only (gc_traverse.h).
#define GC_TRACE_OPAQUE 1
#include "host/bvh/traverse_host.h"

#include "gc_traverse.h"
#include "host/math/to_device.h"

namespace gc {

dev::GcHit trace_closest(const FlatBvh& bvh, const Ray& ray)
{
    return dev::gc_trace_closest(bvh.nodes.data(), bvh.triangles.data(), to_device(ray));
}

bool trace_any(const FlatBvh& bvh, const Ray& ray)
{
    return dev::gc_trace_any(bvh.nodes.data(), bvh.triangles.data(), to_device(ray));
}

dev::GcHit trace_brute_force(const Scene& scene, const Ray& ray)
{
    return trace_brute_force(scene, ray, AlphaBuffers{});
}

}  // namespace gc
