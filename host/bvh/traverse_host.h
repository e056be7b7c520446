// Host reference traversal. trace_closest/trace_any run kernels/shared/gc_traverse.h, the
// very code the OpenCL kernels run, over a FlatBvh; trace_brute_force is the independent
// check: every triangle of the scene through the same gc_intersect.h test and the same tie
// rule (equal t: smaller scene triangle index wins), no BVH involved.
#pragma once

#include "gc_types.h"
#include "host/bvh/flatten.h"
#include "host/math/ray.h"
#include "host/scene/scene.h"

namespace gc {

// prim == GC_INVALID (and t = +inf) on a miss; (u, v) are the barycentrics of v1 and v2.
dev::GcHit trace_closest(const FlatBvh& bvh, const Ray& ray);
bool trace_any(const FlatBvh& bvh, const Ray& ray);
dev::GcHit trace_brute_force(const Scene& scene, const Ray& ray);

}  // namespace gc
