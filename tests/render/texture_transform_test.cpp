// glTF KHR_texture_transform from the scene to the lookup: texture views (scene_convert's
// texture_views: one per distinct texture and transform, sharing texels), the affine rows in
// glTF's convention, and gc_texture_sample applying them, on the host (the kernels compile the
// same header).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "gc_texture.h"
#include "host/render/scene_convert.h"

namespace gc {
namespace {

Texture checker(int w, int h)
{
    Texture t;
    t.width = w;
    t.height = h;
    t.srgb = false;
    t.nearest = true;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) t.texels.push_back(static_cast<std::uint32_t>(x) | static_cast<std::uint32_t>(y) << 8 | 0xff000000u);
    return t;
}

Scene two_textures()
{
    Scene s;
    s.textures = {checker(4, 2), checker(8, 8)};
    Material a;
    a.albedo_texture = 0;
    a.albedo_uv.offset = {0.5f, 0.0f};
    a.normal_texture = 1;
    a.emission_texture = 1;  // identity: the base view
    Material b = a;
    b.metallic_roughness_texture = 0;
    b.metallic_roughness_uv.offset = {0.5f, 0.0f};  // the same pair as a's albedo: one view
    b.normal_uv.rotation = 0.25f;
    s.materials = {a, b, Material{}};
    return s;
}

TEST(TextureViews, UntransformedScenesKeepOneViewPerTexture)
{
    Scene s = two_textures();
    for (Material& m : s.materials) m.albedo_uv = m.metallic_roughness_uv = m.normal_uv = UvTransform{};
    const TextureViews v = texture_views(s);
    ASSERT_EQ(v.views.size(), 2u);
    for (const dev::GcTexture& t : v.views) {
        EXPECT_EQ(t.flags & GC_TEXF_TRANSFORM, 0u);
        EXPECT_EQ(t.uv_u, glm::vec4(0.0f));
    }
    EXPECT_EQ(v.views[1].offset, 8u);
    EXPECT_EQ(make_materials(s)[0].albedo_texture, 0u);
    EXPECT_EQ(make_materials(s)[2].albedo_texture, GC_INVALID);
}

TEST(TextureViews, ShareTexelsAndDedupeIdenticalTransforms)
{
    const Scene s = two_textures();
    const DeviceTextures d = make_textures(s);
    const std::vector<dev::GcMaterial> m = make_materials(s);
    // Base views 0, 1; (texture 0, offset) = 2; (texture 1, rotation) = 3.
    ASSERT_EQ(d.textures.size(), 4u);
    EXPECT_EQ(d.texels.size(), 8u + 64u) << "views share texels";
    EXPECT_EQ(m[0].albedo_texture, 2u);
    EXPECT_EQ(m[1].albedo_texture, 2u);
    EXPECT_EQ(m[1].metallic_roughness_texture, 2u) << "same texture, same transform: one view";
    EXPECT_EQ(m[0].normal_texture, 1u);
    EXPECT_EQ(m[1].normal_texture, 3u);
    EXPECT_EQ(m[0].emission_texture, 1u);
    const dev::GcTexture& off = d.textures[2];
    EXPECT_EQ(off.offset, d.textures[0].offset);
    EXPECT_EQ(off.width, 4u);
    EXPECT_EQ(off.flags, d.textures[0].flags | GC_TEXF_TRANSFORM);
    EXPECT_EQ(off.uv_u, glm::vec4(1.0f, 0.0f, 0.5f, 0.0f));
    EXPECT_EQ(off.uv_v, glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
    EXPECT_EQ(d.textures[3].offset, 8u);
    EXPECT_EQ(summarize(s).textures, 4u);
}

TEST(TextureViews, RowsFollowTheSpecsExample)
{
    // KHR_texture_transform's example: offset (0, 1), rotation pi/2, scale 0.5 reads the lower
    // left quadrant of the image, turned 90 degrees clockwise: uv (0,0) -> (0,1),
    // (1,0) -> (0,0.5), (0,1) -> (0.5,1).
    UvTransform t;
    t.offset = {0.0f, 1.0f};
    t.rotation = 1.57079632679f;
    t.scale = {0.5f, 0.5f};
    const auto r = uv_transform_rows(t);
    auto apply = [&](float u, float v) { return glm::vec2(r[0].x * u + r[0].y * v + r[0].z, r[1].x * u + r[1].y * v + r[1].z); };
    const glm::vec2 a = apply(0, 0), b = apply(1, 0), c = apply(0, 1);
    EXPECT_NEAR(a.x, 0.0f, 1e-6f); EXPECT_NEAR(a.y, 1.0f, 1e-6f);
    EXPECT_NEAR(b.x, 0.0f, 1e-6f); EXPECT_NEAR(b.y, 0.5f, 1e-6f);
    EXPECT_NEAR(c.x, 0.5f, 1e-6f); EXPECT_NEAR(c.y, 1.0f, 1e-6f);
    // Non-uniform scale applies before the rotation (T R S).
    UvTransform ns;
    ns.rotation = 1.57079632679f;
    ns.scale = {2.0f, 1.0f};
    const auto q = uv_transform_rows(ns);
    EXPECT_NEAR(q[1].x, -2.0f, 1e-6f);  // v' = -sin * sx * u
    EXPECT_NEAR(q[0].y, 1.0f, 1e-6f);   // u' = sin * sy * v
}

TEST(TextureViews, LookupAppliesTheTransform)
{
    const Scene s = two_textures();
    const DeviceTextures d = make_textures(s);
    // Texture 0 (4 x 2, nearest, repeat) offset by half its width: the untransformed texture
    // shifted by two texels, bit for bit, at every texel centre and between them.
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x) {
            const float u = (static_cast<float>(x) + 0.25f) / 8.0f, v = (static_cast<float>(y) + 0.25f) / 4.0f;
            const dev::float4 shifted = dev::gc_texture_sample(d.texels.data(), d.textures[2], u, v);
            const dev::float4 plain = dev::gc_texture_sample(d.texels.data(), d.textures[0], u + 0.5f, v);
            EXPECT_EQ(shifted.x, plain.x) << x << "," << y;
            EXPECT_EQ(shifted.y, plain.y) << x << "," << y;
        }
    // Bilinear views of the same texture without the flag ignore the rows entirely.
    dev::GcTexture bogus = d.textures[0];
    bogus.uv_u = glm::vec4(std::numeric_limits<float>::quiet_NaN());
    const dev::float4 a = dev::gc_texture_sample(d.texels.data(), bogus, 0.3f, 0.6f);
    const dev::float4 b = dev::gc_texture_sample(d.texels.data(), d.textures[0], 0.3f, 0.6f);
    EXPECT_EQ(a.x, b.x);
}

TEST(TextureViews, HugeOrNonFiniteTransformsReadATexel)
{
    Scene s = two_textures();
    s.materials[0].albedo_uv.scale = {3e38f, 3e38f};
    s.materials[1].albedo_uv.offset = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()};
    const DeviceTextures d = make_textures(s);
    for (const dev::GcTexture& t : d.textures)
        for (float u : {0.0f, 0.7f, 1e6f, -5.0f})
            for (bool nearest : {false, true}) {
                dev::GcTexture view = t;
                view.flags = nearest ? (view.flags | GC_TEXF_NEAREST) : (view.flags & ~GC_TEXF_NEAREST);
                const dev::float4 c = dev::gc_texture_sample(d.texels.data(), view, u, 0.5f);
                EXPECT_TRUE(std::isfinite(c.x) && c.x >= 0.0f && c.x <= 1.0f);
            }
}

TEST(TextureViews, NormalMapFrameFollowsTheTransform)
{
    auto view_of = [](const UvTransform& t) {
        dev::GcTexture v{};
        if (!t.is_identity()) {
            const auto rows = uv_transform_rows(t);
            v.flags = GC_TEXF_TRANSFORM;
            v.uv_u = glm::vec4(rows[0], 0.0f);
            v.uv_v = glm::vec4(rows[1], 0.0f);
        }
        return v;
    };
    auto xy = [&](const UvTransform& t, float x, float y) {
        const dev::float2 r = dev::gc_texture_tangent_xy(view_of(t), x, y);
        return glm::vec2(r.x, r.y);
    };
    EXPECT_EQ(xy(UvTransform{}, 0.3f, -0.2f), glm::vec2(0.3f, -0.2f)) << "untransformed: the same bits";
    // A quarter turn: the texture's u grows along the mesh's v, i.e. against B (B points up
    // the image, against v): the map's x is the frame's -y.
    UvTransform quarter;
    quarter.rotation = 1.57079632679f;
    const glm::vec2 q = xy(quarter, 1.0f, 0.0f);
    EXPECT_NEAR(q.x, 0.0f, 1e-6f);
    EXPECT_NEAR(q.y, -1.0f, 1e-6f);
    // An offset or a uniform scale leaves the frame alone; a mirror in v flips y.
    UvTransform moved;
    moved.offset = {0.3f, 0.9f};
    moved.scale = {4.0f, 4.0f};
    const glm::vec2 m = xy(moved, 0.6f, -0.8f);
    EXPECT_NEAR(m.x, 0.6f, 1e-6f);
    EXPECT_NEAR(m.y, -0.8f, 1e-6f);
    UvTransform flip;
    flip.offset = {0.0f, 1.0f};
    flip.scale = {1.0f, -1.0f};
    EXPECT_EQ(xy(flip, 0.6f, -0.8f), glm::vec2(0.6f, 0.8f));
    // A degenerate scale keeps the map's own frame rather than making NaNs.
    UvTransform flat;
    flat.scale = {0.0f, 1.0f};
    EXPECT_EQ(xy(flat, 0.6f, -0.8f), glm::vec2(0.6f, -0.8f));
}

}  // namespace
}  // namespace gc
