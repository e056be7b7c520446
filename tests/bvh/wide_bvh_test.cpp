// The BVH4 layout (host/bvh/widen.h): structure against the scene, and the same hits as the
// BVH2 it is collapsed from for leaf sizes 1 to 16 (the traversal tests in traverse_test.cpp
// compare it with the BVH2 on every ray through compare_with_brute_force).
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bvh_checks.h"
#include "host/bvh/widen.h"
#include "test_scenes.h"

namespace gc::test {
namespace {

struct WideShape {
    std::size_t leaves = 0;
    std::size_t used_lanes = 0;
    std::size_t depth = 0; // edges from the root to the deepest inner node
    std::uint32_t max_blocks = 0; // most blocks in one leaf
    std::size_t min_inner_triangles = 0; // fewest triangles below a non-root inner node (0: none)
};

// One child slot of a BVH4 or BVH8 node, so one checker serves both layouts.
struct Slot {
    float lo[3];
    float hi[3];
    std::uint32_t ref;

    bool contains(float x, float y, float z) const
    {
        return lo[0] <= x && x <= hi[0] && lo[1] <= y && y <= hi[1] && lo[2] <= z && z <= hi[2];
    }
};
using SlotNodes = std::vector<std::vector<Slot>>;

SlotNodes slots_of(const WideBvh& wide)
{
    SlotNodes out;
    for (const dev::GcBvh4Node& n : wide.nodes) {
        out.emplace_back();
        for (int k = 0; k < 4; ++k)
            out.back().push_back({{n.lo_x[k], n.lo_y[k], n.lo_z[k]}, {n.hi_x[k], n.hi_y[k], n.hi_z[k]}, n.child[k]});
    }
    return out;
}

SlotNodes slots_of(const Wide8Bvh& wide)
{
    SlotNodes out;
    for (const dev::GcBvh8Node& n : wide.nodes) {
        out.emplace_back();
        for (int k = 0; k < 8; ++k) {
            const bool up = k >= 4;
            const int j = k & 3;
            out.back().push_back({{(up ? n.lo_x1 : n.lo_x0)[j], (up ? n.lo_y1 : n.lo_y0)[j], (up ? n.lo_z1 : n.lo_z0)[j]},
                                  {(up ? n.hi_x1 : n.hi_x0)[j], (up ? n.hi_y1 : n.hi_y0)[j], (up ? n.hi_z1 : n.hi_z0)[j]},
                                  (up ? n.child1 : n.child0)[j]});
        }
    }
    return out;
}

// Walks the tree from the root and checks every rule widen() promises; reports through gtest.
template <class Wide>
WideShape check_wide(const Wide& wide, const Scene& scene)
{
    const SlotNodes nodes = slots_of(wide);
    WideShape shape;
    std::vector<int> prim_seen(scene.triangle_count(), 0);
    std::vector<int> node_seen(nodes.size(), 0);
    int failures = 0;
    auto fail = [&](const std::string& what) {
        if (++failures <= 10) ADD_FAILURE() << what;
    };
    // Returns the triangles below node `index`.
    std::function<std::size_t(std::uint32_t, std::size_t)> visit = [&](std::uint32_t index, std::size_t depth) {
        const std::size_t lanes_before = shape.used_lanes;
        ++node_seen[index];
        shape.depth = std::max(shape.depth, depth);
        const std::vector<Slot>& n = nodes[index];
        bool empty_seen = false;
        for (std::size_t k = 0; k < n.size(); ++k) {
            const Slot& slot = n[k];
            const std::uint32_t ref = slot.ref;
            if (ref == GC_INVALID) {
                empty_seen = true;
                if (!(slot.lo[0] > slot.hi[0])) fail("empty slot with non-empty bounds in node " + std::to_string(index));
                continue;
            }
            if (empty_seen) fail("node " + std::to_string(index) + " has a gap before slot " + std::to_string(k));
            if ((ref & GC_BVH4_LEAF) == 0u) {
                if (ref <= index || ref >= nodes.size()) {
                    fail("node " + std::to_string(index) + " child " + std::to_string(ref) + " out of order");
                    continue;
                }
                for (const Slot& c : nodes[ref]) {
                    if (c.ref == GC_INVALID) continue;
                    if (!slot.contains(c.lo[0], c.lo[1], c.lo[2]) || !slot.contains(c.hi[0], c.hi[1], c.hi[2]))
                        fail("node " + std::to_string(ref) + " is not inside its parent's slot");
                }
                const std::size_t below = visit(ref, depth + 1);
                if (shape.min_inner_triangles == 0 || below < shape.min_inner_triangles) shape.min_inner_triangles = below;
                continue;
            }
            ++shape.leaves;
            const std::uint32_t first = ref & GC_BVH4_LEAF_FIRST_MASK;
            const std::uint32_t count = ((ref >> GC_BVH4_LEAF_COUNT_SHIFT) & 15u) + 1u;
            shape.max_blocks = std::max(shape.max_blocks, count);
            if (first + count > wide.blocks.size()) {
                fail("leaf blocks out of range");
                continue;
            }
            for (std::uint32_t b = first; b < first + count; ++b) {
                const dev::GcTriangle4& q = wide.blocks[b];
                for (int lane = 0; lane < 4; ++lane) {
                    const std::uint32_t prim = q.prim[lane];
                    if (prim == GC_INVALID) {
                        if (q.v0x[lane] != 0.0f || q.v1y[lane] != 0.0f || q.v2z[lane] != 0.0f)
                            fail("unused lane with vertices");
                        continue;
                    }
                    if (prim >= prim_seen.size()) {
                        fail("lane with scene index " + std::to_string(prim));
                        continue;
                    }
                    ++prim_seen[prim];
                    ++shape.used_lanes;
                    const float xs[3] = {q.v0x[lane], q.v1x[lane], q.v2x[lane]};
                    const float ys[3] = {q.v0y[lane], q.v1y[lane], q.v2y[lane]};
                    const float zs[3] = {q.v0z[lane], q.v1z[lane], q.v2z[lane]};
                    for (int c = 0; c < 3; ++c) {
                        const Point3 p = scene.vertex(prim, c);
                        if (xs[c] != p.x || ys[c] != p.y || zs[c] != p.z) fail("lane vertex differs from the scene");
                        if (!slot.contains(xs[c], ys[c], zs[c])) fail("triangle outside its leaf's slot");
                    }
                }
            }
        }
        return shape.used_lanes - lanes_before;
    };
    visit(0, 0);
    for (std::size_t p = 0; p < prim_seen.size(); ++p)
        if (prim_seen[p] != 1) fail("scene triangle " + std::to_string(p) + " appears " + std::to_string(prim_seen[p]) + "x");
    for (std::size_t i = 0; i < node_seen.size(); ++i)
        if (node_seen[i] != 1) fail("node " + std::to_string(i) + " reached " + std::to_string(node_seen[i]) + "x");
    EXPECT_EQ(failures, 0);
    return shape;
}

TEST(WideBvh, CoversEveryTriangleOnceForEveryLeafSize)
{
    const Scene scene = random_soup(10000, 21);
    for (int leaf : {1, 2, 4, 8, 16}) {
        // Expensive node visits make the builder use the long leaves, so multi-block leaves occur.
        const FlatBvh bvh = build_bvh(scene, {.max_leaf_size = leaf, .traversal_cost = leaf > 4 ? 8.0f : 1.0f});
        const BvhStats s = bvh_stats(bvh);
        auto check = [&](const auto& wide, const char* name, std::size_t max_nodes) {
            const WideShape shape = check_wide(wide, scene);
            std::printf("[ wide, leaf %2d ] BVH2 %zu nodes depth %zu -> %s %zu nodes depth %zu, %zu leaves, "
                        "%zu blocks (%.0f%% of lanes used, up to %u per leaf), %.1f bytes per triangle\n",
                        leaf, s.nodes, s.max_depth, name, wide.nodes.size(), shape.depth, shape.leaves,
                        wide.blocks.size(), 100.0 * double(shape.used_lanes) / double(4 * wide.blocks.size()),
                        shape.max_blocks, double(wide_bvh_bytes(wide)) / double(scene.triangle_count()));
            EXPECT_EQ(shape.used_lanes, scene.triangle_count()) << name;
            EXPECT_LE(shape.depth, s.max_depth) << name << " must not be deeper than its BVH2 (stack bound)";
            EXPECT_LT(wide.nodes.size(), max_nodes) << "collapsing should remove most inner nodes";
            if (leaf == 16) {
                EXPECT_GT(shape.max_blocks, 2u) << "the long leaves must be exercised";
            }
        };
        check(widen(bvh), "BVH4", s.nodes / 2);
        check(widen8(bvh), "BVH8", s.nodes / 4);
        expect_agreement(compare_with_brute_force(bvh, scene, mixed_rays(scene, 3000, 22)), "wide vs brute force");
    }
}

// The BVH8 of a large scene makes every subtree of up to eight triangles one leaf (sixteen
// from 2^20 triangles on), so no inner node below the root holds that few; smaller scenes
// and the BVH4 keep one block's worth. The hits stay the BVH2's, bit for bit.
TEST(WideBvh, LargerScenesGetLongerLeavesInTheirBvh8)
{
    EXPECT_EQ(wide_leaf_triangles(8, 65535), 4u);
    EXPECT_EQ(wide_leaf_triangles(8, 65536), 8u);
    EXPECT_EQ(wide_leaf_triangles(8, (1u << 20) - 1), 8u);
    EXPECT_EQ(wide_leaf_triangles(8, 1u << 20), 16u);
    EXPECT_EQ(wide_leaf_triangles(4, 1u << 22), 4u);
    struct Case {
        std::size_t triangles;
        std::uint32_t leaf;  // the rule's leaf size for that scene
        std::size_t rays;
    };
    for (const Case c : {Case{20000, 4, 0}, Case{70000, 8, 1500}, Case{(std::size_t{1} << 20) + 20000, 16, 3000}}) {
        const Scene scene = random_soup(c.triangles, 41, c.triangles > 100000 ? 0.005f : 0.02f);
        const FlatBvh bvh = build_bvh(scene);
        const Wide8Bvh wide8 = widen8(bvh);
        const WideShape shape = check_wide(wide8, scene);
        std::printf("[ wide, leaves ] %zu triangles: BVH8 %zu nodes, up to %u blocks per leaf, fewest triangles "
                    "under an inner node %zu (leaves up to %u)\n",
                    c.triangles, wide8.nodes.size(), shape.max_blocks, shape.min_inner_triangles, c.leaf);
        EXPECT_GT(shape.min_inner_triangles, c.leaf) << c.triangles << " triangles";
        if (c.leaf == 4) {
            EXPECT_LE(shape.min_inner_triangles, 8u) << "a small scene's BVH8 keeps one-block leaves";
        }
        if (c.leaf > 4) {
            // The builder's leaves hold up to 4 triangles, so a leaf's blocks are up to c.leaf / 4.
            EXPECT_EQ(shape.max_blocks, c.leaf / 4) << c.triangles << " triangles";
            const WideShape shape4 = check_wide(widen(bvh), scene);
            EXPECT_LE(shape4.min_inner_triangles, 8u) << "the BVH4 keeps one-block leaves";
        }
        if (c.rays == 0) continue;
        std::size_t differ = 0;
        for (const Ray& r : mixed_rays(scene, c.rays, 44))
            if (!same_bits(trace_closest(wide8, r), trace_closest(bvh, r)) || trace_any(wide8, r) != trace_any(bvh, r))
                ++differ;
        std::printf("[ wide, leaves ] %zu rays: BVH8 and BVH2 hits differ on %zu\n", c.rays, differ);
        EXPECT_EQ(differ, 0u);
    }
}

template <class Bvh>
bool same_wide_bytes(const Bvh& a, const Bvh& b)
{
    using Node = typename decltype(a.nodes)::value_type;
    return a.nodes.size() == b.nodes.size() && a.blocks.size() == b.blocks.size() &&
           std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(Node)) == 0 &&
           std::memcmp(a.blocks.data(), b.blocks.data(), a.blocks.size() * sizeof(dev::GcTriangle4)) == 0;
}

// Large enough that the collapse runs in subtrees on several threads (at least 4 x 16384
// triangles), which are then spliced into the serial walk's order: the same bytes as one
// thread, for both widths and whatever the thread count.
TEST(WideBvh, ThreadCountDoesNotChangeTheWideBvh)
{
    const Scene scene = random_soup(150000, 31, 0.02f);
    const FlatBvh bvh = build_bvh(scene);
    const WideBvh serial4 = widen(bvh, 1);
    const Wide8Bvh serial8 = widen8(bvh, 1);
    for (const int threads : {2, 3, 8}) {
        EXPECT_TRUE(same_wide_bytes(serial4, widen(bvh, threads))) << "BVH4, " << threads << " threads";
        EXPECT_TRUE(same_wide_bytes(serial8, widen8(bvh, threads))) << "BVH8, " << threads << " threads";
    }
    std::printf("[ wide, threads ] BVH4 %zu nodes / %zu blocks and BVH8 %zu nodes / %zu blocks compared byte for "
                "byte with 1, 2, 3 and 8 threads\n",
                serial4.nodes.size(), serial4.blocks.size(), serial8.nodes.size(), serial8.blocks.size());
    check_wide(serial8, scene);
}

TEST(WideBvh, EmptyAndTinyScenes)
{
    const Scene none = empty_scene();
    const WideBvh empty = widen(build_bvh(none));
    ASSERT_EQ(empty.nodes.size(), 1u);
    ASSERT_EQ(empty.blocks.size(), 1u);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(empty.nodes[0].child[k], GC_INVALID);
    for (const Ray& r : mixed_rays(none, 200, 23)) {
        EXPECT_EQ(trace_closest(empty, r).prim, GC_INVALID);
        EXPECT_FALSE(trace_any(empty, r));
    }
    // One triangle: the root is a BVH2 leaf, so the BVH4 root holds one leaf slot.
    Scene one = empty_scene();
    add_triangle(one, {0, 0, 2}, {1, 0, 2}, {0, 1, 2});
    const WideBvh wide = widen(build_bvh(one));
    check_wide(wide, one);
    check_wide(widen8(build_bvh(one)), one);
    const dev::GcHit h = trace_closest(wide, {Point3(0.25f, 0.5f, 0), Vec3(0, 0, 1)});
    EXPECT_EQ(h.prim, 0u);
    EXPECT_EQ(h.t, 2.0f);
}

}  // namespace
}  // namespace gc::test
