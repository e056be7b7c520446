// Host reference traversal. trace_closest/trace_any run kernels/shared/gc_traverse.h, the
// very code the OpenCL kernels run, over a FlatBvh; trace_brute_force is the independent
// check: every triangle of the scene through the same gc_intersect.h test and the same tie
// rule (equal t: smaller scene triangle index wins), no BVH involved.
#pragma once

#include <cstdint>

#include "gc_types.h"
#include "host/bvh/flatten.h"
#include "host/bvh/widen.h"
#include "host/math/ray.h"
#include "host/scene/scene.h"

namespace gc {

// prim == GC_INVALID (and t = +inf) on a miss; (u, v) are the barycentrics of v1 and v2.
// These treat every triangle as opaque, as trace.cl does.
dev::GcHit trace_closest(const FlatBvh& bvh, const Ray& ray);
bool trace_any(const FlatBvh& bvh, const Ray& ray);
dev::GcHit trace_brute_force(const Scene& scene, const Ray& ray);

// The same queries over the BVH4 layout CPUs read (traverse_wide_host.cpp).
dev::GcHit trace_closest(const WideBvh& bvh, const Ray& ray);
bool trace_any(const WideBvh& bvh, const Ray& ray);
dev::GcHit trace_closest(const Wide8Bvh& bvh, const Ray& ray);
bool trace_any(const Wide8Bvh& bvh, const Ray& ray);

// The buffers the alpha-MASK test reads (kernels/shared/gc_alpha.h), in device form, as
// host/render/scene_convert.h makes them for upload. textures/texels may be null when no
// alpha-tested material has a texture.
struct AlphaBuffers {
    const dev::GcTriangleAttribs* attribs = nullptr;
    const dev::GcMaterial* materials = nullptr;
    const dev::GcTexture* textures = nullptr;
    const std::uint32_t* texels = nullptr;
};

// As above, but candidate hits on alpha-MASK cut-outs are skipped, as extend.cl and
// shadow.cl do (traverse_alpha_host.cpp). The brute force decides "alpha tested" from the
// scene (triangle_alpha_tested), not from the BVH's flags.
dev::GcHit trace_closest(const FlatBvh& bvh, const Ray& ray, const AlphaBuffers& alpha);
bool trace_any(const FlatBvh& bvh, const Ray& ray, const AlphaBuffers& alpha);
dev::GcHit trace_closest(const WideBvh& bvh, const Ray& ray, const AlphaBuffers& alpha);
bool trace_any(const WideBvh& bvh, const Ray& ray, const AlphaBuffers& alpha);
dev::GcHit trace_closest(const Wide8Bvh& bvh, const Ray& ray, const AlphaBuffers& alpha);
bool trace_any(const Wide8Bvh& bvh, const Ray& ray, const AlphaBuffers& alpha);
dev::GcHit trace_brute_force(const Scene& scene, const Ray& ray, const AlphaBuffers& alpha);

}  // namespace gc
