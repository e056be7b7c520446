// The shading-level material code of gc_material_eval.h and gc_shade_vertex on the host:
// glTF alpha (MASK decided by gc_alpha.h's traversal test, BLEND a stochastic pass-through),
// normal maps in tangent space, the metallicRoughness texture folded into the factors, and
// textured emission. One triangle in the z = 0 plane, uv = (x, -y) so that dP/du = +x and
// "up the image" (-dP/dv) = +y.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "gc_alpha.h"
#include "gc_path_vertex.h"

namespace gc::dev {
namespace {

std::uint32_t rgba(int r, int g, int b, int a = 255)
{
    return static_cast<std::uint32_t>(r) | (static_cast<std::uint32_t>(g) << 8) | (static_cast<std::uint32_t>(b) << 16) |
           (static_cast<std::uint32_t>(a) << 24);
}

struct OneTriangle {
    std::vector<GcTriangleAttribs> attribs;
    std::vector<GcMaterial> materials;
    std::vector<GcTexture> textures;
    std::vector<uint> texel_data;
    std::vector<GcEmitter> emitter_data{GcEmitter{}};
    std::vector<GcPointLight> point_light_data{GcPointLight{}};
    std::vector<float4> env_pixel_data{float4(0.0f)};
    std::vector<float> env_cdf{0.0f, 1.0f};

    OneTriangle()
    {
        GcTriangleAttribs a{};
        a.n0 = a.n1 = a.n2 = a.ng = make_float4(0, 0, 1, 0);
        // Corners (-1,-1,0), (1,-1,0), (0,1,0) with uv = (x, -y).
        a.uv01 = make_float4(-1.0f, 1.0f, 1.0f, 1.0f);
        a.uv2_u = 0.0f;
        a.uv2_v = -1.0f;
        a.material = 0;
        a.flags = GC_TRIF_HAS_UV;
        a.tangent = make_float4(1, 0, 0, 1);
        attribs.push_back(a);
        GcMaterial m{};
        m.type = GC_MAT_PBR;
        m.albedo = make_float4(0.8f, 0.8f, 0.8f, 1.0f);
        m.emission = make_float4(0, 0, 0, 1.5f);
        m.pbr = make_float4(0.0f, 0.5f, 0.5f, 0.0f);
        m.albedo_texture = m.metallic_roughness_texture = m.normal_texture = m.emission_texture = GC_INVALID;
        m.coat_texture = m.coat_roughness_texture = m.coat_normal_texture = GC_INVALID;
        m.normal_scale = m.coat_normal_scale = 1.0f;
        materials.push_back(m);
    }

    // A 1x1 texture of one texel; returns its index.
    uint add_texture(std::uint32_t texel, bool srgb)
    {
        textures.push_back({static_cast<uint>(texel_data.size()), 1u, 1u, srgb ? GC_TEXF_SRGB : 0u});
        texel_data.push_back(texel);
        return static_cast<uint>(textures.size() - 1);
    }

    GcVertexResult shade(std::uint32_t pixel, std::uint32_t depth = 0) const
    {
        const GcTriangleAttribs* attribs_ptr = attribs.data();
        const GcMaterial* materials_ptr = materials.data();
        const GcTexture* textures_ptr = textures.empty() ? nullptr : textures.data();
        const uint* texels = texel_data.empty() ? nullptr : texel_data.data();
        const GcEmitter* emitters = emitter_data.data();
        const GcPointLight* point_lights = point_light_data.data();
        const float4* env_pixels = env_pixel_data.data();
        const float* env_marginal = env_cdf.data();
        const float* env_conditional = env_cdf.data();
        GcRenderParams params{};
        params.env_radiance = make_float4(1, 1, 1, 0);
        params.max_depth = 8;
        params.rr_depth = 100;
        params.integrator = GC_INTEGRATOR_PATH;
        GcPathState path{};
        path.throughput = make_float4(1, 1, 1, 0);
        path.pixel = pixel;
        path.depth = depth;
        path.flags = 0u;
        const GcRay ray = gc_make_ray(make_float3(0.1f, 0.2f, 1.0f), make_float3(0, 0, -1), 0.0f, GC_FLOAT_MAX);
        GcHit hit{};
        hit.t = 1.0f;
        hit.u = 0.3f;
        hit.v = 0.3f;
        hit.prim = 0;
        return gc_shade_vertex(attribs_ptr, materials_ptr, textures_ptr, texels, emitters, point_lights, env_pixels,
                               env_marginal, env_conditional, params, path, ray, hit);
    }
};

bool passed_through(const GcVertexResult& r)
{
    return (r.flags & GC_VERTEX_CONTINUE) != 0u && r.next.dir_tmax.z == -1.0f && r.next.dir_tmax.x == 0.0f &&
           r.next.org_tmin.z < 0.0f && r.path.throughput.x == 1.0f && (r.path.flags & GC_PATH_SPECULAR) != 0u;
}

TEST(MaterialEval, AlphaMaskIsDecidedInTraversal)
{
    OneTriangle s;
    s.materials[0].flags = GC_MATF_ALPHA_MASK;
    const uint prim = 0;
    auto solid = [&](float u, float v) {
        return gc_alpha_solid(s.attribs.data(), s.materials.data(), s.textures.empty() ? nullptr : s.textures.data(),
                              s.texel_data.empty() ? nullptr : s.texel_data.data(), prim, u, v);
    };
    // The traversal's test (gc_alpha.h): alpha = factor * texture alpha against the cutoff 0.5.
    s.materials[0].albedo.w = 0.3f;
    EXPECT_FALSE(solid(0.3f, 0.3f));
    s.materials[0].albedo.w = 0.5f;
    EXPECT_TRUE(solid(0.3f, 0.3f)) << "alpha == cutoff is solid (glTF: transparent only below)";
    s.materials[0].albedo.w = 1.0f;
    s.materials[0].albedo_texture = s.add_texture(rgba(255, 255, 255, 153), true);
    EXPECT_TRUE(solid(0.3f, 0.3f));
    s.texel_data[0] = rgba(255, 255, 255, 102);
    EXPECT_FALSE(solid(0.3f, 0.3f));
    // A MASK hit that reaches shading passed that test: it is shaded as a surface, whatever
    // its alpha, and costs no pass-through segment.
    for (std::uint32_t px = 0; px < 64; ++px) ASSERT_FALSE(passed_through(s.shade(px))) << px;
}

TEST(MaterialEval, AlphaBlendIsStochastic)
{
    OneTriangle s;
    s.materials[0].flags = GC_MATF_ALPHA_BLEND;
    s.materials[0].albedo.w = 0.25f;
    const int n = 20000;
    int through = 0;
    for (int px = 0; px < n; ++px) through += passed_through(s.shade(static_cast<std::uint32_t>(px))) ? 1 : 0;
    const double frac = static_cast<double>(through) / n;
    const double sigma = std::sqrt(0.75 * 0.25 / n);
    std::printf("[alpha] BLEND alpha 0.25: pass-through fraction %.4f (expected 0.75 +- %.4f)\n", frac, sigma);
    EXPECT_NEAR(frac, 0.75, 5.0 * sigma);
    // Opaque materials never pass.
    s.materials[0].flags = 0u;
    for (std::uint32_t px = 0; px < 200; ++px) ASSERT_FALSE(passed_through(s.shade(px)));
}

TEST(MaterialEval, NormalMapTangentSpace)
{
    OneTriangle s;
    const GcMaterial& m = s.materials[0];
    const GcTriangleAttribs& a = s.attribs[0];
    const float3 n = make_float3(0, 0, 1);
    // No texture: unchanged. Flat texel (128, 128, 255): ~unchanged.
    EXPECT_EQ(gc_shade_normal(s.attribs.data(), s.materials.data(), nullptr, nullptr, nullptr, nullptr, nullptr,
                              nullptr, nullptr, m, a, make_float2(0.3f, 0.3f), n, make_float2(0.3f, 0.3f)),
              n);
    s.materials[0].normal_texture = s.add_texture(rgba(128, 128, 255), false);
    auto mapped = [&](std::uint32_t texel) {
        s.texel_data[0] = texel;
        return gc_shade_normal(s.attribs.data(), s.materials.data(), s.textures.data(), s.texel_data.data(), nullptr,
                               nullptr, nullptr, nullptr, nullptr, s.materials[0], a, make_float2(0.3f, 0.3f), n,
                               make_float2(0.3f, 0.3f));
    };
    const float3 flat = mapped(rgba(128, 128, 255));
    EXPECT_NEAR(flat.z, 1.0f, 1e-4f);
    // +X in the map tilts toward dP/du (+x); +Y toward "up the image" (+y here).
    const float3 tx = mapped(rgba(218, 128, 218));
    const float3 ty = mapped(rgba(128, 218, 218));
    std::printf("[normal map] +X texel -> (%.3f %.3f %.3f), +Y texel -> (%.3f %.3f %.3f)\n", tx.x, tx.y, tx.z, ty.x,
                ty.y, ty.z);
    EXPECT_GT(tx.x, 0.4f);
    EXPECT_NEAR(tx.y, 0.0f, 1e-2f);
    EXPECT_GT(ty.y, 0.4f);
    EXPECT_NEAR(ty.x, 0.0f, 1e-2f);
    // Mirrored uv (w = -1) flips the bitangent.
    s.attribs[0].tangent.w = -1.0f;
    EXPECT_LT(mapped(rgba(128, 218, 218)).y, -0.4f);
    // A texel pointing below the surface keeps the interpolated normal.
    s.attribs[0].tangent.w = 1.0f;
    EXPECT_EQ(mapped(rgba(255, 128, 0)), n);
    for (const float3& v : {flat, tx, ty}) EXPECT_NEAR(glm::length(v), 1.0f, 1e-5f);
}

// clearcoatNormalTexture: the coat's normal is the map applied to the interpolated normal, in
// the shading frame (the base's mapped normal as z), and only a coated material gets one.
TEST(MaterialEval, CoatNormalIsTheCoatMapInTheShadingFrame)
{
    OneTriangle s;
    const GcTriangleAttribs& a = s.attribs[0];
    const float3 n = make_float3(0, 0, 1);
    const float2 bary = make_float2(0.3f, 0.3f);
    const float2 uv = make_float2(0.3f, 0.3f);
    auto with_coat_normal = [&](const GcMaterial& m) {
        const float3 ns = gc_shade_normal(s.attribs.data(), s.materials.data(), s.textures.data(), s.texel_data.data(),
                                          nullptr, nullptr, nullptr, nullptr, nullptr, m, a, bary, n, uv);
        const GcFrame frame = gc_frame_from_normal(ns);
        const GcMaterial out = gc_with_coat_normal(s.attribs.data(), s.materials.data(), s.textures.data(),
                                                   s.texel_data.data(), nullptr, nullptr, nullptr, nullptr, nullptr, m,
                                                   a, bary, n, uv, frame);
        return std::make_pair(out, frame);
    };
    GcMaterial m = s.materials[0];
    m.coat_normal_texture = s.add_texture(rgba(218, 128, 218), false);  // tilted towards +x (dP/du)
    EXPECT_EQ(with_coat_normal(m).first.flags & GC_MATF_COAT_NORMAL, 0u) << "no coat, no coat normal";
    m.flags = GC_MATF_CLEARCOAT;
    m.coat = make_float4(1.0f, 0.1f, 0.0f, 1.0f);
    const auto [coated, frame] = with_coat_normal(m);
    ASSERT_NE(coated.flags & GC_MATF_COAT_NORMAL, 0u);
    const float3 world = gc_frame_to_world(frame, GC_XYZ(coated.coat_normal));
    const float3 want = gc_shade_normal(s.attribs.data(), s.materials.data(), s.textures.data(), s.texel_data.data(),
                                        nullptr, nullptr, nullptr, nullptr, nullptr,
                                        [&] { GcMaterial b = m; b.normal_texture = m.coat_normal_texture; return b; }(),
                                        a, bary, n, uv);
    std::printf("[coat normal] untilted base: local (%.3f %.3f %.3f), world (%.3f %.3f %.3f), the map alone (%.3f %.3f "
                "%.3f)\n", coated.coat_normal.x, coated.coat_normal.y, coated.coat_normal.z, world.x, world.y, world.z,
                want.x, want.y, want.z);
    EXPECT_GT(world.x, 0.4f);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(world[c], want[c], 1e-5f);
    // Under a base normal map tilted the other way, the coat keeps its own direction in the
    // world; in the shading frame it then leans further from z.
    m.normal_texture = s.add_texture(rgba(60, 128, 230), false);
    const auto [both, base_frame] = with_coat_normal(m);
    const float3 world_both = gc_frame_to_world(base_frame, GC_XYZ(both.coat_normal));
    std::printf("[coat normal] under a base tilted to -x: local z %.3f (untilted base %.3f)\n", both.coat_normal.z,
                coated.coat_normal.z);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(world_both[c], want[c], 1e-5f);
    EXPECT_LT(both.coat_normal.z, coated.coat_normal.z);
}

TEST(MaterialEval, MetallicRoughnessAndEmissionTextures)
{
    OneTriangle s;
    s.materials[0].pbr = make_float4(0.5f, 0.8f, 0.5f, 0.0f);
    s.materials[0].metallic_roughness_texture = s.add_texture(rgba(0, 128, 255), false); // G rough, B metal
    const GcMaterial m = gc_shade_material(nullptr, s.materials.data(), s.textures.data(), s.texel_data.data(),
                                           nullptr, nullptr, nullptr, nullptr, nullptr, s.materials[0],
                                           make_float2(0.5f, 0.5f));
    EXPECT_NEAR(m.pbr.x, 0.5f, 1e-6f);
    EXPECT_NEAR(m.pbr.y, 0.8f * 128.0f / 255.0f, 1e-6f);
    // Emission: factor times the sRGB texel (sRGB 188 ~ linear 0.5).
    s.materials[0].emission = make_float4(2.0f, 4.0f, 1.0f, 1.5f);
    s.materials[0].emission_texture = s.add_texture(rgba(188, 255, 0), true);
    const float3 e = gc_shade_emission(nullptr, s.materials.data(), s.textures.data(), s.texel_data.data(), nullptr,
                                       nullptr, nullptr, nullptr, nullptr, s.materials[0], make_float2(0.5f, 0.5f));
    EXPECT_NEAR(e.x, 2.0f * gc_srgb_to_linear_table[188], 1e-6f);
    EXPECT_NEAR(e.y, 4.0f, 1e-6f);
    EXPECT_EQ(e.z, 0.0f);
    // gc_triangle_uv interpolates the corners' uvs.
    const float2 uv = gc_triangle_uv(s.attribs[0], make_float3(0.2f, 0.3f, 0.5f));
    EXPECT_NEAR(uv.x, 0.2f * -1.0f + 0.3f * 1.0f, 1e-6f);
    EXPECT_NEAR(uv.y, 0.2f * 1.0f + 0.3f * 1.0f + 0.5f * -1.0f, 1e-6f);
}

TEST(MaterialEval, LayerTexturesFoldIntoTheirFactorsOnlyWithTheirFlag)
{
    // KHR_materials_clearcoat: clearcoatTexture R scales the factor, clearcoatRoughnessTexture
    // G the roughness; KHR_materials_specular: specularTexture A the factor, the sRGB
    // specularColorTexture the colour. A layer without its flag is left as it is.
    OneTriangle s;
    GcMaterial& m0 = s.materials[0];
    m0.type = GC_MAT_PBR;
    m0.coat = make_float4(0.8f, 0.5f, 0.0f, 0.6f);
    m0.specular = make_float4(1.0f, 0.5f, 0.25f, 1.0f);
    m0.coat_texture = s.add_texture(rgba(51, 0, 0), false);
    m0.coat_roughness_texture = s.add_texture(rgba(0, 102, 0), false);
    m0.specular_texture = s.add_texture(rgba(0, 0, 0, 153), false);
    m0.specular_color_texture = s.add_texture(rgba(188, 255, 0), true);
    m0.sheen_color_texture = m0.sheen_roughness_texture = GC_INVALID;
    auto shade = [&](const GcMaterial& m) {
        return gc_shade_material(nullptr, s.materials.data(), s.textures.data(), s.texel_data.data(), nullptr, nullptr,
                                 nullptr, nullptr, nullptr, m, make_float2(0.5f, 0.5f));
    };
    const GcMaterial off = shade(m0);
    EXPECT_EQ(off.coat.x, 0.8f);
    EXPECT_EQ(off.coat.w, 0.6f);
    EXPECT_EQ(off.specular.x, 1.0f);
    m0.flags = GC_MATF_CLEARCOAT | GC_MATF_SPECULAR;
    const GcMaterial on = shade(m0);
    EXPECT_NEAR(on.coat.x, 0.8f * 51.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(on.coat.y, 0.5f * 102.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(on.coat.w, 0.6f * 153.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(on.specular.x, gc_srgb_to_linear_table[188], 1e-6f);
    EXPECT_NEAR(on.specular.y, 0.5f, 1e-6f);
    EXPECT_EQ(on.specular.z, 0.0f);
}

TEST(MaterialEval, TransmissionTextureScalesTheTransmissionFactor)
{
    // KHR_materials_transmission: transmissionTexture R (linear) times transmissionFactor. A
    // material without transmission leaves the slot unread.
    OneTriangle s;
    GcMaterial& m0 = s.materials[0];
    m0.pbr.w = 0.8f;
    m0.transmission_texture = s.add_texture(rgba(128, 7, 9), false);
    auto shade = [&](const GcMaterial& m) {
        return gc_shade_material(nullptr, s.materials.data(), s.textures.data(), s.texel_data.data(), nullptr, nullptr,
                                 nullptr, nullptr, nullptr, m, make_float2(0.5f, 0.5f));
    };
    EXPECT_NEAR(shade(m0).pbr.w, 0.8f * 128.0f / 255.0f, 1e-6f);
    m0.transmission_texture = s.add_texture(rgba(255, 0, 0), false);
    EXPECT_EQ(shade(m0).pbr.w, 0.8f) << "a texel of 1 keeps the factor's bits";
    m0.pbr.w = 0.0f;
    m0.transmission_texture = 12345u;  // would read past the views if it were read
    EXPECT_EQ(shade(m0).pbr.w, 0.0f);
}

}  // namespace
}  // namespace gc::dev
