// Builder properties: determinism across thread counts, option and input validation, and
// the figures for a large scene (printed, not asserted) and a 100k-triangle torus knot.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

#include "bvh_checks.h"
#include "host/util/error.h"
#include "host/util/host_threads.h"
#include "test_scenes.h"

namespace gc::test {
namespace {

bool same_bytes(const FlatBvh& a, const FlatBvh& b)
{
    return a.nodes.size() == b.nodes.size() && a.triangles.size() == b.triangles.size() &&
           std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(dev::GcBvhNode)) == 0 &&
           std::memcmp(a.triangles.data(), b.triangles.data(), a.triangles.size() * sizeof(dev::GcTriangle)) == 0;
}

TEST(BvhBuilder, ThreadCountDoesNotChangeTheBvh)
{
    // Large enough that the builder really runs tasks in parallel (subtrees >= 512 triangles,
    // nodes >= 32768 triangles, or on 16 threads >= 16384, binned and partitioned in chunks).
    Scene scene = random_soup(150000, 21, 0.02f);
    // Plus a dense clump, so SAH splits are uneven.
    const Scene clump = random_soup(30000, 22, 0.002f);
    for (std::size_t t = 0; t < clump.triangle_count(); ++t)
        add_triangle(scene, Point3(0.01f * clump.vertex(t, 0).glm()), Point3(0.01f * clump.vertex(t, 1).glm()),
                     Point3(0.01f * clump.vertex(t, 2).glm()));
    const FlatBvh one = build_bvh(scene, {.threads = 1});
    const FlatBvh four = build_bvh(scene, {.threads = 4});
    const FlatBvh sixteen = build_bvh(scene, {.threads = 16}); // nodes from 16384 in chunks
    const FlatBvh all = build_bvh(scene, {.threads = 0});
    std::printf("[ determinism ] %zu triangles, %zu nodes; 1 thread %.3f s, 4 threads %.3f s\n",
                scene.triangle_count(), one.nodes.size(), one.build_seconds, four.build_seconds);
    EXPECT_TRUE(same_bytes(one, four)) << "1 vs 4 threads";
    EXPECT_TRUE(same_bytes(one, sixteen)) << "1 vs 16 threads";
    EXPECT_TRUE(same_bytes(one, all)) << "1 thread vs hardware_concurrency";
    check_invariants(four, scene, 4);
}

// On four or more threads, nodes binned in chunks are partitioned stably in those chunks, each
// from the array it lies in into the other one; on one thread every node is partitioned in
// place, which leaves the triangles in another order: the same tree either way. 2^21 +
// 200000 triangles, so that several levels go out of the reference array, back out of the
// scratch array, and their children are built in the reference array again.
TEST(BvhBuilder, ThreadCountDoesNotChangeALargeBvh)
{
    const Scene scene = random_soup((std::size_t{1} << 21) + 200000, 29, 0.005f);
    const FlatBvh one = build_bvh(scene, {.threads = 1});
    const FlatBvh four = build_bvh(scene, {.threads = 4});
    std::printf("[ determinism ] %zu triangles, %zu nodes; 1 thread %.3f s, 4 threads %.3f s\n",
                scene.triangle_count(), one.nodes.size(), one.build_seconds, four.build_seconds);
    ASSERT_TRUE(same_bytes(one, four));
    check_invariants(four, scene, 4);
}

// A large node whose chunks split very differently: a spread of triangles, then a clump of
// coincident ones (which no split separates: they end in median splits) appended after it,
// so that with four threads the stable partition's first chunks send everything one way,
// the last everything the other way and one in between a mix. Their median splits must not
// halve them by the order the partitions left them in. Same tree on one thread and on four,
// every triangle in exactly one leaf.
TEST(BvhBuilder, LopsidedLargeNodesPartitionAlike)
{
    Scene scene = random_soup(600000, 33, 0.005f);
    const std::size_t spread = scene.triangle_count();
    for (std::size_t t = 0; t < 450000; ++t)
        add_triangle(scene, Point3(2.0f, 2.0f, 2.0f), Point3(2.001f, 2.0f, 2.0f), Point3(2.0f, 2.001f, 2.0f));
    ASSERT_GE(scene.triangle_count(), std::size_t{1} << 20);
    const FlatBvh one = build_bvh(scene, {.threads = 1});
    const FlatBvh four = build_bvh(scene, {.threads = 4});
    const BvhStats stats = bvh_stats(one);
    std::printf("[ lopsided ] %zu triangles (%zu coincident), %zu nodes, depth %zu\n", scene.triangle_count(),
                scene.triangle_count() - spread, one.nodes.size(), stats.max_depth);
    ASSERT_TRUE(same_bytes(one, four));
    check_invariants(four, scene, 4);
}

// flatten() lays out a large tree's nodes on a pool (subtrees below a cut depth sized, then
// walked, on all threads): it must write the bytes of the one-thread walk, triangles too.
TEST(BvhFlatten, ThreadCountDoesNotChangeTheLayout)
{
    const Scene scene = random_soup(120000, 28, 0.02f);
    const BvhTree tree = build_bvh_tree(scene);
    set_host_thread_count(1);
    const FlatBvh serial = flatten(tree, scene);
    set_host_thread_count(4);
    const FlatBvh pooled = flatten(tree, scene);
    set_host_thread_count(0);
    std::printf("[ flatten ] %zu triangles, %zu nodes (the pool takes trees of 65536 or more)\n",
                scene.triangle_count(), serial.nodes.size());
    ASSERT_GE(serial.nodes.size(), std::size_t{65536});
    ASSERT_TRUE(same_bytes(serial, pooled)); // a broken layout is no tree to walk below
    check_invariants(pooled, scene, 4);
}

TEST(BvhBuilder, RejectsBadOptions)
{
    const Scene scene = random_soup(10, 23);
    EXPECT_THROW(build_bvh(scene, {.bins = 1}), UsageError);
    EXPECT_THROW(build_bvh(scene, {.bins = 1000}), UsageError);
    EXPECT_THROW(build_bvh(scene, {.max_leaf_size = 0}), UsageError);
    EXPECT_THROW(build_bvh(scene, {.max_leaf_size = kBvhMaxLeafCap + 1}), UsageError);
    EXPECT_THROW(build_bvh(scene, {.intersection_cost = 0.0f}), UsageError);
    EXPECT_THROW(build_bvh(scene, {.traversal_cost = std::numeric_limits<float>::quiet_NaN()}), UsageError);
    EXPECT_THROW(build_bvh(scene, {.threads = -1}), UsageError);
    EXPECT_NO_THROW(build_bvh(scene, {.bins = 2, .max_leaf_size = kBvhMaxLeafCap}));
}

TEST(BvhBuilder, RejectsNonFiniteVerticesNamingTheTriangle)
{
    Scene scene = random_soup(10, 24);
    scene.source_path = "soup.obj";
    scene.positions[3 * 7 + 1] = Point3(0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f);
    try {
        build_bvh(scene);
        FAIL() << "expected InputError";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        std::printf("[ message ] %s\n", msg.c_str());
        EXPECT_NE(msg.find("soup.obj"), std::string::npos);
        EXPECT_NE(msg.find("triangle 7"), std::string::npos);
    }
    Scene bad = random_soup(10, 25);
    bad.positions.pop_back();
    EXPECT_THROW(build_bvh(bad), InputError);
}

// A Scene made in code, not by a loader, may lack what flatten and the device upload index
// per triangle; it gets an InputError naming it, not an out-of-bounds read.
TEST(BvhBuilder, RejectsScenesWithoutTheirPerTriangleArrays)
{
    auto expect_error = [](const Scene& scene, const char* wanted) {
        try {
            build_bvh(scene);
            ADD_FAILURE() << "expected InputError mentioning '" << wanted << "'";
        } catch (const InputError& e) {
            const std::string msg = e.what();
            std::printf("[ message ] %s\n", msg.c_str());
            EXPECT_NE(msg.find(wanted), std::string::npos);
        }
    };
    Scene no_materials = random_soup(10, 27);
    no_materials.materials.clear();
    expect_error(no_materials, "no materials");
    Scene no_normals = random_soup(10, 28);
    no_normals.normals.clear();
    expect_error(no_normals, "vertex normals");
    Scene short_uvs = random_soup(10, 29);
    short_uvs.uvs.assign(3, glm::vec2(0.0f));
    expect_error(short_uvs, "texture coordinates");
    // A material index past the end, on one thread and in flatten's parallel chunks.
    for (std::size_t n : {std::size_t{10}, std::size_t{40000}}) {
        Scene bad_id = random_soup(n, 30);
        bad_id.source_path = "made.obj";
        bad_id.material_ids[n - 3] = 1;
        expect_error(bad_id, ("made.obj: triangle " + std::to_string(n - 3) + " has material 1").c_str());
    }
}

TEST(BvhBuilder, LeafSizeOptionIsHonoured)
{
    const Scene scene = random_soup(20000, 26);
    for (int leaf : {1, 2, 8, 16}) {
        const FlatBvh bvh = build_bvh(scene, {.max_leaf_size = leaf});
        check_invariants(bvh, scene, leaf);
        const BvhStats s = bvh_stats(bvh);
        std::printf("[ leaf <= %2d ] %zu nodes, %zu leaves (%.2f tris/leaf), depth %zu, SAH %.2f\n", leaf, s.nodes,
                    s.leaves, double(scene.triangle_count()) / double(s.leaves), s.max_depth, double(s.sah_cost));
        EXPECT_GT(s.sah_cost, 0.0f);
    }
}

TEST(BvhBuilder, MillionTriangleFigures)
{
    const Scene scene = random_soup(1000000, 27, 0.01f);
    const FlatBvh bvh = build_bvh(scene);
    const BvhStats s = bvh_stats(bvh);
    std::printf("[ 1M random ] %zu triangles: build %.3f s (%.2f Mtris/s), %zu nodes, %zu leaves, depth %zu, "
                "SAH cost %.3f\n",
                scene.triangle_count(), s.build_seconds, 1e-6 * double(scene.triangle_count()) / s.build_seconds,
                s.nodes, s.leaves, s.max_depth, double(s.sah_cost));
    EXPECT_EQ(bvh.triangles.size(), scene.triangle_count());
    EXPECT_EQ(s.nodes, 2 * s.leaves - 1);
    EXPECT_LE(s.max_depth, 63u);
    EXPECT_GT(s.sah_cost, 1.0f);
}

// A scan-sized closed surface (100k triangles) that winds past itself: see torus_knot.
TEST(BvhBuilder, TorusKnot100k)
{
    const Scene scene = torus_knot(1000, 50, 0.5f);
    ASSERT_EQ(scene.triangle_count(), 100000u);
    const FlatBvh bvh = build_bvh(scene);
    const BvhStats s = bvh_stats(bvh);
    std::printf("[ torus knot ] %zu triangles: build %.3f s (%.2f Mtris/s), %zu nodes, %zu leaves, depth %zu, "
                "SAH cost %.3f\n",
                scene.triangle_count(), s.build_seconds, 1e-6 * double(scene.triangle_count()) / s.build_seconds,
                s.nodes, s.leaves, s.max_depth, double(s.sah_cost));
    check_invariants(bvh, scene, 4);
    expect_agreement(compare_with_brute_force(bvh, scene, mixed_rays(scene, 1000, 28)), "torus knot");
}

}  // namespace
}  // namespace gc::test
