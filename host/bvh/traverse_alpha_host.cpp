// The host reference with the alpha-MASK test: gc_traverse.h as extend.cl and shadow.cl
// compile it (gc_alpha.h's hook), and the brute force that checks it. A translation unit of
// its own because the plain reference defines GC_TRACE_OPAQUE for the whole unit; the
// overloads differ in their parameters, so the two instantiations do not collide.
#include "gc_alpha.h"
#include "gc_traverse.h"
#include "host/bvh/traverse_host.h"
#include "host/math/to_device.h"

namespace gc {

dev::GcHit trace_closest(const FlatBvh& bvh, const Ray& ray, const AlphaBuffers& a)
{
    return dev::gc_trace_closest(bvh.nodes.data(), bvh.triangles.data(), a.attribs, a.materials, a.textures, a.texels,
                                 to_device(ray));
}

bool trace_any(const FlatBvh& bvh, const Ray& ray, const AlphaBuffers& a)
{
    return dev::gc_trace_any(bvh.nodes.data(), bvh.triangles.data(), a.attribs, a.materials, a.textures, a.texels,
                             to_device(ray));
}

// Without buffers (a.attribs == nullptr) every triangle is opaque: the plain brute force.
dev::GcHit trace_brute_force(const Scene& scene, const Ray& ray, const AlphaBuffers& a)
{
    const dev::GcRay device_ray = to_device(ray);
    dev::GcHit best = dev::gc_no_hit();
    if (!dev::gc_ray_is_valid(device_ray)) return best;
    const dev::GcRayPre pre = dev::gc_ray_precompute(device_ray);
    for (std::size_t i = 0; i < scene.triangle_count(); ++i) {
        // The ray's own t_max bounds every test, so the accepted t never depends on the order.
        const dev::GcHit h = dev::gc_intersect_triangle(pre, scene.vertex(i, 0).glm(), scene.vertex(i, 1).glm(),
                                                        scene.vertex(i, 2).glm(), ray.tmax);
        if (h.prim == GC_INVALID) continue;
        const auto prim = static_cast<std::uint32_t>(i);
        if (a.attribs && triangle_alpha_tested(scene, i) &&
            !dev::gc_alpha_solid(a.attribs, a.materials, a.textures, a.texels, prim, h.u, h.v))
            continue;
        if (best.prim == GC_INVALID || h.t < best.t || (h.t == best.t && prim < best.prim)) {
            best = h;
            best.prim = prim;
        }
    }
    return best;
}

}  // namespace gc
