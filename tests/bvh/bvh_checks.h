// Structural invariants of a FlatBvh and the traversal-vs-brute-force comparison, shared by
// the BVH tests.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gc_accessors.h"
#include "host/bvh/bvh.h"
#include "host/bvh/traverse_host.h"
#include "host/scene/scene.h"

namespace gc::test {

inline bool box_contains(const dev::GcBvhNode& outer, const dev::GcBvhNode& inner)
{
    return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
           outer.hi.x >= inner.hi.x && outer.hi.y >= inner.hi.y && outer.hi.z >= inner.hi.z;
}

inline bool box_contains(const dev::GcBvhNode& box, const dev::float4& p)
{
    return box.lo.x <= p.x && box.lo.y <= p.y && box.lo.z <= p.z && box.hi.x >= p.x && box.hi.y >= p.y &&
           box.hi.z >= p.z;
}

// Checks every invariant of the flat layout against the scene; reports failures through
// gtest (ADD_FAILURE, bounded in number) so a test can also look at the counters it prints.
inline void check_invariants(const FlatBvh& bvh, const Scene& scene, int max_leaf_size)
{
    const std::size_t n = scene.triangle_count();
    ASSERT_FALSE(bvh.nodes.empty());
    ASSERT_FALSE(bvh.triangles.empty());
    if (n == 0) {
        ASSERT_EQ(bvh.nodes.size(), 1u);
        ASSERT_EQ(bvh.triangles.size(), 1u);
        EXPECT_TRUE(dev::gc_node_is_leaf(bvh.nodes[0]));
        EXPECT_EQ(dev::gc_triangle_prim(bvh.triangles[0]), GC_INVALID);
        EXPECT_EQ(bvh.scene_triangle_count(), 0u);
        return;
    }
    ASSERT_EQ(bvh.triangles.size(), n);
    EXPECT_EQ(bvh.scene_triangle_count(), n);

    std::vector<int> node_refs(bvh.nodes.size(), 0);
    std::vector<int> tri_refs(bvh.triangles.size(), 0);
    std::vector<int> prim_seen(n, 0);
    std::size_t leaves = 0;
    int failures = 0;
    auto fail = [&](const std::string& what) {
        if (++failures <= 10) ADD_FAILURE() << what;
    };
    for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
        const dev::GcBvhNode& node = bvh.nodes[i];
        const std::uint32_t first = dev::gc_node_first(node);
        const std::uint32_t count = dev::gc_node_count(node);
        if (!(node.lo.x <= node.hi.x && node.lo.y <= node.hi.y && node.lo.z <= node.hi.z))
            fail("node " + std::to_string(i) + " has empty bounds");
        if (count == 0) {
            // Pre-order with adjacent pairs: children come after their parent.
            if (first <= i || first + 1 >= bvh.nodes.size()) {
                fail("inner node " + std::to_string(i) + " has children out of range: " + std::to_string(first));
                continue;
            }
            ++node_refs[first];
            ++node_refs[first + 1];
            if (!box_contains(node, bvh.nodes[first]) || !box_contains(node, bvh.nodes[first + 1]))
                fail("inner node " + std::to_string(i) + " does not contain its children's bounds");
        } else {
            ++leaves;
            if (count > static_cast<std::uint32_t>(max_leaf_size))
                fail("leaf " + std::to_string(i) + " holds " + std::to_string(count) + " triangles");
            if (std::size_t(first) + count > bvh.triangles.size()) {
                fail("leaf " + std::to_string(i) + " triangles out of range");
                continue;
            }
            for (std::uint32_t t = first; t < first + count; ++t) {
                ++tri_refs[t];
                const dev::GcTriangle& tri = bvh.triangles[t];
                if (!box_contains(node, tri.v0) || !box_contains(node, tri.v1) || !box_contains(node, tri.v2))
                    fail("leaf " + std::to_string(i) + " does not contain triangle slot " + std::to_string(t));
                const std::uint32_t prim = dev::gc_triangle_prim(tri);
                if (prim >= n) {
                    fail("triangle slot " + std::to_string(t) + " has scene index " + std::to_string(prim));
                    continue;
                }
                ++prim_seen[prim];
                for (int c = 0; c < 3; ++c) {
                    const dev::float4 v = c == 0 ? tri.v0 : (c == 1 ? tri.v1 : tri.v2);
                    const Point3 p = scene.vertex(prim, c);
                    if (v.x != p.x || v.y != p.y || v.z != p.z)
                        fail("triangle slot " + std::to_string(t) + " vertex " + std::to_string(c) +
                             " differs from scene triangle " + std::to_string(prim));
                }
                if (tri.v1.w != 0.0f || tri.v2.w != 0.0f) fail("triangle slot w lanes not zero");
            }
        }
    }
    EXPECT_EQ(bvh.nodes.size(), 2 * leaves - 1) << "a BVH2 has 2 * leaves - 1 nodes";
    EXPECT_EQ(node_refs[0], 0) << "the root is nobody's child";
    for (std::size_t i = 1; i < node_refs.size(); ++i)
        if (node_refs[i] != 1) fail("node " + std::to_string(i) + " referenced " + std::to_string(node_refs[i]) + "x");
    for (std::size_t t = 0; t < tri_refs.size(); ++t)
        if (tri_refs[t] != 1) fail("triangle slot " + std::to_string(t) + " in " + std::to_string(tri_refs[t]) + " leaves");
    for (std::size_t p = 0; p < n; ++p)
        if (prim_seen[p] != 1) fail("scene triangle " + std::to_string(p) + " appears " + std::to_string(prim_seen[p]) + "x");
    EXPECT_EQ(failures, 0);
    const BvhStats stats = bvh_stats(bvh);
    EXPECT_EQ(stats.nodes, bvh.nodes.size());
    EXPECT_EQ(stats.leaves, leaves);
    EXPECT_LE(stats.max_depth, 63u) << "deeper than the kernels' 64-entry stack allows";
}

struct TraceComparison {
    std::size_t rays = 0;
    std::size_t hits = 0;
    std::size_t prim_mismatches = 0;
    std::size_t t_mismatches = 0;   // relative difference above 1e-5
    std::size_t any_mismatches = 0; // any-hit disagrees with closest-hit
    std::size_t wide_mismatches = 0; // the BVH4 or BVH8 layout's closest or any hit differs from the BVH2's
    double max_rel_t_diff = 0.0;
};

inline bool same_bits(const dev::GcHit& a, const dev::GcHit& b)
{
    return a.prim == b.prim && std::bit_cast<std::uint32_t>(a.t) == std::bit_cast<std::uint32_t>(b.t) &&
           std::bit_cast<std::uint32_t>(a.u) == std::bit_cast<std::uint32_t>(b.u) &&
           std::bit_cast<std::uint32_t>(a.v) == std::bit_cast<std::uint32_t>(b.v);
}

// BVH closest/any hit against brute force for each ray. Same prim id, t within 1e-5
// relative (in fact they run the same triangle test, so t is expected to be identical), any
// hit == (closest hit found). The BVH4 layout CPUs read (widen(bvh), gc_traverse4.h) must
// give the BVH2's hits bit for bit.
inline TraceComparison compare_with_brute_force(const FlatBvh& bvh, const Scene& scene, const std::vector<Ray>& rays)
{
    TraceComparison c;
    const WideBvh wide = widen(bvh);
    const Wide8Bvh wide8 = widen8(bvh);
    for (const Ray& ray : rays) {
        ++c.rays;
        const dev::GcHit bvh_hit = trace_closest(bvh, ray);
        const dev::GcHit ref = trace_brute_force(scene, ray);
        const bool any = trace_any(bvh, ray);
        if (!same_bits(trace_closest(wide, ray), bvh_hit) || trace_any(wide, ray) != any) ++c.wide_mismatches;
        if (!same_bits(trace_closest(wide8, ray), bvh_hit) || trace_any(wide8, ray) != any) ++c.wide_mismatches;
        if (ref.prim != GC_INVALID) ++c.hits;
        if (bvh_hit.prim != ref.prim) {
            if (++c.prim_mismatches <= 5)
                std::printf("  mismatch: ray o=(%.9g %.9g %.9g) d=(%.9g %.9g %.9g) bvh prim %u t %.9g, brute prim %u t %.9g\n",
                            double(ray.origin.x), double(ray.origin.y), double(ray.origin.z), double(ray.direction.x),
                            double(ray.direction.y), double(ray.direction.z), bvh_hit.prim, double(bvh_hit.t), ref.prim,
                            double(ref.t));
        } else if (ref.prim != GC_INVALID) {
            const double rel = std::fabs(double(bvh_hit.t) - double(ref.t)) / std::fmax(1e-30, std::fabs(double(ref.t)));
            c.max_rel_t_diff = std::max(c.max_rel_t_diff, rel);
            if (rel > 1e-5 || bvh_hit.u != ref.u || bvh_hit.v != ref.v) ++c.t_mismatches;
        }
        if (any != (ref.prim != GC_INVALID)) ++c.any_mismatches;
    }
    return c;
}

inline void expect_agreement(const TraceComparison& c, const char* scene_name)
{
    std::printf("[ %s ] %zu rays, %zu hits, prim mismatches %zu, t/uv mismatches %zu (max rel t diff %.3g), "
                "any-hit mismatches %zu, BVH4/8 vs BVH2 mismatches %zu\n",
                scene_name, c.rays, c.hits, c.prim_mismatches, c.t_mismatches, c.max_rel_t_diff, c.any_mismatches,
                c.wide_mismatches);
    EXPECT_EQ(c.wide_mismatches, 0u) << scene_name;
    EXPECT_EQ(c.prim_mismatches, 0u) << scene_name;
    EXPECT_EQ(c.t_mismatches, 0u) << scene_name;
    EXPECT_EQ(c.any_mismatches, 0u) << scene_name;
}

}  // namespace gc::test
