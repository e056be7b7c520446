// The two-level traversal (gc_traverse_instances.h) against the flattened scene
// (flatten_instances + the one-level BVH, itself checked against brute force in
// traverse_test.cpp), in every layout, plus the instanced scene's checks and memory.
#include <bit>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "bvh_checks.h"
#include "host/bvh/bvh.h"
#include "host/bvh/traverse_host.h"
#include "host/bvh/traverse_instances_host.h"
#include "host/util/error.h"
#include "instance_scenes.h"

namespace gc {
namespace {

using test::FlatIndex;

// The instanced hit in the flattened scene's terms (prim GC_INVALID on a miss).
dev::GcHit as_flat(const InstancedScene& s, const FlatIndex& index, const dev::GcInstanceHit& h)
{
    dev::GcHit out = h.hit;
    out.prim = h.instance == GC_INVALID ? GC_INVALID : index(s, h.instance, h.hit.prim);
    return out;
}

struct Layouts {
    InstancedBvh b2;
    InstancedBvh4 b4;
    InstancedBvh8 b8;
    explicit Layouts(const InstancedScene& s)
    {
        const InstanceBvhParts parts = build_instance_bvh(s);
        b2 = assemble_binary(parts);
        b4 = assemble_wide(parts);
        b8 = assemble_wide8(parts);
    }
};

TEST(InstanceTraversal, LatticeTransformsGiveTheFlattenedHitsBitForBit)
{
    const InstancedScene s = test::lattice_instances(3, 7);
    validate_instances(s);
    const Scene flat = flatten_instances(s);
    const FlatBvh flat_bvh = build_bvh(flat);
    const Layouts layouts(s);
    const FlatIndex index(s);
    const std::vector<Ray> rays = test::grid_rays(flat, 4000, 11);
    std::size_t hits = 0, twin_hits = 0, mismatches = 0, any_mismatches = 0;
    for (const Ray& r : rays) {
        const dev::GcHit want = trace_closest(flat_bvh, r);
        const bool want_any = trace_any(flat_bvh, r);
        hits += want.prim != GC_INVALID;
        const dev::GcInstanceHit got[3] = {trace_closest(layouts.b2, r), trace_closest(layouts.b4, r),
                                           trace_closest(layouts.b8, r)};
        const bool got_any[3] = {trace_any(layouts.b2, r), trace_any(layouts.b4, r), trace_any(layouts.b8, r)};
        for (int l = 0; l < 3; ++l) {
            mismatches += !test::same_bits(as_flat(s, index, got[l]), want);
            any_mismatches += got_any[l] != want_any;
        }
        twin_hits += got[0].instance == 0u;
    }
    std::printf("lattice: %zu instances, %zu rays, %zu hits (%zu on the twinned instance 0), "
                "%zu closest / %zu any mismatches over 3 layouts\n",
                s.instances.size(), rays.size(), hits, twin_hits, mismatches, any_mismatches);
    EXPECT_GT(hits, rays.size() / 3);
    EXPECT_GT(twin_hits, 0u) << "the twin tie is never exercised";
    EXPECT_EQ(mismatches, 0u);
    EXPECT_EQ(any_mismatches, 0u);
}

TEST(InstanceTraversal, RotatedInstancesAgreeWithTheFlattenedSceneWithinRounding)
{
    const InstancedScene s = test::rotated_instances(40, 3);
    const Scene flat = flatten_instances(s);
    const FlatBvh flat_bvh = build_bvh(flat);
    const Layouts layouts(s);
    const FlatIndex index(s);
    const std::vector<Ray> rays = test::mixed_rays(flat, 4000, 5);
    // The transforms round in world space (flattened vertices) and in object space (the ray)
    // differently, by a few ulps of the coordinates. A hit's t moves by that shift over the
    // cosine of the incidence, so compare the shift itself: the two hit points' distance along
    // the triangle's normal, |delta t| |d . n|, against the scene's largest coordinate.
    const double scale = flat.bounds().largest_abs_coordinate();
    std::size_t hits = 0, prim_mismatches = 0, layout_mismatches = 0;
    double max_rel_t = 0.0;
    for (const Ray& r : rays) {
        const dev::GcHit want = trace_closest(flat_bvh, r);
        const dev::GcInstanceHit got = trace_closest(layouts.b2, r);
        hits += want.prim != GC_INVALID;
        const dev::GcHit g = as_flat(s, index, got);
        // Every layout traces the same object-space rays: those agree bit for bit.
        layout_mismatches += !test::same_bits(as_flat(s, index, trace_closest(layouts.b4, r)), g);
        layout_mismatches += !test::same_bits(as_flat(s, index, trace_closest(layouts.b8, r)), g);
        if (g.prim != want.prim) {
            ++prim_mismatches;
            continue;
        }
        if (want.prim != GC_INVALID)
        {
            const Point3 a = flat.vertex(want.prim, 0);
            const Vec3 n = normalize(cross(flat.vertex(want.prim, 1) - a, flat.vertex(want.prim, 2) - a));
            const double shift = std::fabs(double(g.t) - want.t) * std::fabs(double(dot(r.direction, n)));
            max_rel_t = std::max(max_rel_t, shift / scale);
        }
    }
    std::printf("rotated: %zu rays, %zu hits, %zu prim mismatches (%.3f %%), max |delta t| |d . n| / largest coordinate %.3g, "
                "%zu layout mismatches\n",
                rays.size(), hits, prim_mismatches, 100.0 * double(prim_mismatches) / double(rays.size()), max_rel_t,
                layout_mismatches);
    EXPECT_GT(hits, rays.size() / 3);
    // A ray within rounding of a shared edge may take the neighbour: a handful in 4000.
    EXPECT_LE(prim_mismatches, rays.size() / 200);
    EXPECT_LT(max_rel_t, 1e-6);  // about 16 ulps of the largest coordinate
    EXPECT_EQ(layout_mismatches, 0u);
}

TEST(InstanceTraversal, NoInstancesMissEverything)
{
    InstancedScene s = test::lattice_instances(1, 2);
    s.instances.clear();
    const Layouts layouts(s);
    for (const Ray& r : test::mixed_rays(s.meshes, 200, 1)) {
        EXPECT_EQ(trace_closest(layouts.b2, r).instance, GC_INVALID);
        EXPECT_EQ(trace_closest(layouts.b8, r).instance, GC_INVALID);
        EXPECT_FALSE(trace_any(layouts.b4, r));
    }
}

TEST(InstanceTraversal, MemoryGrowsWithInstancesNotTriangles)
{
    InstancedScene small = test::rotated_instances(100, 9);
    InstancedScene large = test::rotated_instances(800, 9);
    const InstancedBvh a = assemble_binary(build_instance_bvh(small));
    const InstancedBvh b = assemble_binary(build_instance_bvh(large));
    const double per_instance = double(b.instance_bytes() - a.instance_bytes()) / 700.0;
    const std::size_t flat_bytes = build_bvh(flatten_instances(large)).nodes.size() * sizeof(dev::GcBvhNode) +
                                   build_bvh(flatten_instances(large)).triangles.size() * sizeof(dev::GcTriangle);
    std::printf("meshes %zu bytes (both), instances %.1f bytes each; 800 instances %zu bytes vs flattened %zu\n",
                a.mesh_bytes(), per_instance, b.instance_bytes() + b.mesh_bytes(), flat_bytes);
    EXPECT_EQ(a.mesh_bytes(), b.mesh_bytes());
    EXPECT_LT(per_instance, 160.0);
    EXPECT_LT(b.instance_bytes() + b.mesh_bytes(), flat_bytes / 10);
}

TEST(InstanceValidation, BadMeshIndexAndSingularTransformNameTheFile)
{
    InstancedScene s = test::lattice_instances(1, 4);
    s.meshes.source_path = "scenes/bad-instances.gltf";
    s.instances[0].mesh = 7;
    try {
        validate_instances(s);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scenes/bad-instances.gltf"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("mesh 7"), std::string::npos) << e.what();
    }
    s.instances[0].mesh = 0;
    s.instances[0].object_to_world[1] = glm::vec4(0.0f);
    EXPECT_THROW(flatten_instances(s), InputError);
    s.instances[0].object_to_world = glm::mat4(1.0f);
    s.mesh_ranges[1].triangle_count = 1000;
    EXPECT_THROW(validate_instances(s), InputError);
}

}  // namespace
}  // namespace gc
