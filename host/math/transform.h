// An affine transform with its inverse. apply() is overloaded by kind: points get the
// translation, vectors do not, normals go through the inverse transpose so they stay
// perpendicular to transformed surfaces.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "host/math/affine.h"

namespace gc {

class Transform {
public:
    Transform() = default;
    explicit Transform(const glm::mat4& m) : m_matrix(m), m_inverse(glm::inverse(m)) {}
    Transform(const glm::mat4& m, const glm::mat4& inverse) : m_matrix(m), m_inverse(inverse) {}

    static Transform translate(const Vec3& d) { return Transform(glm::translate(glm::mat4(1.0f), d.glm())); }
    static Transform scale(float sx, float sy, float sz)
    {
        return Transform(glm::scale(glm::mat4(1.0f), glm::vec3(sx, sy, sz)));
    }
    static Transform rotate(float radians, const Vec3& axis)
    {
        return Transform(glm::rotate(glm::mat4(1.0f), radians, axis.glm()));
    }

    const glm::mat4& matrix() const { return m_matrix; }
    const glm::mat4& inverse_matrix() const { return m_inverse; }
    Transform inverse() const { return Transform(m_inverse, m_matrix); }

    // True when the transform flips handedness, which flips triangle winding.
    bool swaps_handedness() const { return glm::determinant(glm::mat3(m_matrix)) < 0.0f; }

    Point3 apply(const Point3& p) const
    {
        const glm::vec4 r = m_matrix * glm::vec4(p.glm(), 1.0f);
        return Point3(glm::vec3(r) / r.w);
    }
    Vec3 apply(const Vec3& v) const { return Vec3(glm::mat3(m_matrix) * v.glm()); }
    Normal3 apply(const Normal3& n) const
    {
        return Normal3(glm::transpose(glm::mat3(m_inverse)) * n.glm());
    }

    Transform operator*(const Transform& t) const
    {
        return Transform(m_matrix * t.m_matrix, t.m_inverse * m_inverse);
    }

private:
    glm::mat4 m_matrix{1.0f};
    glm::mat4 m_inverse{1.0f};
};

}  // namespace gc
