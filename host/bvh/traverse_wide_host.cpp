// The host reference over the BVH4 layout: gc_traverse.h compiled with GC_BVH_WIDE, the
// body CPU devices run (gc_traverse4.h). A translation unit of its own because the layout is
// chosen by a macro before the shared headers are included; the overloads differ in their
// parameter types (GcBvh4Node, GcTriangle4), so they do not collide with the BVH2 ones.
#define GC_BVH_WIDE 1
#define GC_TRACE_OPAQUE 1
#include "gc_traverse.h"
#include "host/bvh/traverse_host.h"
#include "host/math/to_device.h"

namespace gc {

dev::GcHit trace_closest(const WideBvh& bvh, const Ray& ray)
{
    return dev::gc_trace_closest(bvh.nodes.data(), bvh.blocks.data(), to_device(ray));
}

bool trace_any(const WideBvh& bvh, const Ray& ray)
{
    return dev::gc_trace_any(bvh.nodes.data(), bvh.blocks.data(), to_device(ray));
}

}  // namespace gc
