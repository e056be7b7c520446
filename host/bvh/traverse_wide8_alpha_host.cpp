// The BVH8 host reference with the alpha-MASK hook (see traverse_wide8_host.cpp).
#define GC_BVH_WIDE 1
#define GC_BVH_WIDE8 1
#include "gc_traverse.h"
#include "host/bvh/traverse_host.h"
#include "host/math/to_device.h"

namespace gc {

dev::GcHit trace_closest(const Wide8Bvh& bvh, const Ray& ray, const AlphaBuffers& a)
{
    return dev::gc_trace_closest(bvh.nodes.data(), bvh.blocks.data(), a.attribs, a.materials, a.textures, a.texels,
                                 to_device(ray));
}

bool trace_any(const Wide8Bvh& bvh, const Ray& ray, const AlphaBuffers& a)
{
    return dev::gc_trace_any(bvh.nodes.data(), bvh.blocks.data(), a.attribs, a.materials, a.textures, a.texels,
                             to_device(ray));
}

}  // namespace gc
