// Small synthetic scenes for the glTF alphaMode MASK tests: the OpenCL traversal and path
// tracer (tests/render/alpha_mask_test.cpp) and the Vulkan raster pass
// (tests/vk/cross_check_test.cpp) look at the same cut-out quad.
#pragma once

#include <cstdint>

#include "host/scene/scene.h"

namespace gc::test {

inline constexpr std::uint32_t k_opaque = 0xffffffffu;      // white, alpha 255
inline constexpr std::uint32_t k_transparent = 0x00ffffffu; // white, alpha 0

// Appends the axis-aligned quad (corners a, b, c, d counter-clockwise seen from its front)
// as two triangles with uv = corner order (0,0) (1,0) (1,1) (0,1).
inline void add_quad(Scene& s, Point3 a, Point3 b, Point3 c, Point3 d, std::uint32_t material)
{
    const Normal3 n(normalize(cross(b - a, d - a)));
    const Point3 p[2][3] = {{a, b, c}, {a, c, d}};
    const glm::vec2 t[2][3] = {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0}, {1, 1}, {0, 1}}};
    for (int tri = 0; tri < 2; ++tri) {
        for (int j = 0; j < 3; ++j) {
            s.positions.push_back(p[tri][j]);
            s.normals.push_back(n);
            s.uvs.push_back(t[tri][j]);
        }
        s.material_ids.push_back(material);
        s.has_vertex_normals.push_back(0);
    }
}

// Triangles 0-1: the MASK quad in z = 0 over [-1, 1]^2, u = (x + 1) / 2, with a 2x2 nearest
// texture whose left column (u < 0.5, so x < 0) is alpha 0. Triangles 2-3: an opaque
// backstop at z = -1.
inline Scene half_cut_quad()
{
    Scene s;
    Material mask;
    mask.type = MaterialType::Pbr;
    mask.alpha_mode = AlphaMode::Mask;
    mask.alpha_cutoff = 0.5f;
    mask.albedo_texture = 0;
    s.materials = {mask, Material{}};
    Texture tex;
    tex.name = "half alpha";
    tex.width = tex.height = 2;
    tex.texels = {k_transparent, k_opaque, k_transparent, k_opaque};
    tex.nearest = true;
    tex.wrap_s = tex.wrap_t = WrapMode::ClampToEdge;
    s.textures = {tex};
    add_quad(s, Point3(-1, -1, 0), Point3(1, -1, 0), Point3(1, 1, 0), Point3(-1, 1, 0), 0);
    add_quad(s, Point3(-2, -2, -1), Point3(2, -2, -1), Point3(2, 2, -1), Point3(-2, 2, -1), 1);
    return s;
}

}  // namespace gc::test
