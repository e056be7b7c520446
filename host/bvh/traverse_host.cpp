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
    const dev::GcRay device_ray = to_device(ray);
    dev::GcHit best;
    best.t = GC_INFINITY;
    best.u = 0.0f;
    best.v = 0.0f;
    best.prim = GC_INVALID;
    if (!dev::gc_ray_is_valid(device_ray)) return best;
    const dev::GcRayPre pre = dev::gc_ray_precompute(device_ray);
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
        // The ray's own t_max bounds every test, so the accepted t never depends on the order.
        const dev::GcHit h = dev::gc_intersect_triangle(pre, scene.vertex(i, 0).glm(), scene.vertex(i, 1).glm(),
                                                        scene.vertex(i, 2).glm(), ray.tmax);
        if (h.prim == GC_INVALID) continue;
        const auto prim = static_cast<std::uint32_t>(i);
        if (best.prim == GC_INVALID || h.t < best.t || (h.t == best.t && prim < best.prim)) {
            best = h;
            best.prim = prim;
        }
    }
    return best;
}

}  // namespace gc
