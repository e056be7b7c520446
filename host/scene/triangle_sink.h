// Appends triangles to a Scene's flat arrays, keeping its invariants: three positions and
// normals per triangle, one material id and has_vertex_normals flag, and uvs and tangents each
// either empty or three per triangle. Both loaders go through it.
#pragma once

#include <cmath>
#include <cstdint>

#include "host/scene/scene.h"

namespace gc {

struct SinkCorner {
    Point3 position;
    Normal3 normal;        // read only when the triangle has vertex normals
    glm::vec2 uv{0.0f};    // read only when the triangle has uvs
    glm::vec4 tangent{0.0f}; // read only when the triangle has tangents: xyz unit, w = +-1
};

// The geometric normal of a counter-clockwise triangle; +Z for a zero-area one, so that
// degenerate triangles (kept: files have them; no ray hits them) never put a NaN into the
// scene. In double: in float the cross product's squared length overflows or underflows for
// triangles ~1e10 or ~1e-10 across, which left emitters of such scenes without a normal.
inline Normal3 face_normal(const Point3& p0, const Point3& p1, const Point3& p2)
{
    const glm::dvec3 c = glm::cross(glm::dvec3(p1.glm()) - glm::dvec3(p0.glm()), glm::dvec3(p2.glm()) - glm::dvec3(p0.glm()));
    const double len = glm::length(c);
    if (!(len > 0.0) || !std::isfinite(len)) return Normal3(0.0f, 0.0f, 1.0f);
    return Normal3(static_cast<float>(c.x / len), static_cast<float>(c.y / len), static_cast<float>(c.z / len));
}

class TriangleSink {
public:
    TriangleSink(Scene& scene, std::size_t expected_triangles) : m_scene(scene)
    {
        m_scene.positions.reserve(m_scene.positions.size() + 3 * expected_triangles);
        m_scene.normals.reserve(m_scene.normals.size() + 3 * expected_triangles);
        m_scene.material_ids.reserve(m_scene.material_ids.size() + expected_triangles);
        m_scene.has_vertex_normals.reserve(m_scene.has_vertex_normals.size() + expected_triangles);
    }

    // with_normals: use c[i].normal, normalized; a zero or non-finite one falls back to the face
    // normal at that corner. with_uv: store c[i].uv (the first such triangle back-fills zeros
    // for the triangles before it, so uvs stays three per triangle). with_tangents: store
    // c[i].tangent the same way (zeros mean "none": the renderer generates that triangle's).
    void add(const SinkCorner c[3], bool with_normals, bool with_uv, std::uint32_t material,
             bool with_tangents = false)
    {
        const Normal3 n_face = face_normal(c[0].position, c[1].position, c[2].position);
        for (int j = 0; j < 3; ++j) {
            m_scene.positions.push_back(c[j].position);
            Normal3 n = n_face;
            if (with_normals) {
                const float len = length(c[j].normal);
                if (len > 0.0f && std::isfinite(len)) n = c[j].normal / len;
            }
            m_scene.normals.push_back(n);
        }
        if (with_uv && m_scene.uvs.size() < 3 * m_scene.material_ids.size())
            m_scene.uvs.resize(3 * m_scene.material_ids.size(), glm::vec2(0.0f));
        if (with_uv || !m_scene.uvs.empty())
            for (int j = 0; j < 3; ++j) m_scene.uvs.push_back(with_uv ? c[j].uv : glm::vec2(0.0f));
        if (with_tangents && m_scene.tangents.size() < 3 * m_scene.material_ids.size())
            m_scene.tangents.resize(3 * m_scene.material_ids.size(), glm::vec4(0.0f));
        if (with_tangents || !m_scene.tangents.empty())
            for (int j = 0; j < 3; ++j) m_scene.tangents.push_back(with_tangents ? c[j].tangent : glm::vec4(0.0f));
        m_scene.material_ids.push_back(material);
        m_scene.has_vertex_normals.push_back(with_normals ? 1 : 0);
    }

private:
    Scene& m_scene;
};

}  // namespace gc
