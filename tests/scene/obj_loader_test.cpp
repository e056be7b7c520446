// OBJ/MTL loading: the bundled scenes, material mapping, and generated and small synthetic files.
#include <chrono>
#include <cmath>

#include <gtest/gtest.h>

#include "host/scene/energy_conservation.h"
#include "host/scene/load.h"
#include "host/scene/scene_checks.h"
#include "scene_test_util.h"

namespace gc {
namespace {

using test::expect_input_error;
using test::ScratchDir;

const Material& material_named(const Scene& s, const std::string& name)
{
    for (const Material& m : s.materials)
        if (m.name == name) return m;
    ADD_FAILURE() << "no material named " << name;
    static const Material none;
    return none;
}

std::size_t triangles_with(const Scene& s, const std::string& name)
{
    std::size_t n = 0;
    for (std::uint32_t id : s.material_ids) n += s.materials[id].name == name;
    return n;
}

// Each triangle's winding normal agrees with the stored normals of its corners (front faces).
void expect_invariants(const Scene& s)
{
    const std::size_t n = s.triangle_count();
    ASSERT_EQ(s.positions.size(), 3 * n);
    ASSERT_EQ(s.normals.size(), 3 * n);
    ASSERT_EQ(s.has_vertex_normals.size(), n);
    ASSERT_TRUE(s.uvs.empty() || s.uvs.size() == 3 * n);
    ASSERT_FALSE(s.materials.empty());
    for (std::size_t i = 0; i < 3 * n; ++i) {
        ASSERT_TRUE(is_finite(s.positions[i])) << i;
        ASSERT_NEAR(length(s.normals[i]), 1.0f, 1e-4f) << i;
    }
    for (std::uint32_t id : s.material_ids) ASSERT_LT(id, s.materials.size());
}

Scene load_cornell(const std::string& name)
{
    return load_scene(test::repo_scene("cornell-box/" + name));
}

TEST(ObjCornell, OriginalCountsAndLight)
{
    const Scene s = load_cornell("CornellBox-Original.obj");
    expect_invariants(s);
    std::printf("  CornellBox-Original: %zu triangles, %zu materials\n", s.triangle_count(), s.materials.size());
    EXPECT_EQ(s.triangle_count(), 36u);
    const Material& light = material_named(s, "light");
    EXPECT_EQ(light.emission, glm::vec3(17, 12, 4));
    EXPECT_EQ(light.type, MaterialType::Lambert);
    EXPECT_EQ(s.emissive_triangles().size(), 2u);
    EXPECT_EQ(triangles_with(s, "light"), 2u);
    EXPECT_EQ(triangles_with(s, "tallBox"), 12u);  // 6 quads, bottom included
    for (const Material& m : s.materials) EXPECT_EQ(m.type, MaterialType::Lambert) << m.name;
    EXPECT_NEAR(material_named(s, "leftWall").albedo.x, 0.63f, 1e-6f);
    EXPECT_FALSE(s.camera.has_value());
    EXPECT_TRUE(s.uvs.empty());
    // Quads are fanned: (v0, v1, v2), (v0, v2, v3), so each pair shares its first corner.
    EXPECT_EQ(s.vertex(0, 0), s.vertex(1, 0));
    EXPECT_EQ(s.vertex(0, 2), s.vertex(1, 1));
    // Floor "v -1.01 0 0.99" is the first vertex; its face normal points up (+Y) into the box.
    EXPECT_EQ(s.vertex(0, 0), Point3(-1.01f, 0.0f, 0.99f));
    EXPECT_GT(s.normals[0].y, 0.99f);
    EXPECT_EQ(s.has_vertex_normals[0], 0);
}

TEST(ObjCornell, MirrorMapsIllum5ToMirror)
{
    const Scene s = load_cornell("CornellBox-Mirror.obj");
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 36u);
    const Material& tall = material_named(s, "tallBox");
    EXPECT_EQ(tall.type, MaterialType::Mirror);
    std::printf("  tallBox: Mirror, specular %.3f %.3f %.3f\n", tall.specular.x, tall.specular.y, tall.specular.z);
    EXPECT_GT(tall.specular.x, 0.0f);
    EXPECT_EQ(material_named(s, "shortBox").type, MaterialType::Lambert);
    EXPECT_EQ(material_named(s, "light").emission, glm::vec3(17, 12, 4));
}

TEST(ObjCornell, SphereMaterialsAndNormals)
{
    const Scene s = load_cornell("CornellBox-Sphere.obj");
    expect_invariants(s);
    std::printf("  CornellBox-Sphere: %zu triangles\n", s.triangle_count());
    EXPECT_EQ(s.triangle_count(), 2188u);
    EXPECT_EQ(material_named(s, "leftSphere").type, MaterialType::Mirror);
    const Material& glass = material_named(s, "rightSphere");
    EXPECT_EQ(glass.type, MaterialType::Dielectric);
    std::printf("  rightSphere: Dielectric, ior %.3f\n", glass.ior);
    EXPECT_GT(glass.ior, 1.0f);
    EXPECT_EQ(material_named(s, "light").emission, glm::vec3(10, 10, 10));
    std::size_t with_normals = 0;
    for (std::uint8_t f : s.has_vertex_normals) with_normals += f;
    std::printf("  triangles with vertex normals: %zu\n", with_normals);
    EXPECT_GT(with_normals, 2000u);
}

TEST(ObjCornell, GlossyIsPhongAndClamped)
{
    const auto path = test::repo_scene("cornell-box/CornellBox-Glossy.obj");
    testing::internal::CaptureStderr();
    const Scene s = load_scene(path);
    const std::string err = testing::internal::GetCapturedStderr();
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 1112u);
    const Material& sphere = material_named(s, "sphere");
    EXPECT_EQ(sphere.type, MaterialType::Phong);
    EXPECT_EQ(sphere.phong_exponent, 32.0f);
    for (int c = 0; c < 3; ++c) EXPECT_LE(sphere.albedo[c] + sphere.specular[c], 1.0f + 1e-6f);
    std::printf("  sphere kd+ks = %.4f (file: 0.486 + 0.7)\n", sphere.albedo.x + sphere.specular.x);
    EXPECT_NE(err.find("'sphere'"), std::string::npos) << err;
    EXPECT_EQ(material_named(s, "shortBox").type, MaterialType::Lambert);  // Ks 0

    LoadOptions lambert;
    lambert.phong_as_lambert = true;
    const Scene l = load_scene(path, lambert);
    const Material& ls = material_named(l, "sphere");
    EXPECT_EQ(ls.type, MaterialType::Lambert);
    EXPECT_NEAR(ls.albedo.x, 0.486f, 1e-6f);  // Kd untouched
}

TEST(ObjCornell, WaterCount)
{
    const Scene s = load_cornell("CornellBox-Water.obj");
    expect_invariants(s);
    std::printf("  CornellBox-Water: %zu triangles\n", s.triangle_count());
    EXPECT_EQ(s.triangle_count(), 7088u);
}

// A large position-only triangle mesh as OBJ text, the shape of a scanned model's file
// ("v x y z" lines, then "f a b c" with 1-based indices, no normals or uvs): an n x n grid of
// quads over [-1, 1]^2, each split in two, with a gentle height field so that the normals
// vary. 2 n^2 triangles; `header` goes first (an mtllib line, say).
std::string position_only_grid_obj(int n, const std::string& header = "")
{
    std::string out = header;
    char line[96];
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = -1.0 + 2.0 * i / n;
            const double y = -1.0 + 2.0 * j / n;
            std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", x, y, 0.1 * std::sin(3 * x) * std::cos(2 * y));
            out += line;
        }
    const auto at = [n](int i, int j) { return j * (n + 1) + i + 1; };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", at(i, j), at(i + 1, j), at(i + 1, j + 1),
                          at(i, j), at(i + 1, j + 1), at(i, j + 1));
            out += line;
        }
    return out;
}

// A scan-sized mesh (70k triangles) without any material: everything gets the default.
TEST(ObjGenerated, LargePositionOnlyMesh)
{
    ScratchDir dir;
    const auto path = dir.write("grid.obj", position_only_grid_obj(187));
    const auto t0 = std::chrono::steady_clock::now();
    const Scene s = load_scene(path);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("  grid: %zu triangles in %.1f ms\n", s.triangle_count(), ms);
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 2u * 187u * 187u);
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].name, "default");
    EXPECT_EQ(s.materials[0].albedo, glm::vec3(0.5f));
    const Bounds3 b = s.bounds();
    EXPECT_EQ(b.lo.x, -1.0f);
    EXPECT_EQ(b.hi.y, 1.0f);
    EXPECT_NEAR(b.hi.z, 0.1f, 1e-3f);
}

// A 100k-triangle mesh whose mtllib names a file that is not there: one warning of ours, the
// default material, and tinyobjloader's own duplicate message filtered out.
TEST(ObjGenerated, LargeMeshMissingMtl)
{
    ScratchDir dir;
    const auto path = dir.write("big.obj", position_only_grid_obj(224, "mtllib big.mtl\n"));
    testing::internal::CaptureStderr();
    const auto t0 = std::chrono::steady_clock::now();
    const Scene s = load_scene(path);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const std::string err = testing::internal::GetCapturedStderr();
    std::printf("  big: %zu triangles in %.1f ms\n  stderr: %s", s.triangle_count(), ms, err.c_str());
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 2u * 224u * 224u);
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].name, "default");
    EXPECT_NE(err.find("material library 'big.mtl' not found; using the default material"), std::string::npos);
    EXPECT_EQ(err.find("Failed to load"), std::string::npos);  // tinyobjloader's duplicate is filtered
}

TEST(ObjSpot, Texture)
{
    const Scene s = load_scene(test::test_data_scene("spot/spot_textured.obj"));
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 5856u);
    ASSERT_EQ(s.textures.size(), 1u);
    const Texture& t = s.textures[0];
    std::printf("  spot texture: %s %dx%d\n", t.name.c_str(), t.width, t.height);
    EXPECT_EQ(t.width, 1024);
    EXPECT_EQ(t.height, 1024);
    EXPECT_TRUE(t.srgb);
    EXPECT_EQ(t.texels.size(), 1024u * 1024u);
    EXPECT_EQ(t.texels[0] >> 24, 255u);  // RGB PNG -> opaque
    EXPECT_EQ(material_named(s, "spot").albedo_texture, 0);
    ASSERT_EQ(s.uvs.size(), 3 * s.triangle_count());
    // The texture is the unit square (a few seam vertices stray just outside it).
    glm::vec2 lo(1e9f), hi(-1e9f);
    for (const glm::vec2& uv : s.uvs) {
        lo = glm::min(lo, uv);
        hi = glm::max(hi, uv);
    }
    std::printf("  uv range (%.3f, %.3f) .. (%.3f, %.3f)\n", lo.x, lo.y, hi.x, hi.y);
    EXPECT_GT(lo.x, -0.1f);
    EXPECT_GT(lo.y, -0.1f);
    EXPECT_LT(hi.x, 1.1f);
    EXPECT_LT(hi.y, 1.1f);
    EXPECT_GT(hi.x - lo.x, 0.5f);
}

TEST(ObjSpot, QuadsFanToSameCount)
{
    const Scene s = load_scene(test::test_data_scene("spot/spot_quadrangulated.obj"));
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 5856u);
}

// --- synthetic files

TEST(ObjSynthetic, QuadNegativeIndicesAndCrlf)
{
    ScratchDir dir;
    const auto p = dir.write("quad.obj",
                             "# a unit quad\r\nv 0 0 0 # inline comment\r\nv 1 0 0\r\nv 1 1 0\r\nv 0 1 0\r\nf -4 -3 -2 -1\r\n");
    const Scene s = load_scene(p);
    expect_invariants(s);
    ASSERT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(s.vertex(0, 0), Point3(0, 0, 0));
    EXPECT_EQ(s.vertex(0, 1), Point3(1, 0, 0));
    EXPECT_EQ(s.vertex(0, 2), Point3(1, 1, 0));
    EXPECT_EQ(s.vertex(1, 0), Point3(0, 0, 0));
    EXPECT_EQ(s.vertex(1, 1), Point3(1, 1, 0));
    EXPECT_EQ(s.vertex(1, 2), Point3(0, 1, 0));
    EXPECT_EQ(s.normals[0], Normal3(0, 0, 1));  // counter-clockwise seen from +Z
    EXPECT_EQ(s.materials[s.material_ids[0]].name, "default");
}

TEST(ObjSynthetic, PentagonFan)
{
    ScratchDir dir;
    const auto p = dir.write("penta.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n");
    const Scene s = load_scene(p);
    ASSERT_EQ(s.triangle_count(), 3u);
    for (int t = 0; t < 3; ++t) EXPECT_EQ(s.vertex(t, 0), Point3(0, 0, 0));
    EXPECT_EQ(s.vertex(2, 2), Point3(-1, 1, 0));
}

TEST(ObjSynthetic, VertexNormalsAndUvs)
{
    ScratchDir dir;
    const auto p = dir.write("vn.obj",
                             "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 0.25\n"
                             "vn 0 0 2\nvn 0 1 1\nvn 0 0 0\n"
                             "f 1/1/1 2/2/2 3/3/3\n"  // third normal is zero -> face normal
                             "f 1 2 3\n");
    const Scene s = load_scene(p);
    expect_invariants(s);
    ASSERT_EQ(s.triangle_count(), 2u);
    EXPECT_EQ(s.has_vertex_normals[0], 1);
    EXPECT_EQ(s.has_vertex_normals[1], 0);
    EXPECT_EQ(s.normals[0], Normal3(0, 0, 1));                     // normalized
    EXPECT_NEAR(s.normals[1].y, std::sqrt(0.5f), 1e-6f);
    EXPECT_EQ(s.normals[2], Normal3(0, 0, 1));                     // zero -> face normal
    ASSERT_EQ(s.uvs.size(), 6u);
    EXPECT_EQ(s.uvs[1], glm::vec2(1.0f, 1.0f));                    // v flipped: 1 - 0
    EXPECT_EQ(s.uvs[2], glm::vec2(0.0f, 0.75f));
    EXPECT_EQ(s.uvs[3], glm::vec2(0.0f));                          // no vt on the second face
}

TEST(ObjSynthetic, DegenerateTriangleKept)
{
    ScratchDir dir;
    const auto p = dir.write("degenerate.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nv 0 1 0\nf 1 2 3\nf 1 1 1\nf 1 2 4\n");
    const Scene s = load_scene(p);
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 3u);
}

TEST(ObjErrors, EveryTriangleZeroAreaIsRefused)
{
    ScratchDir dir;
    const auto p = dir.write("flat.obj", "v 0 0 0\nv 1 1 1\nv 2 2 2\nf 1 2 3\nf 1 1 1\nf 3 2 1\n");
    expect_input_error([&] { load_scene(p); }, {"flat.obj", "every triangle has zero area (3 triangle(s)"});
    // A quad whose four corners lie on one line fans into two flat triangles.
    const auto q = dir.write("line.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nf 1 2 3 4\n");
    expect_input_error([&] { load_scene(q); }, {"line.obj", "every triangle has zero area (2 triangle(s)"});
}

TEST(ObjSynthetic, TinyAndHugeTrianglesHaveArea)
{
    // In float the cross product of these edges underflows to 0 (1e-60) or overflows to inf
    // (1e60); the area test must see both as the real triangles they are.
    for (const float scale : {1e-30f, 1e-44f, 1e30f, 3e38f})
        EXPECT_FALSE(has_zero_area(Point3(0, 0, 0), Point3(scale, 0, 0), Point3(0, scale, 0))) << scale;
    EXPECT_TRUE(has_zero_area(Point3(0, 0, 0), Point3(1e30f, 0, 0), Point3(2e30f, 0, 0)));
}

// The kernels render the Cornell box the same from 1e-12 to 1e12 times its size, and darker
// or black outside (scene_checks.h): scenes outside are refused with their extent.
TEST(ObjErrors, ScenesOutsideTheRenderableScalesAreRefused)
{
    ScratchDir dir;
    auto triangle = [&](const std::string& name, const std::string& s) {
        return dir.write(name, "v 0 0 0\nv " + s + " 0 0\nv 0 " + s + " 0\nf 1 2 3\n");
    };
    EXPECT_EQ(load_scene(triangle("small_ok.obj", "2e-12")).triangle_count(), 1u);
    EXPECT_EQ(load_scene(triangle("large_ok.obj", "1e12")).triangle_count(), 1u);
    expect_input_error([&] { load_scene(triangle("tiny.obj", "5e-13")); },
                       {"tiny.obj", "the scene is 5e-13 units across", "scale the scene up"});
    expect_input_error([&] { load_scene(triangle("huge.obj", "3e12")); },
                       {"huge.obj", "scene coordinates reach 3e+12", "scale the scene down"});
    // Small but far from the origin counts by its coordinates.
    expect_input_error([&] { load_scene(dir.write("far.obj", "v 2e12 0 0\nv 2e12 1 0\nv 2e12 0 1\nf 1 2 3\n")); },
                       {"far.obj", "scene coordinates reach 2e+12"});
}

TEST(ObjSynthetic, MaterialsAndMissingMtl)
{
    ScratchDir dir;
    dir.write("m.mtl",
              "newmtl red\nKd 0.8 0.1 0.1\nillum 1\n"
              "newmtl shiny\nKd 0.8 0.8 0.8\nKs 0.5 0.5 0.5\nNs 20\nillum 2\n"
              "newmtl glass\nNi 1.33\nillum 7\n"
              "newmtl lamp\nKd 0 0 0\nKe 3 2 1\n");
    const auto p = dir.write("m.obj",
                             "mtllib m.mtl nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\n"
                             "usemtl red\nf 1 2 3\nusemtl shiny\nf 1 2 3\nusemtl glass\nf 1 2 3\n"
                             "usemtl lamp\nf 1 2 3\nusemtl unknown\nf 1 2 3\n");
    testing::internal::CaptureStderr();
    const Scene s = load_scene(p);
    const std::string err = testing::internal::GetCapturedStderr();
    std::printf("  stderr: %s", err.c_str());
    expect_invariants(s);
    ASSERT_EQ(s.triangle_count(), 5u);
    EXPECT_EQ(s.materials[s.material_ids[0]].type, MaterialType::Lambert);
    const Material& shiny = s.materials[s.material_ids[1]];
    EXPECT_EQ(shiny.type, MaterialType::Phong);
    EXPECT_NEAR(shiny.albedo.x + shiny.specular.x, 1.0f, 1e-6f);
    EXPECT_NEAR(shiny.albedo.x / shiny.specular.x, 0.8f / 0.5f, 1e-5f);
    EXPECT_EQ(s.materials[s.material_ids[2]].type, MaterialType::Dielectric);
    EXPECT_NEAR(s.materials[s.material_ids[2]].ior, 1.33f, 1e-6f);
    EXPECT_EQ(s.materials[s.material_ids[3]].emission, glm::vec3(3, 2, 1));
    EXPECT_EQ(s.materials[s.material_ids[4]].name, "default");
    EXPECT_EQ(s.emissive_triangles(), std::vector<std::uint32_t>{3});
    EXPECT_NE(err.find("material library 'nowhere.mtl' not found; using the default material"), std::string::npos);
    EXPECT_NE(err.find("'shiny'"), std::string::npos);  // the clamp warning names the material
}

TEST(ObjSynthetic, MissingTextureNamesBothFiles)
{
    ScratchDir dir;
    dir.write("t.mtl", "newmtl tex\nKd 1 1 1\nmap_Kd textures/missing.png\n");
    const auto p = dir.write("t.obj", "mtllib t.mtl\nusemtl tex\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_input_error([&] { load_scene(p); }, {"missing.png", "t.obj"});
}

TEST(ObjSynthetic, UnreadableTexture)
{
    ScratchDir dir;
    dir.write("bad.png", "this is not a png");
    dir.write("t.mtl", "newmtl tex\nKd 1 1 1\nmap_Kd bad.png\n");
    const auto p = dir.write("t.obj", "mtllib t.mtl\nusemtl tex\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_input_error([&] { load_scene(p); }, {"bad.png", "t.obj"});
}

TEST(ObjErrors, NanCoordinateNamesLine)
{
    ScratchDir dir;
    const auto p = dir.write("nan.obj", "v 0 0 0\nv 1 0 0\n\nv 0 nan 0\nf 1 2 3\n");
    expect_input_error([&] { load_scene(p); }, {"nan.obj:4:", "nan"});
}

TEST(ObjErrors, InfAndGarbageCoordinates)
{
    ScratchDir dir;
    expect_input_error([&] { load_scene(dir.write("inf.obj", "v 0 0 inf\n")); }, {"inf.obj:1:", "not finite"});
    expect_input_error([&] { load_scene(dir.write("big.obj", "v 0 0 1e39\n")); }, {"big.obj:1:"});
    expect_input_error([&] { load_scene(dir.write("abc.obj", "v 0 abc 0\n")); }, {"abc.obj:1:", "not a number"});
    expect_input_error([&] { load_scene(dir.write("short.obj", "v 0 0\n")); }, {"short.obj:1:", "needs 3"});
    expect_input_error([&] { load_scene(dir.write("vn.obj", "vn 0 0 -nan\n")); }, {"vn.obj:1:"});
}

TEST(ObjErrors, OutOfRangeIndexNamesLine)
{
    ScratchDir dir;
    const auto p = dir.write("oob.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
    expect_input_error([&] { load_scene(p); }, {"oob.obj:5:", "index 4 out of range", "3 vertices"});
    // Indices count the vertices declared so far, not the whole file.
    expect_input_error([&] { load_scene(dir.write("later.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n")); },
                       {"later.obj:3:"});
    expect_input_error([&] { load_scene(dir.write("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n")); },
                       {"neg.obj:4:", "-4"});
    expect_input_error([&] { load_scene(dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")); },
                       {"zero.obj:4:", "index 0"});
    expect_input_error([&] { load_scene(dir.write("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n")); },
                       {"vt.obj:5:", "texture coordinate index 2"});
    expect_input_error([&] { load_scene(dir.write("vn2.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//1 2//1 3//1\n")); },
                       {"vn2.obj:4:", "normal index 1"});
    expect_input_error([&] { load_scene(dir.write("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")); },
                       {"two.obj:3:", "at least 3"});
}

TEST(ObjErrors, EmptyAndNoTriangles)
{
    ScratchDir dir;
    expect_input_error([&] { load_scene(dir.write("empty.obj", "")); }, {"empty.obj", "no triangles"});
    expect_input_error([&] { load_scene(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n# nothing else\n")); },
                       {"points.obj", "no triangles"});
}

TEST(ObjErrors, GarbageBinary)
{
    ScratchDir dir;
    std::vector<unsigned char> bytes(4096);
    unsigned state = 12345;
    for (unsigned char& b : bytes) b = static_cast<unsigned char>((state = state * 1103515245u + 12345u) >> 16);
    expect_input_error([&] { load_scene(dir.write("garbage.obj", bytes)); }, {"garbage.obj"});
}

TEST(LoadScene, UnsupportedExtensionAndMissingFile)
{
    ScratchDir dir;
    expect_input_error([&] { load_scene(dir.write("x.ply", "ply\n")); }, {"x.ply", ".obj", ".gltf", ".glb"});
    expect_input_error([&] { load_scene(dir.path() / "absent.obj"); }, {"absent.obj", "not found"});
    expect_input_error([&] { load_scene(dir.path() / "absent.glb"); }, {"absent.glb", "not found"});
    // The extension is case-insensitive.
    const Scene s = load_scene(dir.write("UPPER.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
    EXPECT_EQ(s.triangle_count(), 1u);
}

TEST(EnergyConservation, ScalesOnlyChannelsAboveOne)
{
    Material m;
    m.albedo = {0.8f, 0.2f, 0.6f};
    m.specular = {0.6f, 0.2f, 0.4f};
    EXPECT_TRUE(enforce_energy_conservation(m));
    EXPECT_NEAR(m.albedo.x + m.specular.x, 1.0f, 1e-6f);
    EXPECT_NEAR(m.albedo.x / m.specular.x, 0.8f / 0.6f, 1e-5f);
    EXPECT_EQ(m.albedo.y, 0.2f);
    EXPECT_EQ(m.specular.z, 0.4f);
    EXPECT_FALSE(enforce_energy_conservation(m));
}

}  // namespace
}  // namespace gc
