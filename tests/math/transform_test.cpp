// Transform: points translate, vectors do not, normals go through the inverse transpose.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "host/math/transform.h"

namespace gc {
namespace {

TEST(Transform, PointsTranslateVectorsDoNot)
{
    const Transform t = Transform::translate(Vec3(1, 2, 3));
    EXPECT_EQ(t.apply(Point3(0, 0, 0)), Point3(1, 2, 3));
    EXPECT_EQ(t.apply(Point3(1, 1, 1)), Point3(2, 3, 4));
    EXPECT_EQ(t.apply(Vec3(1, 1, 1)), Vec3(1, 1, 1));
    EXPECT_EQ(t.apply(Normal3(0, 1, 0)), Normal3(0, 1, 0));
    // A difference of points transforms like a vector.
    const Point3 a{1, 0, 0}, b{0, 5, 2};
    EXPECT_EQ(t.apply(b) - t.apply(a), t.apply(b - a));
}

TEST(Transform, InverseUndoes)
{
    const Transform t = Transform::translate(Vec3(1, -2, 3)) * Transform::rotate(0.7f, Vec3(0, 1, 0)) *
                        Transform::scale(2, 3, 0.5f);
    const Point3 p{0.3f, -1.2f, 4.0f};
    const Point3 q = t.inverse().apply(t.apply(p));
    EXPECT_NEAR(q.x, p.x, 1e-5f);
    EXPECT_NEAR(q.y, p.y, 1e-5f);
    EXPECT_NEAR(q.z, p.z, 1e-5f);
}

TEST(Transform, NormalStaysPerpendicularUnderNonUniformScale)
{
    // A plane through the origin containing tangents t1, t2, with normal n = t1 x t2.
    const Vec3 t1 = normalize(Vec3(1, 1, 0));
    const Vec3 t2 = Vec3(0, 0, 1);
    const Normal3 n(cross(t1, t2));
    ASSERT_NEAR(dot(n, t1), 0.0f, 1e-6f);

    const Transform s = Transform::rotate(0.4f, Vec3(1, 2, 3)) * Transform::scale(4, 1, 0.25f);
    const Vec3 t1s = s.apply(t1), t2s = s.apply(t2);
    const Normal3 ns = s.apply(n);
    const float err = std::fabs(dot(normalize(ns), normalize(t1s)));
    std::printf("|cos(normal, tangent)| after non-uniform scale: %g (inverse transpose)\n", err);
    EXPECT_NEAR(err, 0.0f, 1e-5f);
    EXPECT_NEAR(dot(normalize(ns), normalize(t2s)), 0.0f, 1e-5f);

    // The plain matrix would have broken it: that is why normals are a separate type.
    const Vec3 wrong = s.apply(Vec3(n));
    const float wrong_cos = std::fabs(dot(normalize(wrong), normalize(t1s)));
    std::printf("|cos| if the normal were transformed as a vector: %g\n", wrong_cos);
    EXPECT_GT(wrong_cos, 0.1f);
}

TEST(Transform, SwapsHandedness)
{
    EXPECT_FALSE(Transform().swaps_handedness());
    EXPECT_FALSE(Transform::scale(2, 3, 4).swaps_handedness());
    EXPECT_TRUE(Transform::scale(-1, 1, 1).swaps_handedness());
    EXPECT_FALSE(Transform::scale(-1, -1, 1).swaps_handedness());
    EXPECT_TRUE((Transform::rotate(1.0f, Vec3(0, 0, 1)) * Transform::scale(1, 1, -2)).swaps_handedness());
    EXPECT_FALSE(Transform::translate(Vec3(-5, -5, -5)).swaps_handedness());
}

TEST(Transform, CompositionOrder)
{
    // (T * S) applies S first.
    const Transform ts = Transform::translate(Vec3(1, 0, 0)) * Transform::scale(2, 2, 2);
    EXPECT_EQ(ts.apply(Point3(1, 1, 1)), Point3(3, 2, 2));
    const Transform st = Transform::scale(2, 2, 2) * Transform::translate(Vec3(1, 0, 0));
    EXPECT_EQ(st.apply(Point3(1, 1, 1)), Point3(4, 2, 2));
}

}  // namespace
}  // namespace gc
