// kernels/shared/gc_intersect.h on its own: the slab test's +-0 / NaN handling and the
// watertight triangle test.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "gc_intersect.h"

namespace gc::dev {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float3 inv(float3 d) { return {1.0f / d.x, 1.0f / d.y, 1.0f / d.z}; }

float box_entry(float3 o, float3 d, float tmin = 0.0f, float tmax = kInf)
{
    return gc_intersect_aabb(o, inv(d), tmin, tmax, float3(0, 0, 0), float3(1, 1, 1));
}

// The box test returns the entry lowered by a small absolute margin (gc_intersect.h), never
// more than the true entry.
void expect_entry(float got, float expected)
{
    EXPECT_LE(got, expected);
    EXPECT_NEAR(got, expected, 1e-4f * std::fmax(1.0f, std::fabs(expected)));
}

TEST(IntersectAabb, HitReturnsEntryClippedToTmin)
{
    expect_entry(box_entry({0.5f, 0.5f, -1.0f}, {0, 0, 1}), 1.0f);
    expect_entry(box_entry({0.5f, 0.5f, 0.5f}, {0, 0, 1}), 0.0f);
    expect_entry(box_entry({0.5f, 0.5f, -1.0f}, {0, 0, 1}, 1.5f), 1.5f);
}

TEST(IntersectAabb, MissesReturnSentinel)
{
    EXPECT_EQ(box_entry({0.5f, 0.5f, -1.0f}, {0, 0, -1}), GC_AABB_MISS) << "box behind";
    EXPECT_EQ(box_entry({0.5f, 0.5f, -1.0f}, {0, 0, 1}, 0.0f, 0.5f), GC_AABB_MISS) << "tmax before box";
    EXPECT_EQ(box_entry({0.5f, 0.5f, -1.0f}, {0, 0, 1}, 2.5f), GC_AABB_MISS) << "tmin after box";
    EXPECT_EQ(box_entry({2.0f, 0.5f, -1.0f}, {1, 0, 1}), GC_AABB_MISS) << "passes beside";
}

TEST(IntersectAabb, SignedZeroDirectionComponents)
{
    // Parallel to the x slabs, inside them: +0 and -0 must agree and hit.
    for (float zero : {0.0f, -0.0f}) {
        for (float zero2 : {0.0f, -0.0f}) {
            expect_entry(box_entry({0.5f, 0.5f, -1.0f}, {zero, zero2, 1}), 1.0f);
            EXPECT_EQ(box_entry({1.5f, 0.5f, -1.0f}, {zero, zero2, 1}), GC_AABB_MISS) << "outside the x slab";
            EXPECT_EQ(box_entry({-0.5f, 0.5f, -1.0f}, {zero, zero2, 1}), GC_AABB_MISS) << "outside the x slab";
        }
    }
}

TEST(IntersectAabb, OriginOnSlabPlaneWithZeroComponentIsInside)
{
    // (plane - o) * inf = 0 * inf = NaN: the closed slab contains the ray, so it must hit,
    // for both planes and both zero signs, and never return NaN.
    for (float x : {0.0f, 1.0f}) {
        for (float zero : {0.0f, -0.0f}) {
            expect_entry(box_entry({x, 0.5f, -1.0f}, {zero, 0, 1}), 1.0f);
        }
    }
    // On an edge of the box (two NaN axes) too.
    expect_entry(box_entry({1.0f, 0.0f, -2.0f}, {-0.0f, 0.0f, 1}), 2.0f);
}

TEST(IntersectAabb, FlatBoxIsHit)
{
    const float e = gc_intersect_aabb({0.5f, 0.5f, -1.0f}, inv({0, 0, 1}), 0.0f, kInf, {0, 0, 0.25f}, {1, 1, 0.25f});
    expect_entry(e, 1.25f);
}

TEST(IntersectAabb, EmptyBoundsAlwaysMiss)
{
    const float3 lo(kInf, kInf, kInf);
    const float3 hi(-kInf, -kInf, -kInf);
    int hits = 0;
    const float comps[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.3f};
    for (float dx : comps)
        for (float dy : comps)
            for (float dz : comps) {
                if (dx == 0 && dy == 0 && dz == 0) continue;
                for (float o : {0.0f, -3.0f, 1e30f})
                    if (gc_intersect_aabb({o, o, o}, inv({dx, dy, dz}), 0.0f, kInf, lo, hi) < GC_AABB_MISS) ++hits;
            }
    EXPECT_EQ(hits, 0);
}

TEST(RayValidity, RejectsNanZeroDirectionAndEmptyInterval)
{
    const float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(gc_ray_is_valid(gc_make_ray({0, 0, 0}, {0, 0, 1}, 0.0f, kInf)));
    EXPECT_TRUE(gc_ray_is_valid(gc_make_ray({0, 0, 0}, {-0.0f, 0, 1}, 0.0f, 0.0f)));
    EXPECT_FALSE(gc_ray_is_valid(gc_make_ray({nan, 0, 0}, {0, 0, 1}, 0.0f, kInf)));
    EXPECT_FALSE(gc_ray_is_valid(gc_make_ray({0, 0, 0}, {0, nan, 1}, 0.0f, kInf)));
    EXPECT_FALSE(gc_ray_is_valid(gc_make_ray({0, 0, 0}, {0, -0.0f, 0}, 0.0f, kInf)));
    EXPECT_FALSE(gc_ray_is_valid(gc_make_ray({0, 0, 0}, {0, 0, 1}, 2.0f, 1.0f)));
    EXPECT_FALSE(gc_ray_is_valid(gc_make_ray({0, 0, 0}, {0, 0, 1}, nan, 1.0f)));
}

GcHit hit_triangle(float3 o, float3 d, float3 a, float3 b, float3 c, float tmin = 0.0f, float tmax = kInf)
{
    return gc_intersect_triangle(gc_ray_precompute(gc_make_ray(o, d, tmin, tmax)), a, b, c, tmax);
}

TEST(IntersectTriangle, HitDistanceAndBarycentrics)
{
    const float3 a(0, 0, 2), b(1, 0, 2), c(0, 1, 2);
    const GcHit h = hit_triangle({0.25f, 0.5f, 0.0f}, {0, 0, 1}, a, b, c);
    ASSERT_EQ(h.prim, 0u);
    EXPECT_EQ(h.t, 2.0f);
    EXPECT_FLOAT_EQ(h.u, 0.25f);
    EXPECT_FLOAT_EQ(h.v, 0.5f);
    // Two-sided: the same from behind, and with a non-unit, negative direction.
    const GcHit back = hit_triangle({0.25f, 0.5f, 4.0f}, {0, 0, -2}, a, b, c);
    ASSERT_EQ(back.prim, 0u);
    EXPECT_EQ(back.t, 1.0f);
    EXPECT_FLOAT_EQ(back.u, 0.25f);
}

TEST(IntersectTriangle, MissesOutsideAndOutsideInterval)
{
    const float3 a(0, 0, 2), b(1, 0, 2), c(0, 1, 2);
    EXPECT_EQ(hit_triangle({0.75f, 0.5f, 0.0f}, {0, 0, 1}, a, b, c).prim, GC_INVALID) << "beyond the hypotenuse";
    EXPECT_EQ(hit_triangle({0.25f, 0.25f, 0.0f}, {0, 0, 1}, a, b, c, 0.0f, 1.999f).prim, GC_INVALID);
    EXPECT_EQ(hit_triangle({0.25f, 0.25f, 0.0f}, {0, 0, 1}, a, b, c, 2.001f).prim, GC_INVALID);
    EXPECT_EQ(hit_triangle({0.25f, 0.25f, 0.0f}, {0, 0, 1}, a, b, c, 2.0f, 2.0f).prim, 0u) << "interval is closed";
    EXPECT_EQ(hit_triangle({0.25f, 0.25f, 3.0f}, {0, 0, 1}, a, b, c).prim, GC_INVALID) << "behind the origin";
}

TEST(IntersectTriangle, DegenerateTrianglesNeverHit)
{
    const float3 p(0.5f, 0.5f, 2.0f);
    EXPECT_EQ(hit_triangle({0.5f, 0.5f, 0.0f}, {0, 0, 1}, p, p, p).prim, GC_INVALID) << "point";
    // Segment seen end-on and side-on.
    EXPECT_EQ(hit_triangle({0.5f, 0.5f, 0.0f}, {0, 0, 1}, {0.5f, 0.5f, 2}, {0.5f, 0.5f, 3}, {0.5f, 0.5f, 4}).prim,
              GC_INVALID);
    EXPECT_EQ(hit_triangle({0.5f, 0.5f, 0.0f}, {0, 0, 1}, {0, 0.5f, 2}, {1, 0.5f, 2}, {0.25f, 0.5f, 2}).prim,
              GC_INVALID);
}

TEST(IntersectTriangle, SharedEdgesAndVerticesAreWatertight)
{
    // A fan of 8 triangles around the point (0.3, 0.7, 5) in a tilted plane; rays from the
    // origin through the centre vertex and through points on the shared edges must hit at
    // least one triangle of the fan.
    const float3 centre(0.3f, 0.7f, 5.0f);
    float3 rim[8];
    for (int i = 0; i < 8; ++i) {
        const float ang = 0.785398163f * static_cast<float>(i);
        rim[i] = float3(0.3f + std::cos(ang), 0.7f + std::sin(ang), 5.0f + 0.37f * std::cos(ang) - 0.21f * std::sin(ang));
    }
    int misses = 0;
    int probes = 0;
    // s = 0 aims at the centre vertex, shared by all 8. s stays below 1: the rim vertices are
    // on the fan's outer boundary, where rounding of the target may legitimately step outside.
    for (int k = 0; k < 64; ++k) {
        const float s = static_cast<float>(k) / 64.0f;
        for (int e = 0; e < 8; ++e) {
            const float3 target = centre + s * (rim[e] - centre); // on the edge shared by e-1 and e
            int hits = 0;
            for (int i = 0; i < 8; ++i)
                if (hit_triangle({0, 0, 0}, target, centre, rim[i], rim[(i + 1) % 8]).prim == 0u) ++hits;
            ++probes;
            if (hits == 0 && ++misses <= 5) std::printf("  leak at edge %d, s = %g\n", e, double(s));
        }
    }
    std::printf("[ fan ] %d edge/vertex probes, %d leaked\n", probes, misses);
    EXPECT_EQ(misses, 0);
}

}  // namespace
}  // namespace gc::dev
