// Bounds3: the empty box, unions, surface area and the helpers the BVH builder uses.
#include <cstdio>

#include <gtest/gtest.h>

#include "host/math/bounds3.h"

namespace gc {
namespace {

TEST(Bounds3, DefaultIsEmptyAndUnionIdentity)
{
    const Bounds3 empty;
    EXPECT_TRUE(empty.empty());
    EXPECT_EQ(empty.surface_area(), 0.0f);
    const Bounds3 b(Point3(0, 0, 0), Point3(1, 2, 3));
    const Bounds3 u = unite(empty, b);
    EXPECT_EQ(u.lo, b.lo);
    EXPECT_EQ(u.hi, b.hi);
    EXPECT_TRUE(unite(empty, empty).empty());
}

TEST(Bounds3, ConstructorOrdersCorners)
{
    const Bounds3 b(Point3(1, -1, 5), Point3(-2, 3, 0));
    EXPECT_EQ(b.lo, Point3(-2, -1, 0));
    EXPECT_EQ(b.hi, Point3(1, 3, 5));
    EXPECT_FALSE(b.empty());
}

TEST(Bounds3, UnionWithBoxAndPoint)
{
    const Bounds3 a(Point3(0, 0, 0), Point3(1, 1, 1));
    const Bounds3 b(Point3(2, -1, 0.5f), Point3(3, 0.5f, 0.75f));
    const Bounds3 u = unite(a, b);
    EXPECT_EQ(u.lo, Point3(0, -1, 0));
    EXPECT_EQ(u.hi, Point3(3, 1, 1));
    EXPECT_TRUE(u.contains(a));
    EXPECT_TRUE(u.contains(b));
    const Bounds3 p = unite(Bounds3(), Point3(4, 5, 6));
    EXPECT_FALSE(p.empty());  // a single point is a degenerate, non-empty box
    EXPECT_EQ(p.surface_area(), 0.0f);
    EXPECT_EQ(unite(a, Point3(-1, 0.5f, 2)).lo, Point3(-1, 0, 0));
}

TEST(Bounds3, SurfaceAreaCentroidExtent)
{
    const Bounds3 b(Point3(0, 0, 0), Point3(1, 2, 3));
    const float sa = b.surface_area();
    std::printf("surface area of 1x2x3 box = %g (want 22)\n", sa);
    EXPECT_FLOAT_EQ(sa, 22.0f);
    EXPECT_EQ(b.centroid(), Point3(0.5f, 1, 1.5f));
    EXPECT_EQ(b.max_extent(), 2);
    EXPECT_EQ(b.diagonal(), Vec3(1, 2, 3));
    EXPECT_EQ(b.offset(Point3(0.5f, 2, 0)), Vec3(0.5f, 1, 0));
    EXPECT_TRUE(b.contains(Point3(1, 2, 3)));
    EXPECT_FALSE(b.contains(Point3(1.001f, 1, 1)));
}

}  // namespace
}  // namespace gc
