// Host traversal (gc_traverse.h, the kernels' code) against brute force over every
// triangle, on scenes chosen to break BVHs: random soup, a closed sphere from inside and
// outside, axis-parallel rays with signed zeros, clipped intervals, empty and degenerate
// scenes, coincident centroids, exact ties.
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <limits>

#include <gtest/gtest.h>

#include "bvh_checks.h"
#include "test_scenes.h"

namespace gc::test {
namespace {

constexpr std::size_t kRays = 10000;

TEST(BvhTraverse, RandomSoupMatchesBruteForce)
{
    const Scene scene = random_soup(10000, 1);
    const FlatBvh bvh = build_bvh(scene);
    check_invariants(bvh, scene, 4);
    const TraceComparison c = compare_with_brute_force(bvh, scene, mixed_rays(scene, kRays, 2));
    expect_agreement(c, "soup 10k");
    EXPECT_GT(c.hits, kRays / 3) << "the rays must exercise hits";
}

TEST(BvhTraverse, SphereFromInsideIsWatertight)
{
    const Scene scene = uv_sphere(48, 96, 1.0f);
    const FlatBvh bvh = build_bvh(scene);
    check_invariants(bvh, scene, 4);
    Rng rng(3);
    std::vector<Ray> rays;
    for (std::size_t i = 0; i < kRays; ++i) rays.push_back({Point3(0, 0, 0), rng.direction()});
    // Straight at every vertex (where up to 6 triangles meet) and at edge midpoints.
    for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
        rays.push_back({Point3(0, 0, 0), scene.vertex(t, 0) - Point3(0, 0, 0)});
        rays.push_back({Point3(0, 0, 0), midpoint(scene.vertex(t, 0), scene.vertex(t, 1)) - Point3(0, 0, 0)});
    }
    std::size_t bvh_misses = 0;
    std::size_t any_misses = 0;
    for (const Ray& r : rays) {
        if (trace_closest(bvh, r).prim == GC_INVALID) ++bvh_misses;
        if (!trace_any(bvh, r)) ++any_misses;
    }
    std::printf("[ sphere inside ] %zu triangles, %zu rays from the centre: %zu closest misses, %zu any misses\n",
                scene.triangle_count(), rays.size(), bvh_misses, any_misses);
    EXPECT_EQ(bvh_misses, 0u);
    EXPECT_EQ(any_misses, 0u);
    rays.resize(kRays); // brute force on the random ones
    expect_agreement(compare_with_brute_force(bvh, scene, rays), "sphere inside");
}

TEST(BvhTraverse, SphereFromOutside)
{
    const Scene scene = uv_sphere(48, 96, 1.0f);
    const FlatBvh bvh = build_bvh(scene);
    Rng rng(4);
    std::vector<Ray> rays;
    std::size_t aimed = 0;
    for (std::size_t i = 0; i < kRays; ++i) {
        const Point3 o = Point3(0, 0, 0) + 3.0f * rng.direction();
        if (i % 2 == 0) {
            // At a point well inside the sphere: must hit.
            rays.push_back({o, (Point3(0, 0, 0) + 0.8f * rng.uniform() * rng.direction()) - o});
            ++aimed;
        } else {
            rays.push_back({o, rng.direction()});
        }
    }
    std::size_t aimed_misses = 0;
    for (std::size_t i = 0; i < rays.size(); i += 2)
        if (trace_closest(bvh, rays[i]).prim == GC_INVALID) ++aimed_misses;
    std::printf("[ sphere outside ] %zu rays aimed inside the sphere, %zu misses\n", aimed, aimed_misses);
    EXPECT_EQ(aimed_misses, 0u);
    expect_agreement(compare_with_brute_force(bvh, scene, rays), "sphere outside");
}

// Axis-aligned quads on a lattice plus a soup; rays along the axes with +-0 in the other two
// components, half of them starting exactly on lattice planes (box faces: the 0 * inf case).
TEST(BvhTraverse, AxisParallelRaysWithSignedZeros)
{
    Scene scene = random_soup(2000, 5, 0.1f);
    for (int k = -2; k <= 2; ++k) {
        const float c = 0.5f * static_cast<float>(k);
        add_triangle(scene, {c, -1, -1}, {c, 1, -1}, {c, 1, 1});
        add_triangle(scene, {c, -1, -1}, {c, 1, 1}, {c, -1, 1});
        add_triangle(scene, {-1, c, -1}, {1, c, -1}, {1, c, 1});
        add_triangle(scene, {-1, -1, c}, {1, -1, c}, {1, 1, c});
    }
    const FlatBvh bvh = build_bvh(scene);
    check_invariants(bvh, scene, 4);
    Rng rng(6);
    std::vector<Ray> rays;
    const Bounds3 box(Point3(-1.5f, -1.5f, -1.5f), Point3(1.5f, 1.5f, 1.5f));
    for (std::size_t i = 0; i < kRays; ++i) {
        Point3 o = rng.point(box);
        if (i % 2 == 1) {
            // Snap two coordinates onto vertex coordinates / lattice planes.
            const std::size_t t = rng.below(static_cast<std::uint32_t>(scene.triangle_count()));
            const Point3 v = scene.vertex(t, static_cast<int>(rng.below(3)));
            o = i % 4 == 1 ? Point3(o.x, v.y, v.z) : Point3(v.x, o.y, 0.5f * static_cast<float>(rng.below(5)) - 1.0f);
        }
        const int axis = static_cast<int>(rng.below(3));
        const float sign = rng.below(2) ? 1.0f : -1.0f;
        const float z1 = rng.below(2) ? 0.0f : -0.0f;
        const float z2 = rng.below(2) ? 0.0f : -0.0f;
        const Vec3 d = axis == 0 ? Vec3(sign, z1, z2) : (axis == 1 ? Vec3(z1, sign, z2) : Vec3(z1, z2, sign));
        rays.push_back({o, d});
    }
    const TraceComparison c = compare_with_brute_force(bvh, scene, rays);
    expect_agreement(c, "axis-parallel");
    EXPECT_GT(c.hits, kRays / 4);

    // A direct case: +x ray with -0 / +0 components through the middle of the x = 0 quad.
    for (float z1 : {0.0f, -0.0f}) {
        for (float z2 : {0.0f, -0.0f}) {
            const dev::GcHit h = trace_closest(bvh, {Point3(-0.25f, 0.2f, 0.3f), Vec3(1, z1, z2)});
            EXPECT_NE(h.prim, GC_INVALID);
            EXPECT_LE(h.t, 0.25f);
        }
    }
}

TEST(BvhTraverse, IntervalExcludingTheHit)
{
    const Scene scene = random_soup(10000, 7);
    const FlatBvh bvh = build_bvh(scene);
    const std::vector<Ray> base = mixed_rays(scene, kRays, 8);
    std::vector<Ray> clipped;
    std::size_t closed_end_ok = 0;
    std::size_t hits = 0;
    for (const Ray& r : base) {
        const dev::GcHit h = trace_closest(bvh, r);
        if (h.prim == GC_INVALID) continue;
        ++hits;
        Ray before = r; // ends just short of the hit
        before.tmax = std::nextafter(h.t, 0.0f);
        Ray after = r; // starts just past it
        after.tmin = std::nextafter(h.t, std::numeric_limits<float>::infinity());
        Ray exact = r; // ends exactly at it: the interval is closed
        exact.tmax = h.t;
        EXPECT_NE(trace_closest(bvh, before).prim, h.prim);
        if (trace_closest(bvh, exact).prim == h.prim) ++closed_end_ok;
        clipped.insert(clipped.end(), {before, after, exact});
    }
    EXPECT_EQ(closed_end_ok, hits);
    expect_agreement(compare_with_brute_force(bvh, scene, clipped), "clipped intervals");

    // Single triangle at t = 2 with tmax = 1 / tmin = 3: plain misses.
    Scene one = empty_scene();
    add_triangle(one, {-1, -1, 2}, {1, -1, 2}, {0, 1, 2});
    const FlatBvh one_bvh = build_bvh(one);
    EXPECT_EQ(trace_closest(one_bvh, {Point3(0, 0, 0), Vec3(0, 0, 1), 0.0f, 1.0f}).prim, GC_INVALID);
    EXPECT_EQ(trace_closest(one_bvh, {Point3(0, 0, 0), Vec3(0, 0, 1), 3.0f}).prim, GC_INVALID);
    EXPECT_FALSE(trace_any(one_bvh, {Point3(0, 0, 0), Vec3(0, 0, 1), 0.0f, 1.0f}));
}

TEST(BvhTraverse, EmptySceneMissesEverything)
{
    const Scene scene = empty_scene();
    const FlatBvh bvh = build_bvh(scene);
    check_invariants(bvh, scene, 4);
    std::vector<Ray> rays = mixed_rays(scene, 1000, 9);
    rays.push_back({Point3(0, 0, 0), Vec3(0.0f, -0.0f, 1.0f)});
    rays.push_back({Point3(0, 0, 0), Vec3(-0.0f, 1.0f, 0.0f)});
    std::size_t hits = 0;
    for (const Ray& r : rays)
        if (trace_closest(bvh, r).prim != GC_INVALID || trace_any(bvh, r)) ++hits;
    EXPECT_EQ(hits, 0u);
    const BvhStats s = bvh_stats(bvh);
    EXPECT_EQ(s.nodes, 1u);
    EXPECT_EQ(s.leaves, 1u);
    EXPECT_EQ(s.sah_cost, 0.0f);
}

TEST(BvhTraverse, SingleTriangle)
{
    Scene scene = empty_scene();
    add_triangle(scene, {0, 0, 2}, {1, 0, 2}, {0, 1, 2});
    const FlatBvh bvh = build_bvh(scene);
    check_invariants(bvh, scene, 4);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    const dev::GcHit h = trace_closest(bvh, {Point3(0.25f, 0.5f, 0), Vec3(0, 0, 1)});
    ASSERT_EQ(h.prim, 0u);
    EXPECT_EQ(h.t, 2.0f);
    EXPECT_FLOAT_EQ(h.u, 0.25f);
    EXPECT_FLOAT_EQ(h.v, 0.5f);
    EXPECT_EQ(trace_closest(bvh, {Point3(0.75f, 0.5f, 0), Vec3(0, 0, 1)}).prim, GC_INVALID);
    expect_agreement(compare_with_brute_force(bvh, scene, mixed_rays(scene, kRays, 10)), "single triangle");
}

TEST(BvhTraverse, AllZeroAreaTriangles)
{
    // Points (three equal vertices) and needles (collinear vertices).
    Scene scene = empty_scene();
    Rng rng(11);
    const Bounds3 cube(Point3(-1, -1, -1), Point3(1, 1, 1));
    for (int i = 0; i < 1000; ++i) {
        const Point3 p = rng.point(cube);
        add_triangle(scene, p, p, p);
    }
    const FlatBvh points = build_bvh(scene);
    check_invariants(points, scene, 4);
    const TraceComparison c_points = compare_with_brute_force(points, scene, mixed_rays(scene, kRays, 12));
    expect_agreement(c_points, "point triangles");
    EXPECT_EQ(c_points.hits, 0u) << "zero-area triangles have det == 0";

    for (int i = 0; i < 1000; ++i) {
        const Point3 p = rng.point(cube);
        const Vec3 d = 0.1f * rng.direction();
        add_triangle(scene, p, p + d, p + 2.0f * d);
    }
    const FlatBvh needles = build_bvh(scene);
    check_invariants(needles, scene, 4);
    expect_agreement(compare_with_brute_force(needles, scene, mixed_rays(scene, kRays, 13)), "needle triangles");
}

TEST(BvhTraverse, AllCentroidsEqual)
{
    // Triangles whose bounding boxes all have the same centre: concentric, in the three axis
    // planes. Binning finds no split; the builder must fall back to count splits and still
    // respect the leaf size and depth limits.
    Scene scene = empty_scene();
    const Point3 c(0.1f, 0.2f, 0.3f);
    for (int i = 0; i < 3000; ++i) {
        const float r = 0.1f + 0.001f * static_cast<float>(i % 1000);
        const int plane = i % 3;
        auto at = [&](float a, float b) {
            return plane == 0 ? c + Vec3(a, b, 0) : (plane == 1 ? c + Vec3(0, a, b) : c + Vec3(b, 0, a));
        };
        add_triangle(scene, at(-r, -r), at(r, -r), at(0, r));
    }
    const FlatBvh bvh = build_bvh(scene);
    check_invariants(bvh, scene, 4);
    const BvhStats s = bvh_stats(bvh);
    std::printf("[ equal centroids ] %zu nodes, max depth %zu\n", s.nodes, s.max_depth);
    const TraceComparison cmp = compare_with_brute_force(bvh, scene, mixed_rays(scene, kRays, 14));
    expect_agreement(cmp, "equal centroids");
    EXPECT_GT(cmp.hits, 0u);
}

TEST(BvhTraverse, ExactTiesGoToTheSmallestSceneIndex)
{
    // 64 exact copies of one triangle scattered among a soup: every copy is hit at the same
    // t, bit for bit, and the closest hit must be the copy with the smallest scene index,
    // whatever leaf order the BVH chose: three BVHs of different shapes must agree.
    Scene scene = random_soup(3000, 16, 0.05f);
    const Point3 a(-0.5f, -0.5f, 0.0f), b(0.5f, -0.5f, 0.0f), c(0.0f, 0.5f, 0.0f);
    std::vector<std::uint32_t> copies;
    for (std::uint32_t i = 0; i < 64; ++i) {
        const std::uint32_t slot = 37 * i + 11;
        for (int k = 0; k < 3; ++k) scene.positions[3 * slot + k] = k == 0 ? a : (k == 1 ? b : c);
        copies.push_back(slot);
    }
    const FlatBvh bvh = build_bvh(scene);
    const FlatBvh bvh_leaf1 = build_bvh(scene, {.bins = 4, .max_leaf_size = 1});
    const FlatBvh bvh_leaf16 = build_bvh(scene, {.bins = 7, .max_leaf_size = 16, .traversal_cost = 0.1f});
    check_invariants(bvh, scene, 4);
    check_invariants(bvh_leaf1, scene, 1);
    check_invariants(bvh_leaf16, scene, 16);
    // In leaf order the copies need not come smallest-first; make sure the test means it.
    std::vector<std::uint32_t> leaf_order;
    for (const dev::GcTriangle& t : bvh.triangles)
        if (t.v0.x == a.x && t.v0.y == a.y && t.v0.z == a.z && t.v1.x == b.x) leaf_order.push_back(dev::gc_triangle_prim(t));
    ASSERT_EQ(leaf_order.size(), copies.size());
    std::printf("[ ties ] first copy in leaf order: %u (smallest index %u)\n", leaf_order.front(), copies.front());

    Rng rng(17);
    std::size_t wrong = 0;
    std::size_t copy_hits = 0;
    for (int i = 0; i < 1000; ++i) {
        const Point3 target = barycentric(a, b, c, 0.3f * rng.uniform(), 0.3f * rng.uniform());
        const Point3 origin = target + Vec3(0.1f * rng.uniform(), 0.1f * rng.uniform(), i % 2 ? 3.0f : -3.0f);
        const Ray ray{origin, target - origin};
        const dev::GcHit h = trace_closest(bvh, ray);
        const dev::GcHit ref = trace_brute_force(scene, ray);
        const bool is_copy = std::find(copies.begin(), copies.end(), h.prim) != copies.end();
        if (is_copy) ++copy_hits;
        if (h.prim != ref.prim || (is_copy && h.prim != copies.front())) ++wrong;
        if (trace_closest(bvh_leaf1, ray).prim != h.prim || trace_closest(bvh_leaf16, ray).prim != h.prim) ++wrong;
    }
    std::printf("[ ties ] %zu of 1000 rays hit the stacked copies\n", copy_hits);
    EXPECT_GT(copy_hits, 500u);
    EXPECT_EQ(wrong, 0u);
}

TEST(BvhTraverse, ExponentialSpacingKeepsDepthWithinStack)
{
    // Triangles at x = 1.2^i: SAH peels one triangle per level here; the depth guard must
    // keep the tree within the kernels' 64-entry stack.
    Scene scene = empty_scene();
    for (int i = 0; i < 400; ++i) {
        const float x = std::pow(1.2f, static_cast<float>(i));
        const float w = 0.01f * x;
        add_triangle(scene, {x, 0, 0}, {x + w, 1, 0}, {x, 0, 1});
    }
    const FlatBvh bvh = build_bvh(scene, {.max_leaf_size = 1});
    check_invariants(bvh, scene, 1);
    const BvhStats s = bvh_stats(bvh);
    std::printf("[ exponential ] max depth %zu\n", s.max_depth);
    Rng rng(15);
    std::vector<Ray> rays;
    for (std::size_t i = 0; i < kRays; ++i) {
        const int t = static_cast<int>(rng.below(400));
        const float x = std::pow(1.2f, static_cast<float>(t));
        rays.push_back({Point3(-1.0f, 0.3f * rng.uniform(), 0.3f * rng.uniform()),
                        Vec3(x + 1.0f, 0.2f * rng.uniform(), 0.2f * rng.uniform())});
    }
    expect_agreement(compare_with_brute_force(bvh, scene, rays), "exponential");
}

}  // namespace
}  // namespace gc::test
