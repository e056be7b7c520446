// Compile-time proof of the typed-math table in host/math/affine.h (Goldman, "On the
// algebraic and geometric foundations of computer graphics", TOG 2002). Each concept asks
// whether an expression is well formed; a static_assert on it turns "this must not compile"
// into a test that fails the build if affine.h ever grows a hole. The concepts must be
// templates: a bare requires-expression outside a template would be ill-formed, not false.
#include <concepts>
#include <cstdio>
#include <type_traits>

#include <gtest/gtest.h>

#include "host/math/affine.h"

namespace gc {
namespace {

template <class A, class B> concept Addable = requires(A a, B b) { a + b; };
template <class A, class B> concept Subtractable = requires(A a, B b) { a - b; };
template <class A, class B> concept Multipliable = requires(A a, B b) { a * b; };
template <class A, class B> concept Divisible = requires(A a, B b) { a / b; };
template <class A, class B> concept AddAssignable = requires(A a, B b) { a += b; };
template <class A, class B> concept SubAssignable = requires(A a, B b) { a -= b; };
template <class A> concept Negatable = requires(A a) { -a; };
template <class A, class B> concept Dottable = requires(A a, B b) { dot(a, b); };
template <class A, class B> concept Crossable = requires(A a, B b) { cross(a, b); };
template <class A> concept HasLength = requires(A a) { length(a); };
template <class A> concept Normalizable = requires(A a) { normalize(a); };

// The result type of an expression, for the legal rows of the table.
template <class A, class B> using SumT = decltype(std::declval<A>() + std::declval<B>());
template <class A, class B> using DiffT = decltype(std::declval<A>() - std::declval<B>());
template <class A, class B> using ProdT = decltype(std::declval<A>() * std::declval<B>());

// --- Point3: only differences and displacements.
static_assert(!Addable<Point3, Point3>, "Point3 + Point3 must not compile");
static_assert(!Multipliable<float, Point3>, "scalar * Point3 must not compile");
static_assert(!Multipliable<Point3, float>, "Point3 * scalar must not compile");
static_assert(!Multipliable<double, Point3>, "double * Point3 must not compile");
static_assert(!Multipliable<int, Point3>, "int * Point3 must not compile");
static_assert(!Divisible<Point3, float>, "Point3 / scalar must not compile");
static_assert(!Negatable<Point3>, "-Point3 must not compile");
static_assert(!AddAssignable<Point3&, Point3>, "Point3 += Point3 must not compile");
static_assert(!Addable<Point3, Normal3>, "Point3 + Normal3 must not compile");
static_assert(!Subtractable<Point3, Normal3>, "Point3 - Normal3 must not compile");

static_assert(std::same_as<DiffT<Point3, Point3>, Vec3>);
static_assert(std::same_as<SumT<Point3, Vec3>, Point3>);
static_assert(std::same_as<DiffT<Point3, Vec3>, Point3>);
static_assert(AddAssignable<Point3&, Vec3> && SubAssignable<Point3&, Vec3>);

// --- Vec3: a vector space, but a vector minus a point is meaningless; Vec3 + Point3 is
// the commuted Point3 + Vec3 and is not provided either (the table lists only p + v).
static_assert(!Subtractable<Vec3, Point3>, "Vec3 - Point3 must not compile");
static_assert(!Addable<Vec3, Point3>, "Vec3 + Point3 must not compile");
static_assert(!Addable<Vec3, Normal3>, "Vec3 + Normal3 must not compile (explicit conversion)");
static_assert(!Subtractable<Vec3, Normal3>, "Vec3 - Normal3 must not compile");
static_assert(!AddAssignable<Vec3&, Point3>);
static_assert(std::same_as<SumT<Vec3, Vec3>, Vec3>);
static_assert(std::same_as<DiffT<Vec3, Vec3>, Vec3>);
static_assert(std::same_as<ProdT<float, Vec3>, Vec3>);
static_assert(std::same_as<ProdT<Vec3, float>, Vec3>);
static_assert(std::same_as<decltype(-std::declval<Vec3>()), Vec3>);
static_assert(std::same_as<decltype(std::declval<Vec3>() / 2.0f), Vec3>);

// --- Normal3: scales and adds with normals only.
static_assert(!Addable<Normal3, Vec3>, "Normal3 + Vec3 must not compile");
static_assert(!Addable<Normal3, Point3>, "Normal3 + Point3 must not compile");
static_assert(std::same_as<SumT<Normal3, Normal3>, Normal3>);
static_assert(std::same_as<ProdT<float, Normal3>, Normal3>);
static_assert(std::same_as<ProdT<Normal3, float>, Normal3>);
static_assert(std::same_as<decltype(-std::declval<Normal3>()), Normal3>);

// --- Products: never with a point; no cross of two normals.
static_assert(!Dottable<Point3, Vec3>, "dot(Point3, Vec3) must not compile");
static_assert(!Dottable<Vec3, Point3>, "dot(Vec3, Point3) must not compile");
static_assert(!Dottable<Point3, Point3>, "dot(Point3, Point3) must not compile");
static_assert(!Dottable<Point3, Normal3>, "dot(Point3, Normal3) must not compile");
static_assert(!Crossable<Point3, Vec3>, "cross(Point3, Vec3) must not compile");
static_assert(!Crossable<Vec3, Point3>, "cross(Vec3, Point3) must not compile");
static_assert(!Crossable<Point3, Point3>, "cross(Point3, Point3) must not compile");
static_assert(!Crossable<Normal3, Normal3>, "cross(Normal3, Normal3) must not compile");
static_assert(!Crossable<Vec3, Normal3>, "cross(Vec3, Normal3) must not compile (convert explicitly)");
static_assert(!HasLength<Point3>, "length(Point3) must not compile");
static_assert(!Normalizable<Point3>, "normalize(Point3) must not compile");
static_assert(std::same_as<decltype(dot(Vec3{}, Vec3{})), float>);
static_assert(std::same_as<decltype(dot(Vec3{}, Normal3{})), float>);
static_assert(std::same_as<decltype(dot(Normal3{}, Vec3{})), float>);
static_assert(std::same_as<decltype(cross(Vec3{}, Vec3{})), Vec3>);
static_assert(std::same_as<decltype(distance(Point3{}, Point3{})), float>);

// --- Conversions between kinds are explicit only.
static_assert(!std::is_convertible_v<Vec3, Point3>, "Vec3 -> Point3 must not be implicit");
static_assert(!std::is_convertible_v<Point3, Vec3>, "Point3 -> Vec3 must not be implicit");
static_assert(!std::is_convertible_v<Vec3, Normal3>, "Vec3 -> Normal3 must not be implicit");
static_assert(!std::is_convertible_v<Normal3, Vec3>, "Normal3 -> Vec3 must not be implicit");
static_assert(!std::is_convertible_v<Point3, Normal3>, "Point3 -> Normal3 must not be implicit");
static_assert(!std::is_convertible_v<Normal3, Point3>, "Normal3 -> Point3 must not be implicit");
static_assert(!std::is_convertible_v<glm::vec3, Point3>, "glm::vec3 -> Point3 must not be implicit");
static_assert(!std::is_convertible_v<glm::vec3, Vec3>, "glm::vec3 -> Vec3 must not be implicit");
static_assert(std::is_constructible_v<Normal3, Vec3> && std::is_constructible_v<Vec3, Normal3>);
static_assert(std::is_constructible_v<Point3, glm::vec3> && std::is_constructible_v<Vec3, glm::vec3>);
// A point becomes a vector only as a difference from the origin.
static_assert(!std::is_constructible_v<Vec3, Point3>, "Vec3(Point3) must not exist: use p - Point3::origin()");
static_assert(!std::is_constructible_v<Point3, Vec3>, "Point3(Vec3) must not exist: use Point3::origin() + v");

// --- The affine combinations return points.
static_assert(std::same_as<decltype(lerp(0.5f, Point3{}, Point3{})), Point3>);
static_assert(std::same_as<decltype(midpoint(Point3{}, Point3{})), Point3>);
static_assert(std::same_as<decltype(barycentric(Point3{}, Point3{}, Point3{}, 0.f, 0.f)), Point3>);

// A runtime witness so the table shows up in the test list (it already passed at compile time).
TEST(AffineTable, IllegalExpressionsDoNotCompile)
{
    std::printf("typed-math table: every static_assert above held at compile time\n");
    EXPECT_FALSE((Addable<Point3, Point3>));
    EXPECT_FALSE((Multipliable<float, Point3>));
    EXPECT_FALSE((Crossable<Normal3, Normal3>));
    EXPECT_TRUE((Addable<Point3, Vec3>));
}

}  // namespace
}  // namespace gc
