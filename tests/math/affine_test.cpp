// Runtime values of the typed-math helpers: the affine combinations and products.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "host/math/affine.h"
#include "host/math/ray.h"

namespace gc {
namespace {

void expect_point_near(const Point3& got, const Point3& want, float tol = 1e-6f)
{
    EXPECT_NEAR(got.x, want.x, tol);
    EXPECT_NEAR(got.y, want.y, tol);
    EXPECT_NEAR(got.z, want.z, tol);
}

TEST(Affine, PointDifferenceAndDisplacement)
{
    const Point3 a{1, 2, 3}, b{4, 6, 3};
    const Vec3 d = b - a;
    EXPECT_EQ(d, Vec3(3, 4, 0));
    EXPECT_EQ(a + d, b);
    EXPECT_EQ(b - d, a);
    EXPECT_FLOAT_EQ(distance(a, b), 5.0f);
}

TEST(Affine, LerpEndpointsAndInterior)
{
    const Point3 a{1, 2, 3}, b{5, -2, 7};
    expect_point_near(lerp(0.0f, a, b), a);
    expect_point_near(lerp(1.0f, a, b), b);
    expect_point_near(lerp(0.25f, a, b), Point3(2, 1, 4));
    // Extrapolation is still an affine combination (weights -1 and 2).
    expect_point_near(lerp(2.0f, a, b), Point3(9, -6, 11));
}

// unit_vector / unit_direction work where float's squared length does not: below ~1e-19 it
// underflows to 0 (normalize gives NaN), above ~1e19 it overflows (normalize gives 0).
TEST(Affine, UnitVectorsAtAnyScale)
{
    for (const float scale : {1e-40f, 1e-30f, 1e-20f, 1.0f, 1e20f, 1e30f, 3e38f}) {
        const Vec3 u = unit_vector(Vec3(3 * (scale / 5), 0, 4 * (scale / 5)));
        EXPECT_NEAR(u.x, 0.6f, 1e-3f) << scale;  // 1e-40 is subnormal: only a few digits
        EXPECT_NEAR(u.z, 0.8f, 1e-3f) << scale;
        const Vec3 d = unit_direction(Point3(-scale, 0, 0), Point3(scale, 0, 0));  // 2 * 3e38 overflows float
        EXPECT_EQ(d, Vec3(1, 0, 0)) << scale;
    }
    EXPECT_EQ(unit_vector(Vec3(0, 0, 0)), Vec3(0, 0, 0));
    EXPECT_EQ(unit_direction(Point3(1, 2, 3), Point3(1, 2, 3)), Vec3(0, 0, 0));
}

TEST(Affine, Midpoint)
{
    expect_point_near(midpoint(Point3(-1, 0, 2), Point3(3, 4, 2)), Point3(1, 2, 2));
    // Symmetric.
    expect_point_near(midpoint(Point3(3, 4, 2), Point3(-1, 0, 2)), Point3(1, 2, 2));
}

TEST(Affine, BarycentricVerticesAndCentroid)
{
    const Point3 p0{0, 0, 0}, p1{3, 0, 0}, p2{0, 6, 3};
    expect_point_near(barycentric(p0, p1, p2, 0, 0), p0);
    expect_point_near(barycentric(p0, p1, p2, 1, 0), p1);
    expect_point_near(barycentric(p0, p1, p2, 0, 1), p2);
    const float third = 1.0f / 3.0f;
    const Point3 c = barycentric(p0, p1, p2, third, third);
    std::printf("centroid = (%.7f, %.7f, %.7f)\n", c.x, c.y, c.z);
    expect_point_near(c, Point3(1, 2, 1), 1e-6f);
    // Edge midpoint p1-p2 has barycentrics (0, 1/2, 1/2).
    expect_point_near(barycentric(p0, p1, p2, 0.5f, 0.5f), midpoint(p1, p2));
}

TEST(Affine, DotCrossAndNormals)
{
    const Vec3 x{1, 0, 0}, y{0, 1, 0};
    EXPECT_EQ(cross(x, y), Vec3(0, 0, 1));
    EXPECT_EQ(cross(y, x), Vec3(0, 0, -1));
    EXPECT_FLOAT_EQ(dot(Vec3(1, 2, 3), Vec3(4, -5, 6)), 12.0f);
    EXPECT_FLOAT_EQ(dot(Vec3(1, 2, 3), Normal3(0, 0, 1)), 3.0f);
    EXPECT_FLOAT_EQ(absdot(Vec3(1, 2, -3), Normal3(0, 0, 1)), 3.0f);
    EXPECT_FLOAT_EQ(length(normalize(Vec3(3, 4, 12))), 1.0f);
    EXPECT_EQ(face_forward(Normal3(0, 0, 1), Vec3(0, 0, -1)), Normal3(0, 0, -1));
    EXPECT_EQ(face_forward(Normal3(0, 0, 1), Vec3(0, 1, 1)), Normal3(0, 0, 1));
    // Explicit conversions keep the components.
    EXPECT_EQ(Vec3(Normal3(1, 2, 3)), Vec3(1, 2, 3));
    EXPECT_EQ(Normal3(Vec3(1, 2, 3)), Normal3(1, 2, 3));
    EXPECT_EQ(Point3(1, 2, 3) - Point3::origin(), Vec3(1, 2, 3));
}

TEST(Affine, MinMaxAndFinite)
{
    EXPECT_EQ(min(Point3(1, 5, -2), Point3(3, 0, 4)), Point3(1, 0, -2));
    EXPECT_EQ(max(Point3(1, 5, -2), Point3(3, 0, 4)), Point3(3, 5, 4));
    EXPECT_TRUE(is_finite(Point3(1, 2, 3)));
    EXPECT_FALSE(is_finite(Vec3(1, NAN, 3)));
    EXPECT_FALSE(is_finite(Normal3(INFINITY, 0, 0)));
}

TEST(Affine, RayAt)
{
    const Ray r{Point3(1, 1, 1), Vec3(0, 2, 0), 0.5f, 4.0f};
    EXPECT_EQ(r.at(1.5f), Point3(1, 4, 1));
    EXPECT_TRUE(r.contains(0.5f));
    EXPECT_FALSE(r.contains(4.5f));
}

}  // namespace
}  // namespace gc
