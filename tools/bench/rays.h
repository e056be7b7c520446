// The benchmark's ray sets: camera rays, then cosine-distributed diffuse rays and shadow rays
// from the camera rays' hits. Built once per scene on the host, so every device and Embree
// trace exactly the same rays.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "gc_types.h"
#include "host/bvh/flatten.h"
#include "host/scene/scene.h"

namespace gc::bench {

struct RaySet {
    std::vector<dev::GcRay> primary; // one per pixel of a width x height image, pixel centres
    std::vector<dev::GcRay> diffuse; // one per primary hit: cosine hemisphere about the facing normal
    std::vector<dev::GcRay> shadow;  // one per primary hit: towards a point on an emitter (t in [0, 0.999])
};

// Primary hits come from the host reference traversal (the kernels' own code), run on
// `threads` threads. Scenes without emitters aim their shadow rays at a square above the
// scene's bounds. Deterministic: a ray's random numbers are a hash of its index.
RaySet make_rays(const Scene& scene, const FlatBvh& bvh, const Camera& camera, int width, int height, int threads);

// Average work per ray of gc_traverse.h's ordered traversal, counted on the host over
// `sample` rays spread evenly through the set: inner-node visits (each reads both 32-byte
// children), leaves and triangle tests (48 bytes each). The GPU roofline estimate is built
// from these.
struct TraversalCost {
    double inner_visits = 0.0;
    double leaf_visits = 0.0;
    double triangle_tests = 0.0;
    // Bytes one ray reads, ignoring caches: the ray, its children pairs, its triangles, plus the result.
    double bytes_per_ray() const { return 32.0 + 64.0 * inner_visits + 48.0 * triangle_tests + 16.0; }
};
TraversalCost traversal_cost(const FlatBvh& bvh, const std::vector<dev::GcRay>& rays, bool any_hit,
                             std::size_t sample);

// Runs fn(begin, end) over [0, count) in chunks on `threads` std::threads.
void parallel_for(std::size_t count, int threads, std::size_t chunk,
                  const std::function<void(std::size_t, std::size_t)>& fn);

}  // namespace gc::bench
