// Typed affine math after Goldman: points, vectors and normals are different things.
//
//   Point3 - Point3 -> Vec3        Point3 +/- Vec3 -> Point3      Vec3 +/- Vec3 -> Vec3
//   scalar * Vec3   -> Vec3        scalar * Normal3 -> Normal3
//
// and nothing else: Point3 + Point3, scalar * Point3, Vec3 - Point3 and dot/cross with
// points do not compile. Affine combinations of points go through lerp, barycentric and
// midpoint, which are the only meaningful ones. Conversions between kinds are explicit.
// Normals transform by the inverse transpose (transform.h). tests/math proves the table.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

namespace gc {

class Vec3;
class Normal3;

// A displacement. Storage is a glm::vec3, reachable through glm() for interop.
class Vec3 {
public:
    float x = 0, y = 0, z = 0;

    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    explicit constexpr Vec3(const glm::vec3& v) : x(v.x), y(v.y), z(v.z) {}
    explicit constexpr Vec3(const Normal3& n);

    glm::vec3 glm() const { return {x, y, z}; }
    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }

    Vec3 operator+(const Vec3& v) const { return {x + v.x, y + v.y, z + v.z}; }
    Vec3 operator-(const Vec3& v) const { return {x - v.x, y - v.y, z - v.z}; }
    Vec3 operator-() const { return {-x, -y, -z}; }
    Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
    Vec3 operator/(float s) const { return {x / s, y / s, z / s}; }
    Vec3& operator+=(const Vec3& v) { return *this = *this + v; }
    Vec3& operator-=(const Vec3& v) { return *this = *this - v; }
    Vec3& operator*=(float s) { return *this = *this * s; }
    bool operator==(const Vec3&) const = default;
};

inline Vec3 operator*(float s, const Vec3& v) { return v * s; }

// A position. Only differences of points, and points moved by vectors, are defined.
class Point3 {
public:
    float x = 0, y = 0, z = 0;

    constexpr Point3() = default;
    constexpr Point3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    explicit constexpr Point3(const glm::vec3& v) : x(v.x), y(v.y), z(v.z) {}

    static constexpr Point3 origin() { return {0, 0, 0}; }
    glm::vec3 glm() const { return {x, y, z}; }
    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }

    Vec3 operator-(const Point3& p) const { return {x - p.x, y - p.y, z - p.z}; }
    Point3 operator+(const Vec3& v) const { return {x + v.x, y + v.y, z + v.z}; }
    Point3 operator-(const Vec3& v) const { return {x - v.x, y - v.y, z - v.z}; }
    Point3& operator+=(const Vec3& v) { return *this = *this + v; }
    Point3& operator-=(const Vec3& v) { return *this = *this - v; }
    bool operator==(const Point3&) const = default;
};

// A surface normal: a covector. Scales and adds like a vector but is never crossed with
// another normal nor transformed by the plain matrix.
class Normal3 {
public:
    float x = 0, y = 0, z = 0;

    constexpr Normal3() = default;
    constexpr Normal3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    explicit constexpr Normal3(const Vec3& v) : x(v.x), y(v.y), z(v.z) {}
    explicit constexpr Normal3(const glm::vec3& v) : x(v.x), y(v.y), z(v.z) {}

    glm::vec3 glm() const { return {x, y, z}; }
    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }

    Normal3 operator+(const Normal3& n) const { return {x + n.x, y + n.y, z + n.z}; }
    Normal3 operator-(const Normal3& n) const { return {x - n.x, y - n.y, z - n.z}; }
    Normal3 operator-() const { return {-x, -y, -z}; }
    Normal3 operator*(float s) const { return {x * s, y * s, z * s}; }
    Normal3 operator/(float s) const { return {x / s, y / s, z / s}; }
    Normal3& operator+=(const Normal3& n) { return *this = *this + n; }
    bool operator==(const Normal3&) const = default;
};

inline Normal3 operator*(float s, const Normal3& n) { return n * s; }

constexpr Vec3::Vec3(const Normal3& n) : x(n.x), y(n.y), z(n.z) {}

// --- Products. No overload takes a Point3.
inline float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float dot(const Vec3& a, const Normal3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float dot(const Normal3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float dot(const Normal3& a, const Normal3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float absdot(const Vec3& a, const Normal3& b) { return std::fabs(dot(a, b)); }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

inline float length_squared(const Vec3& v) { return dot(v, v); }
inline float length(const Vec3& v) { return std::sqrt(length_squared(v)); }
inline float length(const Normal3& n) { return std::sqrt(dot(n, n)); }
inline Vec3 normalize(const Vec3& v) { return v / length(v); }
inline Normal3 normalize(const Normal3& n) { return n / length(n); }
inline float distance(const Point3& a, const Point3& b) { return length(a - b); }

namespace detail {
inline Vec3 unit_vector_in_double(double x, double y, double z)
{
    const double len = std::sqrt(x * x + y * y + z * z);
    if (!(len > 0.0)) return {};
    return {static_cast<float>(x / len), static_cast<float>(y / len), static_cast<float>(z / len)};
}
}  // namespace detail

// v / |v| computed in double: in float, |v|^2 underflows for |v| below ~1e-19 and overflows
// above ~1e19, where normalize() returns NaN or zero. The zero vector stays zero.
inline Vec3 unit_vector(const Vec3& v) { return detail::unit_vector_in_double(v.x, v.y, v.z); }

// The unit vector from `from` towards `to`, differenced in double too (the float difference
// of two distant points can overflow). Zero when the points coincide.
inline Vec3 unit_direction(const Point3& from, const Point3& to)
{
    return detail::unit_vector_in_double(double(to.x) - from.x, double(to.y) - from.y, double(to.z) - from.z);
}

// Flips n to the hemisphere of v (pbrt's FaceForward).
inline Normal3 face_forward(const Normal3& n, const Vec3& v) { return dot(n, v) < 0 ? -n : n; }

// --- The affine combinations of points.
// (1 - t) a + t b, written as a + t (b - a) so it never adds points.
inline Point3 lerp(float t, const Point3& a, const Point3& b) { return a + t * (b - a); }
inline Point3 midpoint(const Point3& a, const Point3& b) { return a + 0.5f * (b - a); }
// p0 + b1 (p1 - p0) + b2 (p2 - p0): the point with barycentrics (1 - b1 - b2, b1, b2).
inline Point3 barycentric(const Point3& p0, const Point3& p1, const Point3& p2, float b1, float b2)
{
    return p0 + b1 * (p1 - p0) + b2 * (p2 - p0);
}

// Component-wise extremes: bounding boxes need them, and they are affine-invariant.
inline Point3 min(const Point3& a, const Point3& b)
{
    return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)};
}
inline Point3 max(const Point3& a, const Point3& b)
{
    return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)};
}

inline bool is_finite(const Point3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }
inline bool is_finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool is_finite(const Normal3& n) { return std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z); }

}  // namespace gc
