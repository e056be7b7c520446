// Host reference of the two-level traversal: kernels/shared/gc_traverse_instances.h over an
// InstancedBvh in each layout, every triangle opaque (as trace_instances.cl does). One
// translation unit per layout, since the layout is a macro chosen before the shared headers.
#pragma once

#include "gc_instance.h"
#include "host/bvh/instance_bvh.h"
#include "host/math/ray.h"

namespace gc {

// instance == GC_INVALID on a miss; hit.prim indexes the scene of meshes.
dev::GcInstanceHit trace_closest(const InstancedBvh& bvh, const Ray& ray);
bool trace_any(const InstancedBvh& bvh, const Ray& ray);
dev::GcInstanceHit trace_closest(const InstancedBvh4& bvh, const Ray& ray);
bool trace_any(const InstancedBvh4& bvh, const Ray& ray);
dev::GcInstanceHit trace_closest(const InstancedBvh8& bvh, const Ray& ray);
bool trace_any(const InstancedBvh8& bvh, const Ray& ray);

}  // namespace gc
