// The host reference over the BVH8 layout (gc_traverse8.h), as traverse_wide_host.cpp is
// for the BVH4: a translation unit of its own because the layout is chosen by macros.
#define GC_BVH_WIDE 1
#define GC_BVH_WIDE8 1
#define GC_TRACE_OPAQUE 1
#include "gc_traverse.h"
#include "host/bvh/traverse_host.h"
#include "host/math/to_device.h"

namespace gc {

dev::GcHit trace_closest(const Wide8Bvh& bvh, const Ray& ray)
{
    return dev::gc_trace_closest(bvh.nodes.data(), bvh.blocks.data(), to_device(ray));
}

bool trace_any(const Wide8Bvh& bvh, const Ray& ray)
{
    return dev::gc_trace_any(bvh.nodes.data(), bvh.blocks.data(), to_device(ray));
}

}  // namespace gc
