// Authored per-vertex tangents (glTF TANGENT) from the scene to the shading: the octahedral
// packing of kernels/shared/gc_tangent.h, make_triangle_attribs storing it in the normals' .w,
// and gc_shade_normal (gc_material_eval.h) building the normal map's frame from it, all on the
// host (the kernels compile the same headers).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "gc_material_eval.h"
#include "host/render/scene_convert.h"
#include "host/scene/triangle_sink.h"

namespace gc {
namespace {

using dev::float3;
using dev::float4;
using dev::GcTriangleAttribs;

double angle_between(const glm::dvec3& a, const glm::dvec3& b)
{
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

glm::dvec3 dvec(const float4& v) { return {v.x, v.y, v.z}; }

TEST(TangentPacking, OctahedralRoundTrip)
{
    // Directions: a Fibonacci sphere, the axes, the octant diagonals and the fold's seams
    // (z = 0, the lower hemisphere's edges), each at two lengths: the encoder normalises.
    std::vector<glm::dvec3> dirs;
    const int n = 100000;
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / n;
        const double r = std::sqrt(1.0 - z * z);
        dirs.push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
    }
    for (int s = 0; s < 27; ++s) {
        const glm::dvec3 d(s % 3 - 1, s / 3 % 3 - 1, s / 9 - 1);
        if (glm::length(d) > 0.0) dirs.push_back(glm::normalize(d));
    }
    for (int i = 0; i < 360; ++i)
        dirs.push_back({std::cos(i * M_PI / 180.0), std::sin(i * M_PI / 180.0), i % 2 ? 1e-7 : -1e-7});

    // Rounding moves the octahedral point by at most h = 0.5 / 16383 in x and y, so by at most
    // sqrt(6) h in 3-D (z = 1 - |x| - |y| moves by |dx| + |dy|); the point is at least 1/sqrt(3)
    // from the origin, so its direction turns by at most sqrt(3) sqrt(6) h = 1.29e-4 rad.
    const double bound = std::sqrt(18.0) * 0.5 / 16383.0 + 1e-6;
    double max_err = 0.0;
    double max_len_err = 0.0;
    for (const glm::dvec3& d : dirs)
        for (float w : {1.0f, -1.0f})
            for (float scale : {1.0f, 7.5f}) {
                const float3 t(static_cast<float>(d.x * scale), static_cast<float>(d.y * scale),
                               static_cast<float>(d.z * scale));
                const dev::uint bits = dev::gc_tangent_encode(t, w);
                ASSERT_EQ(bits & 0x40000000u, 0u) << "bit 30 must stay clear (no NaN/Inf pattern)";
                const float carrier = dev::gc_as_float(bits);
                ASSERT_TRUE(std::isfinite(carrier));
                ASSERT_EQ(dev::gc_as_uint(carrier), bits);
                const float4 back = dev::gc_tangent_decode(bits);
                ASSERT_EQ(back.w, w) << "bitangent sign lost";
                max_err = std::fmax(max_err, angle_between(d, dvec(back)));
                max_len_err = std::fmax(max_len_err, std::fabs(glm::length(dvec(back)) - 1.0));
            }
    std::printf("[tangent packing] %zu directions x 2 signs x 2 lengths: max angular error %.3e rad (%.5f deg), "
                "bound %.3e; max |length - 1| %.2e\n",
                dirs.size(), max_err, max_err * 180.0 / M_PI, bound, max_len_err);
    EXPECT_LE(max_err, bound);
    EXPECT_LE(max_len_err, 1e-6);
}

// One triangle in the z = 0 plane, corners (-1,-1,0), (1,-1,0), (0,1,0), normals +z, uv = (x, -y),
// so the generated tangent is dP/du = +x with B = +y "up the image"; each corner gets `tangent`.
Scene plane_triangle(const std::vector<glm::vec4>& tangents)
{
    Scene s;
    s.materials.emplace_back();
    TriangleSink sink(s, 1);
    SinkCorner c[3];
    const Point3 p[3] = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    for (int j = 0; j < 3; ++j) {
        c[j].position = p[j];
        c[j].normal = Normal3(0, 0, 1);
        c[j].uv = glm::vec2(p[j].x, -p[j].y);
        if (!tangents.empty()) c[j].tangent = tangents[static_cast<std::size_t>(j)];
    }
    sink.add(c, true, true, 0, !tangents.empty());
    return s;
}

TEST(AuthoredTangents, SceneConvertPacksThemIntoTheNormalsW)
{
    // The sink back-fills: a triangle without tangents before one with them gets zeros.
    Scene s = plane_triangle({});
    {
        TriangleSink sink(s, 2);
        SinkCorner c[3];
        const Point3 p[3] = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
        for (int j = 0; j < 3; ++j) c[j].position = p[j];
        c[0].tangent = glm::vec4(0, 1, 0, -1);
        c[1].tangent = glm::vec4(0.6f, 0.8f, 0, -1);
        c[2].tangent = glm::vec4(-1, 0, 0, -1);
        sink.add(c, false, false, 0, true);
        c[2].tangent = glm::vec4(0.0f); // one corner without: the triangle keeps generated ones
        sink.add(c, false, false, 0, true);
    }
    ASSERT_EQ(s.triangle_count(), 3u);
    ASSERT_EQ(s.tangents.size(), 9u);
    for (int j = 0; j < 3; ++j) EXPECT_EQ(s.tangents[static_cast<std::size_t>(j)], glm::vec4(0.0f));

    const BigArray<GcTriangleAttribs> a = make_triangle_attribs(s);
    ASSERT_EQ(a.size(), 3u);
    EXPECT_EQ(a[0].flags & GC_TRIF_HAS_TANGENTS, 0u);
    EXPECT_EQ(a[0].n0.w, 0.0f);
    EXPECT_EQ(a[2].flags & GC_TRIF_HAS_TANGENTS, 0u);
    EXPECT_EQ(a[2].n0.w, 0.0f);
    ASSERT_NE(a[1].flags & GC_TRIF_HAS_TANGENTS, 0u);
    const float4 corners[3] = {a[1].n0, a[1].n1, a[1].n2};
    for (int j = 0; j < 3; ++j) {
        const glm::vec4 want = s.tangents[3 + static_cast<std::size_t>(j)];
        const float4 got = dev::gc_tangent_decode(dev::gc_as_uint(corners[j].w));
        EXPECT_LT(angle_between(dvec(want), dvec(got)), 1.3e-4) << j;
        EXPECT_EQ(got.w, -1.0f) << j;
        EXPECT_EQ(glm::vec3(corners[j]), glm::vec3(s.normals[3 + static_cast<std::size_t>(j)].glm())) << j;
    }
}

// gc_shade_normal on a 1x1 normal map of `texel` (RGB, linear) at barycentrics (0.3, 0.3).
struct NormalMap {
    BigArray<GcTriangleAttribs> attribs;
    std::vector<dev::GcMaterial> materials;
    std::vector<dev::GcTexture> textures{{0u, 1u, 1u, 0u}};
    std::vector<dev::uint> texels{0u};

    explicit NormalMap(const Scene& s) : attribs(make_triangle_attribs(s)), materials(make_materials(s))
    {
        materials[0].normal_texture = 0;
        materials[0].normal_scale = 1.0f;
    }

    glm::dvec3 shade(int r, int g, int b)
    {
        texels[0] = static_cast<dev::uint>(r) | static_cast<dev::uint>(g) << 8 | static_cast<dev::uint>(b) << 16 | 0xff000000u;
        const float3 ns(0, 0, 1);
        const float3 n = dev::gc_shade_normal(attribs.data(), materials.data(), textures.data(), texels.data(), nullptr,
                                              nullptr, nullptr, nullptr, nullptr, materials[0], attribs[0],
                                              dev::make_float2(0.3f, 0.3f), ns, dev::make_float2(0.0f, 0.0f));
        return {n.x, n.y, n.z};
    }
};

// What the normal map should give in the frame (T, B = w cross(N, T), N = +z), T unit in the
// plane: the texel decoded as 2 c / 255 - 1, mapped, normalised.
glm::dvec3 expected(glm::dvec3 t, double w, int r, int g, int b)
{
    const glm::dvec3 nz(0, 0, 1);
    t = glm::normalize(t);
    const glm::dvec3 bt = w * glm::cross(nz, t);
    auto c = [](int v) { return 2.0 * v / 255.0 - 1.0; };
    return glm::normalize(t * c(r) + bt * c(g) + nz * c(b));
}

TEST(AuthoredTangents, NormalMapFollowsTheAuthoredFrame)
{
    // Generated frame: T = +x. The same triangle with authored tangents turned 90 degrees
    // about the normal (T = +y): the map's +X now tilts toward +y, its +Y toward -x.
    NormalMap gen(plane_triangle({}));
    const glm::vec4 gt = glm::vec4(gen.attribs[0].tangent);
    ASSERT_EQ(gen.attribs[0].flags & GC_TRIF_HAS_TANGENTS, 0u);
    ASSERT_NEAR(gt.x, 1.0f, 1e-6f);
    ASSERT_EQ(gt.w, 1.0f);
    const glm::vec4 up(0, 1, 0, 1);
    NormalMap rot(plane_triangle({up, up, up}));
    ASSERT_NE(rot.attribs[0].flags & GC_TRIF_HAS_TANGENTS, 0u);

    struct Case {
        const char* what;
        NormalMap* map;
        glm::dvec3 t;
        double w;
        int r, g, b;
    };
    const Case cases[] = {{"generated, +X texel", &gen, {1, 0, 0}, 1, 218, 128, 218},
                          {"generated, +Y texel", &gen, {1, 0, 0}, 1, 128, 218, 218},
                          {"authored +y, +X texel", &rot, {0, 1, 0}, 1, 218, 128, 218},
                          {"authored +y, +Y texel", &rot, {0, 1, 0}, 1, 128, 218, 218}};
    glm::dvec3 got[4];
    for (int i = 0; i < 4; ++i) {
        const Case& c = cases[i];
        got[i] = c.map->shade(c.r, c.g, c.b);
        const glm::dvec3 want = expected(c.t, c.w, c.r, c.g, c.b);
        const double err = angle_between(got[i], want);
        std::printf("[authored tangents] %-22s -> (%.4f %.4f %.4f), expected (%.4f %.4f %.4f), %.1e rad\n", c.what,
                    got[i].x, got[i].y, got[i].z, want.x, want.y, want.z, err);
        EXPECT_LT(err, 2e-4) << c.what;
    }
    // The turn itself: the +X texel's tilt is 90 degrees around +z from the generated one.
    const double turn = std::atan2(got[2].y, got[2].x) - std::atan2(got[0].y, got[0].x);
    std::printf("[authored tangents] +X texel tilt turned by %.3f deg\n", turn * 180.0 / M_PI);
    EXPECT_NEAR(turn * 180.0 / M_PI, 90.0, 0.05);

    // The authored bitangent sign: w = -1 flips the map's +Y (now toward +x).
    const glm::vec4 up_mirrored(0, 1, 0, -1);
    NormalMap mir(plane_triangle({up_mirrored, up_mirrored, up_mirrored}));
    const glm::dvec3 m = mir.shade(128, 218, 218);
    EXPECT_LT(angle_between(m, expected({0, 1, 0}, -1, 128, 218, 218)), 2e-4);
    EXPECT_GT(m.x, 0.4);

    // Per-vertex tangents are interpolated: +x at v0, +y at v1 and v2, seen at (u, v) =
    // (0.3, 0.3) give T along 0.4 x + 0.6 y.
    NormalMap mixed(plane_triangle({{1, 0, 0, 1}, up, up}));
    const glm::dvec3 x = mixed.shade(218, 128, 218);
    const glm::dvec3 want = expected({0.4, 0.6, 0}, 1, 218, 128, 218);
    std::printf("[authored tangents] interpolated frame, +X texel -> (%.4f %.4f %.4f), expected (%.4f %.4f %.4f)\n",
                x.x, x.y, x.z, want.x, want.y, want.z);
    EXPECT_LT(angle_between(x, want), 2e-4);

    // Clearing the flag falls back to the generated tangent even with bits in n0..n2.w.
    rot.attribs[0].flags &= ~GC_TRIF_HAS_TANGENTS;
    EXPECT_LT(angle_between(rot.shade(218, 128, 218), expected({1, 0, 0}, 1, 218, 128, 218)), 2e-4);
}

}  // namespace
}  // namespace gc
