// The bench's host-side work count (traversal_cost), which the GPU roofline line is built
// from: it must average over rays spread through the whole set. A primary set's first rays
// are the image's top rows, often all background; counting only those read 0 inner nodes
// per ray for the dragon's primary rays.
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "gc_accessors.h"
#include "host/bvh/bvh.h"
#include "tests/bvh/test_scenes.h"
#include "tools/bench/rays.h"

namespace gc::bench {
namespace {

dev::GcRay ray(float ox, float oy, float oz, float dx, float dy, float dz)
{
    return dev::gc_make_ray({ox, oy, oz}, {dx, dy, dz}, 0.0f, GC_RAY_UNBOUNDED);
}

TEST(BenchRays, TraversalCostCountsRaysFromTheWholeSet)
{
    const Scene scene = test::random_soup(4000, 5);  // in [-1, 1]^3
    const FlatBvh bvh = build_bvh(scene);
    // First half: rays beside the scene, pointing away from it (they miss the root's box);
    // second half: rays through the soup along z.
    std::vector<dev::GcRay> rays;
    for (int i = 0; i < 1000; ++i) rays.push_back(ray(-3.0f, -3.0f, -3.0f - 0.001f * float(i), -1.0f, 0.0f, 0.0f));
    for (int i = 0; i < 1000; ++i)
        rays.push_back(ray(-0.9f + 0.0018f * float(i), 0.5f - 0.001f * float(i), -3.0f, 0.0f, 0.0f, 1.0f));
    const TraversalCost every = traversal_cost(bvh, rays, false, rays.size());
    const TraversalCost sampled = traversal_cost(bvh, rays, false, 500);
    const TraversalCost any = traversal_cost(bvh, rays, true, 500);
    std::printf("[ bench rays ] inner nodes per ray: all 2000 rays %.2f, 500 sampled %.2f (any hit %.2f); "
                "triangle tests %.2f / %.2f\n",
                every.inner_visits, sampled.inner_visits, any.inner_visits, every.triangle_tests,
                sampled.triangle_tests);
    EXPECT_GT(every.inner_visits, 2.0) << "half the rays cross the soup";
    EXPECT_NEAR(sampled.inner_visits, every.inner_visits, 0.15 * every.inner_visits)
        << "500 rays spread over the set must see both halves";
    EXPECT_NEAR(sampled.triangle_tests, every.triangle_tests, 0.15 * every.triangle_tests);
    EXPECT_GT(any.inner_visits, 0.0);
    EXPECT_LE(any.inner_visits, sampled.inner_visits) << "an any-hit query stops at its first hit";
}

}  // namespace
}  // namespace gc::bench
