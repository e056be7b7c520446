// glTF loading: the sample scenes in tests/data, and small synthetic .gltf/.glb files that
// exercise embedded textures, transforms, materials, cameras, lights and every validation path.
#include <chrono>
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "host/scene/gltf_conformance.h"
#include "host/scene/gltf_loader.h"
#include "host/scene/instances.h"
#include "host/scene/load.h"
#include "host/scene/triangle_sink.h"
#include "scene_test_util.h"
#include "tiny_images.h"

namespace gc {
namespace {

using test::expect_input_error;
using test::ScratchDir;

// One triangle (0,0,0), (1,0,0), (0,1,0), counter-clockwise seen from +Z, normals +Z,
// u16 indices 0 1 2: positions at byte 0, normals at 36, indices at 72, padded to 80.
std::vector<unsigned char> triangle_bin(std::uint16_t i0 = 0, std::uint16_t i1 = 1, std::uint16_t i2 = 2)
{
    const float data[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::uint16_t idx[4] = {i0, i1, i2, 0};
    std::vector<unsigned char> bin(80);
    std::memcpy(bin.data(), data, 72);
    std::memcpy(bin.data() + 72, idx, 8);
    return bin;
}

// The parts of a one-triangle glTF document a test may replace.
struct Doc {
    std::string buffer_uri = "\"uri\": \"tri.bin\", ";
    std::string buffer_length = "80";
    std::string position_accessor = R"({"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3"})";
    std::string primitive_extra = R"(, "indices": 2)";
    std::string attributes = R"("POSITION": 0, "NORMAL": 1)";
    std::string extra_primitives;
    std::string nodes = R"([{"mesh": 0}])";
    std::string scenes = R"([{"nodes": [0]}])";
    std::string top = "";  // extra top-level members, each followed by a comma
    std::string asset = R"({"version": "2.0"})";
    std::string extra_accessors;    // appended after the three above, each preceded by a comma
    std::string extra_buffer_views; // the same for bufferViews

    std::string json() const
    {
        return "{" + top + R"("asset": )" + asset + R"(, "scene": 0, "scenes": )" + scenes + R"(, "nodes": )" + nodes +
               R"(, "meshes": [{"primitives": [{"attributes": {)" + attributes + "}" + primitive_extra + "}" +
               extra_primitives + R"(]}], "accessors": [)" + position_accessor +
               R"(, {"bufferView": 0, "byteOffset": 36, "componentType": 5126, "count": 3, "type": "VEC3"},
                   {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"})" + extra_accessors +
               R"(], "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 72},
                               {"buffer": 0, "byteOffset": 72, "byteLength": 6})" + extra_buffer_views +
               R"(], "buffers": [{)" + buffer_uri + R"("byteLength": )" + buffer_length + "}]}";
    }
};

std::filesystem::path write_gltf(const ScratchDir& dir, const Doc& doc, const std::vector<unsigned char>& bin = triangle_bin())
{
    dir.write("tri.bin", bin);
    return dir.write("tri.gltf", doc.json());
}

void put_u32(std::vector<unsigned char>& out, std::uint32_t v)
{
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>(v >> (8 * i)));
}

// A .glb with the document's JSON (buffer without uri) and the bin as its BIN chunk.
std::vector<unsigned char> make_glb(Doc doc, std::vector<unsigned char> bin = triangle_bin())
{
    doc.buffer_uri = "";
    std::string json = doc.json();
    while (json.size() % 4) json.push_back(' ');
    while (bin.size() % 4) bin.push_back(0);
    std::vector<unsigned char> out;
    put_u32(out, 0x46546C67);
    put_u32(out, 2);
    put_u32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
    put_u32(out, static_cast<std::uint32_t>(json.size()));
    put_u32(out, 0x4E4F534A);
    out.insert(out.end(), json.begin(), json.end());
    put_u32(out, static_cast<std::uint32_t>(bin.size()));
    put_u32(out, 0x004E4942);
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
}

// Every triangle's winding agrees with its shading normals: front faces stay front.
void expect_front_faces_consistent(const Scene& s)
{
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
        const Normal3 n = face_normal(s.vertex(t, 0), s.vertex(t, 1), s.vertex(t, 2));
        for (int j = 0; j < 3; ++j) EXPECT_GT(dot(n, s.normals[3 * t + static_cast<std::size_t>(j)]), 0.0f) << t;
    }
}

struct Timed {
    Scene scene;
    double ms;
};
Timed timed_load(const std::filesystem::path& p)
{
    const auto t0 = std::chrono::steady_clock::now();
    Scene s = load_scene(p);
    return {std::move(s), std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count()};
}

void expect_invariants(const Scene& s)
{
    const std::size_t n = s.triangle_count();
    ASSERT_EQ(s.positions.size(), 3 * n);
    ASSERT_EQ(s.normals.size(), 3 * n);
    ASSERT_TRUE(s.uvs.empty() || s.uvs.size() == 3 * n);
    ASSERT_TRUE(s.tangents.empty() || s.tangents.size() == 3 * n);
    for (std::uint32_t id : s.material_ids) ASSERT_LT(id, s.materials.size());
    for (const Normal3& nn : s.normals) ASSERT_NEAR(length(nn), 1.0f, 1e-4f);
    for (const Material& m : s.materials) {
        for (int slot : {m.albedo_texture, m.metallic_roughness_texture, m.normal_texture, m.emission_texture})
            ASSERT_LT(slot, static_cast<int>(s.textures.size()));
    }
}

// --- sample scenes (tests/data/scenes; sources and licences in their READMEs)

TEST(GltfSample, BoxTextured)
{
    const Timed t = timed_load(test::test_data_scene("box-textured/BoxTextured.gltf"));
    const Scene& s = t.scene;
    std::printf("  box-textured: %zu triangles, %zu textures in %.1f ms\n", s.triangle_count(), s.textures.size(), t.ms);
    expect_invariants(s);
    EXPECT_EQ(s.triangle_count(), 12u);
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_TRUE(s.textures[0].srgb);
    EXPECT_GT(s.textures[0].width, 0);
    ASSERT_FALSE(s.materials.empty());
    EXPECT_EQ(s.materials[0].type, MaterialType::Pbr);
    EXPECT_EQ(s.materials[0].albedo_texture, 0);
    EXPECT_EQ(s.uvs.size(), 36u);
    expect_front_faces_consistent(s);
}

// The Khronos Avocado with its textures reduced to 256x256 (the README says how): TANGENT,
// a normal map and a packed metallic-roughness texture in external PNGs.
TEST(GltfSample, Avocado)
{
    const Timed t = timed_load(test::test_data_scene("avocado/Avocado.gltf"));
    std::printf("  avocado: %zu triangles in %.1f ms\n", t.scene.triangle_count(), t.ms);
    expect_invariants(t.scene);
    EXPECT_EQ(t.scene.triangle_count(), 682u);
    EXPECT_EQ(t.scene.textures.size(), 3u);
    // Its TANGENT reaches the scene (the material has a normal map), unit with w = +-1.
    ASSERT_EQ(t.scene.tangents.size(), 3u * 682u);
    for (const glm::vec4& tn : t.scene.tangents) {
        ASSERT_NEAR(glm::length(glm::vec3(tn)), 1.0f, 1e-5f);
        ASSERT_EQ(std::fabs(tn.w), 1.0f);
    }
}

TEST(GltfSample, RetroUfoHierarchy)
{
    const Timed t = timed_load(test::test_data_scene("retro-ufo/retroufo.glb"));
    std::printf("  retro-ufo: %zu triangles in %.1f ms\n", t.scene.triangle_count(), t.ms);
    expect_invariants(t.scene);
    EXPECT_EQ(t.scene.triangle_count(), 16428u);
}

// A .glb whose four material textures are images inside its BIN chunk (a JPEG base colour,
// PNG metallic-roughness, normal and emissive maps), the layout exporters write for a
// self-contained asset. The one-triangle geometry with uvs comes first, then the images,
// each 4-byte aligned.
std::vector<unsigned char> glb_with_embedded_textures()
{
    std::vector<unsigned char> bin = triangle_bin();
    const float uvs[6] = {0, 0, 1, 0, 0, 1};
    bin.resize(104);
    std::memcpy(bin.data() + 80, uvs, sizeof uvs);
    Doc doc;
    doc.attributes = R"("POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 3)";
    doc.primitive_extra = R"(, "indices": 2, "material": 0)";
    doc.extra_accessors = R"(, {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"})";
    doc.extra_buffer_views = R"(, {"buffer": 0, "byteOffset": 80, "byteLength": 24})";
    std::string images;
    const std::pair<const std::vector<unsigned char>*, const char*> encoded[4] = {
        {&test::k_jpeg_checker_4x4, "image/jpeg"},
        {&test::k_png_metallic_roughness_4x4, "image/png"},
        {&test::k_png_normal_4x4, "image/png"},
        {&test::k_png_emission_4x4, "image/png"}};
    for (int i = 0; i < 4; ++i) {
        while (bin.size() % 4) bin.push_back(0);
        const std::vector<unsigned char>& bytes = *encoded[i].first;
        doc.extra_buffer_views += R"(, {"buffer": 0, "byteOffset": )" + std::to_string(bin.size()) +
                                  R"(, "byteLength": )" + std::to_string(bytes.size()) + "}";
        images += std::string(i ? ", " : "") + R"({"bufferView": )" + std::to_string(3 + i) + R"(, "mimeType": ")" +
                  encoded[i].second + "\"}";
        bin.insert(bin.end(), bytes.begin(), bytes.end());
    }
    while (bin.size() % 4) bin.push_back(0);
    doc.buffer_length = std::to_string(bin.size());
    doc.top = R"("materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                 "metallicRoughnessTexture": {"index": 1}}, "normalTexture": {"index": 2},
                 "emissiveTexture": {"index": 3}, "emissiveFactor": [1, 1, 1]}],
              "textures": [{"source": 0}, {"source": 1}, {"source": 2}, {"source": 3}],
              "images": [)" + images + "],";
    return make_glb(doc, bin);
}

TEST(GltfSynthetic, GlbEmbeddedTextures)
{
    ScratchDir dir;
    const Scene s = load_scene(dir.write("textured.glb", glb_with_embedded_textures()));
    expect_invariants(s);
    ASSERT_EQ(s.triangle_count(), 1u);
    EXPECT_EQ(s.uvs.size(), 3u);
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    ASSERT_GE(m.albedo_texture, 0);
    ASSERT_GE(m.metallic_roughness_texture, 0);
    ASSERT_GE(m.normal_texture, 0);
    ASSERT_GE(m.emission_texture, 0);
    EXPECT_TRUE(m.is_emissive());
    const Texture& albedo = s.textures[static_cast<std::size_t>(m.albedo_texture)];
    const Texture& mr = s.textures[static_cast<std::size_t>(m.metallic_roughness_texture)];
    const Texture& normal = s.textures[static_cast<std::size_t>(m.normal_texture)];
    const Texture& emission = s.textures[static_cast<std::size_t>(m.emission_texture)];
    // Colour textures are sRGB, data textures linear.
    EXPECT_TRUE(albedo.srgb);
    EXPECT_TRUE(emission.srgb);
    EXPECT_FALSE(mr.srgb);
    EXPECT_FALSE(normal.srgb);
    for (const Texture* t : {&albedo, &mr, &normal, &emission}) {
        EXPECT_EQ(t->width, 4);
        EXPECT_EQ(t->height, 4);
        ASSERT_EQ(t->texels.size(), 16u);
    }
    // The PNGs decode to their exact bytes (RGBA8, R in the low byte, opaque).
    EXPECT_EQ(normal.texels[5], 0xFFFF8080u);
    EXPECT_EQ(mr.texels[5], 0xFFFF8000u);
    EXPECT_EQ(emission.texels[5], 0xFF28C8FFu);
    // The JPEG is lossy: its checker's first texel is reddish, the one beside it bluish.
    const auto channel = [](std::uint32_t texel, int c) { return int((texel >> (8 * c)) & 0xFF); };
    EXPECT_GT(channel(albedo.texels[0], 0), channel(albedo.texels[0], 2));
    EXPECT_LT(channel(albedo.texels[2], 0), channel(albedo.texels[2], 2));
}

// Cut anywhere (in the header, the JSON chunk, the geometry, an embedded image, the last byte),
// a .glb with embedded images is an input error naming the file, not a crash or a partial scene.
TEST(GltfSynthetic, TruncatedTexturedGlbIsAnError)
{
    const std::vector<unsigned char> bytes = glb_with_embedded_textures();
    ScratchDir dir;
    for (std::size_t n : {std::size_t(0), std::size_t(11), std::size_t(20), std::size_t(200), bytes.size() / 2,
                          bytes.size() - 600, bytes.size() - 1}) {
        const auto p = dir.write("cut.glb", std::vector<unsigned char>(bytes.begin(), bytes.begin() + static_cast<long>(n)));
        expect_input_error([&] { load_scene(p); }, {"cut.glb"});
    }
}

// --- synthetic files

TEST(GltfSynthetic, IndexedTriangleGltfAndGlb)
{
    ScratchDir dir;
    const Scene a = load_scene(write_gltf(dir, Doc{}));
    const Scene b = load_scene(dir.write("tri.glb", make_glb(Doc{})));
    for (const Scene* s : {&a, &b}) {
        expect_invariants(*s);
        ASSERT_EQ(s->triangle_count(), 1u);
        EXPECT_EQ(s->vertex(0, 1), Point3(1, 0, 0));
        EXPECT_EQ(s->has_vertex_normals[0], 1);
        EXPECT_EQ(s->normals[0], Normal3(0, 0, 1));
        ASSERT_EQ(s->materials.size(), 1u);
        EXPECT_EQ(s->materials[0].name, "default");
        EXPECT_TRUE(s->uvs.empty());
    }
}

TEST(GltfSynthetic, NonIndexedAndSkippedModes)
{
    ScratchDir dir;
    Doc doc;
    doc.primitive_extra = "";
    doc.extra_primitives = R"(, {"attributes": {"POSITION": 0}, "mode": 1})";
    testing::internal::CaptureStderr();
    const Scene s = load_scene(write_gltf(dir, doc));
    const std::string err = testing::internal::GetCapturedStderr();
    std::printf("  stderr: %s", err.c_str());
    EXPECT_EQ(s.triangle_count(), 1u);
    EXPECT_NE(err.find("mode 1"), std::string::npos);
}

TEST(GltfSynthetic, HierarchyComposesTransforms)
{
    ScratchDir dir;
    Doc doc;
    // Parent translates by +10 x; child rotates 90 degrees about Z and scales by 2.
    doc.nodes = R"([{"translation": [10, 0, 0], "children": [1]},
                    {"mesh": 0, "rotation": [0, 0, 0.70710678, 0.70710678], "scale": [2, 2, 2]}])";
    const Scene s = load_scene(write_gltf(dir, doc));
    ASSERT_EQ(s.triangle_count(), 1u);
    const Point3 p1 = s.vertex(0, 1);  // (1,0,0) -> scale (2,0,0) -> rotate (0,2,0) -> (10,2,0)
    std::printf("  (1,0,0) -> (%.4f, %.4f, %.4f)\n", p1.x, p1.y, p1.z);
    EXPECT_NEAR(p1.x, 10.0f, 1e-5f);
    EXPECT_NEAR(p1.y, 2.0f, 1e-5f);
    EXPECT_NEAR(p1.z, 0.0f, 1e-5f);
    EXPECT_NEAR(s.normals[0].z, 1.0f, 1e-5f);

    // The same through a column-major matrix.
    doc.nodes = R"([{"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 3,4,5,1], "mesh": 0}])";
    const Scene m = load_scene(write_gltf(dir, doc));
    EXPECT_EQ(m.vertex(0, 1), Point3(4, 4, 5));
}

TEST(GltfSynthetic, MirroringTransformKeepsFrontFaces)
{
    ScratchDir dir;
    Doc doc;
    doc.nodes = R"([{"mesh": 0, "scale": [-1, 1, 1]}])";
    const Scene s = load_scene(write_gltf(dir, doc));
    ASSERT_EQ(s.triangle_count(), 1u);
    const Normal3 n = face_normal(s.vertex(0, 0), s.vertex(0, 1), s.vertex(0, 2));
    std::printf("  winding normal after scale(-1,1,1): (%.1f, %.1f, %.1f)\n", n.x, n.y, n.z);
    EXPECT_EQ(n, Normal3(0, 0, 1));
    expect_front_faces_consistent(s);

    // Without NORMAL the face normal must still face +Z (the original front side).
    doc.attributes = R"("POSITION": 0)";
    const Scene f = load_scene(write_gltf(dir, doc));
    EXPECT_EQ(f.has_vertex_normals[0], 0);
    EXPECT_EQ(f.normals[0], Normal3(0, 0, 1));
}

TEST(GltfSynthetic, MaterialFactorsAndExtensions)
{
    ScratchDir dir;
    Doc doc;
    doc.primitive_extra = R"(, "indices": 2, "material": 0)";
    doc.top = R"("materials": [{"name": "m", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 0.5],
        "metallicFactor": 0.3, "roughnessFactor": 0.7}, "emissiveFactor": [1, 1, 0],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 5}, "KHR_materials_ior": {"ior": 1.33},
                       "KHR_materials_transmission": {"transmissionFactor": 0.9}},
        "doubleSided": true, "alphaMode": "MASK", "alphaCutoff": 0.25}],
        "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_ior", "KHR_materials_transmission"],)";
    const Scene s = load_scene(write_gltf(dir, doc));
    ASSERT_EQ(s.materials.size(), 1u);
    const Material& m = s.materials[0];
    EXPECT_EQ(m.type, MaterialType::Pbr);
    EXPECT_EQ(m.albedo, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(m.opacity, 0.5f);
    EXPECT_NEAR(m.metallic, 0.3f, 1e-6f);
    EXPECT_NEAR(m.roughness, 0.7f, 1e-6f);
    EXPECT_EQ(m.emission, glm::vec3(5, 5, 0));
    EXPECT_NEAR(m.ior, 1.33f, 1e-6f);
    EXPECT_NEAR(m.transmission, 0.9f, 1e-6f);
    EXPECT_TRUE(m.double_sided);
    EXPECT_EQ(m.alpha_mode, AlphaMode::Mask);
    EXPECT_EQ(m.alpha_cutoff, 0.25f);
}

// KHR_materials_transmission's transmissionTexture is read as a linear texture with its
// transform (R scales transmissionFactor, gc_material_eval.h); a bad reference is refused.
TEST(GltfSynthetic, TransmissionTextureIsRead)
{
    ScratchDir dir;
    dir.write("t.ppm", std::string("P6\n1 1\n255\n") + "\x80\x10\x10");
    Doc doc;
    doc.primitive_extra = R"(, "indices": 2, "material": 0)";
    doc.top = R"("materials": [{"name": "m", "extensions": {"KHR_materials_transmission":
        {"transmissionFactor": 0.9, "transmissionTexture": {"index": 0,
         "extensions": {"KHR_texture_transform": {"scale": [2, 2]}}}}}}],
        "textures": [{"source": 0}], "images": [{"uri": "t.ppm"}],
        "extensionsUsed": ["KHR_materials_transmission", "KHR_texture_transform"],)";
    testing::internal::CaptureStderr();
    const Scene s = load_scene(write_gltf(dir, doc));
    const std::string err = testing::internal::GetCapturedStderr();
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_NEAR(s.materials[0].transmission, 0.9f, 1e-6f);
    EXPECT_EQ(s.materials[0].layers.transmission_texture.texture, 0);
    EXPECT_EQ(s.materials[0].layers.transmission_texture.uv.scale, glm::vec2(2.0f));
    ASSERT_EQ(s.textures.size(), 1u);
    EXPECT_FALSE(s.textures[0].srgb) << "transmission is a linear channel";
    EXPECT_EQ(err.find("transmissionTexture"), std::string::npos) << err;

    doc.top = R"("materials": [{"name": "m", "extensions": {"KHR_materials_transmission":
        {"transmissionFactor": 0.9, "transmissionTexture": {"index": "zero"}}}}],
        "textures": [{"source": 0}], "images": [{"uri": "t.ppm"}],)";
    try {
        load_scene(write_gltf(dir, doc));
        FAIL() << "a transmissionTexture without an integer index was accepted";
    } catch (const InputError& e) {
        std::printf("%s\n", e.what());
        EXPECT_NE(std::string(e.what()).find("transmissionTexture"), std::string::npos) << e.what();
    }
}

// The one-triangle document with per-vertex TANGENT (accessor 3, 48 bytes after the 80 of
// triangle_bin) and a material whose normal map (a 1x1 PPM) reads them.
struct TangentDoc {
    Doc doc;
    std::vector<unsigned char> bin = triangle_bin();

    explicit TangentDoc(const float (&tangents)[12], bool normal_map = true, const char* type = "VEC4")
    {
        bin.resize(128);
        std::memcpy(bin.data() + 80, tangents, 48);
        doc.buffer_length = "128";
        doc.attributes = R"("POSITION": 0, "NORMAL": 1, "TANGENT": 3)";
        doc.primitive_extra = R"(, "indices": 2, "material": 0)";
        doc.extra_accessors = std::string(R"(, {"bufferView": 2, "componentType": 5126, "count": 3, "type": ")") + type + "\"}";
        doc.extra_buffer_views = R"(, {"buffer": 0, "byteOffset": 80, "byteLength": 48})";
        doc.top = normal_map ? R"("materials": [{"normalTexture": {"index": 0}}], "textures": [{"source": 0}],
                                  "images": [{"uri": "n.ppm"}],)"
                             : R"("materials": [{}],)";
    }

    std::filesystem::path write(const ScratchDir& dir) const
    {
        const std::string ppm = std::string("P6\n1 1\n255\n") + "\x80\x80\xff";
        dir.write("n.ppm", ppm);
        return write_gltf(dir, doc, bin);
    }
};

TEST(GltfSynthetic, TangentsReachTheScene)
{
    ScratchDir dir;
    // v0: +y, v1: +y at length 2 (renormalised), v2: +x with a mirrored bitangent.
    const float tangents[12] = {0, 1, 0, 1, 0, 2, 0, 1, 1, 0, 0, -1};
    TangentDoc t(tangents);
    testing::internal::CaptureStderr();
    const Scene s = load_scene(t.write(dir));
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(err.find("TANGENT"), std::string::npos) << err;
    expect_invariants(s);
    ASSERT_GE(s.materials[0].normal_texture, 0);
    ASSERT_EQ(s.tangents.size(), 3u);
    EXPECT_EQ(s.tangents[0], glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(s.tangents[1], glm::vec4(0, 1, 0, 1));
    EXPECT_EQ(s.tangents[2], glm::vec4(1, 0, 0, -1));

    // A 90-degree turn about +z maps the tangents like directions: +y -> -x, +x -> +y.
    t.doc.nodes = R"([{"mesh": 0, "rotation": [0, 0, 0.70710678, 0.70710678]}])";
    const Scene r = load_scene(t.write(dir));
    ASSERT_EQ(r.tangents.size(), 3u);
    std::printf("  rotated tangents: (%.4f %.4f %.4f %g) (%.4f %.4f %.4f %g)\n", r.tangents[0].x, r.tangents[0].y,
                r.tangents[0].z, r.tangents[0].w, r.tangents[2].x, r.tangents[2].y, r.tangents[2].z, r.tangents[2].w);
    EXPECT_NEAR(r.tangents[0].x, -1.0f, 1e-6f);
    EXPECT_NEAR(r.tangents[0].y, 0.0f, 1e-6f);
    EXPECT_NEAR(r.tangents[2].y, 1.0f, 1e-6f);
    EXPECT_EQ(r.tangents[2].w, -1.0f);

    // A non-uniform scale maps them like directions too (not by the normals' inverse
    // transpose): (1, 1, 0) scaled by (2, 1, 1) is along (2, 1, 0).
    const float diagonal[12] = {1, 1, 0, 1, 1, 1, 0, 1, 1, 1, 0, 1};
    TangentDoc d(diagonal);
    d.doc.nodes = R"([{"mesh": 0, "scale": [2, 1, 1]}])";
    const Scene sc = load_scene(d.write(dir));
    ASSERT_EQ(sc.tangents.size(), 3u);
    EXPECT_NEAR(sc.tangents[0].x, 2.0f / std::sqrt(5.0f), 1e-6f);
    EXPECT_NEAR(sc.tangents[0].y, 1.0f / std::sqrt(5.0f), 1e-6f);

    // A mirroring node swaps the winding (corners 1 and 2) and flips w, so B = w cross(N, T)
    // still maps to the mirrored bitangent.
    t.doc.nodes = R"([{"mesh": 0, "scale": [-1, 1, 1]}])";
    const Scene m = load_scene(t.write(dir));
    ASSERT_EQ(m.tangents.size(), 3u);
    EXPECT_EQ(m.tangents[0], glm::vec4(0, 1, 0, -1));  // v0
    EXPECT_EQ(m.tangents[1], glm::vec4(-1, 0, 0, 1));  // v2, mirrored
    EXPECT_EQ(m.tangents[2], glm::vec4(0, 1, 0, -1));  // v1

    // A zero tangent is "none" at that corner (the renderer then generates the triangle's).
    const float zero_v1[12] = {0, 1, 0, 1, 0, 0, 0, 1, 1, 0, 0, 1};
    const Scene z = load_scene(TangentDoc(zero_v1).write(dir));
    ASSERT_EQ(z.tangents.size(), 3u);
    EXPECT_EQ(z.tangents[1], glm::vec4(0.0f));

    // Without a normal map nothing reads them, so they are not kept.
    const Scene plain = load_scene(TangentDoc(tangents, false).write(dir));
    EXPECT_TRUE(plain.tangents.empty());
}

TEST(GltfErrors, BadTangents)
{
    ScratchDir dir;
    const float tangents[12] = {0, 1, 0, 1, 0, 1, 0, 1, 1, 0, 0, -1};
    TangentDoc vec3(tangents, true, "VEC3");
    expect_input_error([&] { load_scene(vec3.write(dir)); }, {"tri.gltf", "accessor 3", "VEC3 FLOAT", "VEC4 FLOAT"});
    TangentDoc short_count(tangents);
    short_count.doc.extra_accessors = R"(, {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC4"})";
    expect_input_error([&] { load_scene(short_count.write(dir)); }, {"tri.gltf", "TANGENT has 2 elements", "POSITION 3"});
    float nan_w[12];
    std::memcpy(nan_w, tangents, sizeof nan_w);
    nan_w[7] = std::nanf("");
    expect_input_error([&] { load_scene(TangentDoc(nan_w).write(dir)); }, {"tri.gltf", "accessor 3", "tangent 1", "not finite"});
}

// The one-triangle document with TEXCOORD_0 (floats, accessor 3) and TEXCOORD_1 (normalized
// UNSIGNED_SHORT, KHR_mesh_quantization, accessor 4), one 1x1 texture and the given materials.
struct UvDoc {
    Doc doc;
    std::vector<unsigned char> bin = triangle_bin();

    explicit UvDoc(const std::string& materials)
    {
        const float uv0[6] = {0, 0, 1, 0, 0, 1};
        const std::uint16_t uv1[6] = {0, 65535, 65535, 65535, 0, 0};
        bin.resize(116);
        std::memcpy(bin.data() + 80, uv0, sizeof uv0);
        std::memcpy(bin.data() + 104, uv1, sizeof uv1);
        doc.buffer_length = "116";
        doc.attributes = R"("POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 3, "TEXCOORD_1": 4)";
        doc.primitive_extra = R"(, "indices": 2, "material": 0)";
        doc.extra_accessors = R"(, {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"},
                                   {"bufferView": 3, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2"})";
        doc.extra_buffer_views = R"(, {"buffer": 0, "byteOffset": 80, "byteLength": 24},
                                      {"buffer": 0, "byteOffset": 104, "byteLength": 12})";
        doc.top = R"("materials": )" + materials + R"(, "textures": [{"source": 0}], "images": [{"uri": "t.ppm"}],
                     "extensionsUsed": ["KHR_texture_transform", "KHR_mesh_quantization"],)";
    }

    std::filesystem::path write(const ScratchDir& dir) const
    {
        dir.write("t.ppm", std::string("P6\n1 1\n255\n") + "\x80\x80\xff");
        return write_gltf(dir, doc, bin);
    }
};

TEST(GltfTextureTransform, ParsedPerSlot)
{
    ScratchDir dir;
    const UvDoc d(R"([{"pbrMetallicRoughness": {
        "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, -0.25]}}},
        "metallicRoughnessTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"rotation": 0.5}}}},
        "normalTexture": {"index": 0, "scale": 0.5, "extensions": {"KHR_texture_transform": {"scale": [2, 3]}}},
        "emissiveTexture": {"index": 0}, "emissiveFactor": [1, 1, 1]}])");
    testing::internal::CaptureStderr();
    const Scene s = load_scene(d.write(dir));
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(err.find("KHR_texture_transform"), std::string::npos) << err;
    const Material& m = s.materials[0];
    EXPECT_EQ(m.albedo_uv.offset, glm::vec2(0.5f, -0.25f));
    EXPECT_EQ(m.albedo_uv.rotation, 0.0f);
    EXPECT_EQ(m.albedo_uv.scale, glm::vec2(1.0f));
    EXPECT_EQ(m.metallic_roughness_uv.rotation, 0.5f);
    EXPECT_EQ(m.metallic_roughness_uv.offset, glm::vec2(0.0f));
    EXPECT_EQ(m.normal_uv.scale, glm::vec2(2.0f, 3.0f));
    EXPECT_EQ(m.normal_scale, 0.5f);
    EXPECT_TRUE(m.emission_uv.is_identity());
    // TEXCOORD_0 is read: no slot asks for another set.
    ASSERT_EQ(s.uvs.size(), 3u);
    EXPECT_EQ(s.uvs[1], glm::vec2(1, 0));
}

TEST(GltfTextureTransform, TexCoordOverrideSelectsTheSet)
{
    ScratchDir dir;
    // The extension's texCoord (1) overrides the textureInfo's (0): TEXCOORD_1, quantized as
    // normalized UNSIGNED_SHORT, is the set loaded.
    const UvDoc one(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 0,
        "extensions": {"KHR_texture_transform": {"texCoord": 1}}}}}])");
    const Scene s = load_scene(one.write(dir));
    ASSERT_EQ(s.uvs.size(), 3u);
    EXPECT_EQ(s.uvs[0], glm::vec2(0, 1));
    EXPECT_EQ(s.uvs[1], glm::vec2(1, 1));
    EXPECT_EQ(s.uvs[2], glm::vec2(0, 0));

    // Slots that end up reading different sets: one set per triangle is kept, with a warning
    // naming the file and the material.
    const UvDoc mixed(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
        "metallicRoughnessTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1}}}}}])");
    testing::internal::CaptureStderr();
    const Scene m = load_scene(mixed.write(dir));
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_NE(err.find("tri.gltf: material 0: its textures read different TEXCOORD sets"), std::string::npos) << err;
    EXPECT_EQ(m.uvs[1], glm::vec2(1, 0));
}

TEST(GltfTextureTransform, MalformedValuesAreRefusedNamingTheSlot)
{
    ScratchDir dir;
    const auto refused = [&](const std::string& ext, std::initializer_list<std::string> parts) {
        const UvDoc d(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
            "extensions": {"KHR_texture_transform": )" + ext + "}}}}]");
        expect_input_error([&] { load_scene(d.write(dir)); }, parts);
    };
    refused(R"({"offset": [1]})", {"tri.gltf", "material 0", "baseColorTexture", "offset is not an array of two numbers"});
    refused(R"({"offset": "a"})", {"tri.gltf", "offset is not an array of two numbers"});
    refused(R"({"scale": [1, null]})", {"tri.gltf", "scale is not an array of two numbers"});
    refused(R"({"scale": [1e300, 1]})", {"tri.gltf", "baseColorTexture", "scale is not finite"});
    refused(R"({"rotation": "x"})", {"tri.gltf", "rotation is not a number"});
    refused(R"({"rotation": 1e39})", {"tri.gltf", "rotation is not finite"});
    refused(R"({"texCoord": -1})", {"tri.gltf", "material 0", "texCoord is not an integer in [0, 31]"});
    refused(R"({"texCoord": 0.5})", {"tri.gltf", "texCoord is not an integer"});
    // tinygltf drops an extension value that is not an object before the loader sees it: the
    // slot then reads its texture untransformed (the loader's own "is not an object" check
    // stays for parsers that keep it).
    const UvDoc scalar(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
        "extensions": {"KHR_texture_transform": 7}}}}])");
    EXPECT_TRUE(load_scene(scalar.write(dir)).materials[0].albedo_uv.is_identity());
    // Huge but finite values load: the lookup guards the coordinates they make (gc_texture.h).
    const UvDoc huge(R"([{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0,
        "extensions": {"KHR_texture_transform": {"offset": [1e30, -1e30], "scale": [3e38, 3e38]}}}}}])");
    EXPECT_EQ(load_scene(huge.write(dir)).materials[0].albedo_uv.scale.x, 3e38f);
}

TEST(GltfQuantization, QuantizedAttributesLoadThroughTheNodeTransform)
{
    // KHR_mesh_quantization as an exporter writes it (and requires it): SHORT positions that a
    // node scale dequantizes, normalized BYTE normals (renormalised), UNSIGNED_BYTE uvs.
    ScratchDir dir;
    std::vector<unsigned char> bin = triangle_bin();
    bin.resize(124);
    const std::int16_t pos[12] = {0, 0, 0, 0, 100, 0, 0, 0, 0, 100, 0, 0};
    const std::int8_t nrm[12] = {0, 0, 127, 0, 0, 0, 100, 0, 0, 0, 127, 0};
    const std::uint8_t uv[6] = {0, 0, 2, 0, 0, 3};
    std::memcpy(bin.data() + 80, pos, sizeof pos);
    std::memcpy(bin.data() + 104, nrm, sizeof nrm);
    std::memcpy(bin.data() + 116, uv, sizeof uv);
    Doc doc;
    doc.buffer_length = "124";
    doc.attributes = R"("POSITION": 3, "NORMAL": 4, "TEXCOORD_0": 5)";
    doc.nodes = R"([{"mesh": 0, "scale": [0.01, 0.01, 0.01]}])";
    doc.extra_accessors = R"(, {"bufferView": 2, "componentType": 5122, "count": 3, "type": "VEC3"},
                               {"bufferView": 3, "componentType": 5120, "normalized": true, "count": 3, "type": "VEC3"},
                               {"bufferView": 4, "componentType": 5121, "count": 3, "type": "VEC2"})";
    doc.extra_buffer_views = R"(, {"buffer": 0, "byteOffset": 80, "byteLength": 24, "byteStride": 8},
                                  {"buffer": 0, "byteOffset": 104, "byteLength": 12, "byteStride": 4},
                                  {"buffer": 0, "byteOffset": 116, "byteLength": 6})";
    doc.top = R"("extensionsUsed": ["KHR_mesh_quantization"], "extensionsRequired": ["KHR_mesh_quantization"],)";
    testing::internal::CaptureStderr();
    const Scene s = load_scene(write_gltf(dir, doc, bin));
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(err.find("KHR_mesh_quantization"), std::string::npos) << err;
    expect_invariants(s);
    ASSERT_EQ(s.triangle_count(), 1u);
    EXPECT_EQ(s.positions[1], Point3(1, 0, 0));
    EXPECT_EQ(s.positions[2], Point3(0, 1, 0));
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(s.normals[static_cast<std::size_t>(i)].z, 1.0f, 1e-6f) << i;
    ASSERT_EQ(s.uvs.size(), 3u);
    EXPECT_EQ(s.uvs[1], glm::vec2(2, 0));
    EXPECT_EQ(s.uvs[2], glm::vec2(0, 3));
}

TEST(GltfSynthetic, CameraAndPointLights)
{
    ScratchDir dir;
    Doc doc;
    doc.nodes = R"([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5]},
                    {"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
                    {"extensions": {"KHR_lights_punctual": {"light": 1}}}])";
    doc.scenes = R"([{"nodes": [0, 1, 2, 3]}])";
    doc.top = R"("cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.1}}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1, 0.5, 0.25], "intensity": 4},
                                                           {"type": "spot", "spot": {}}]}},)";
    testing::internal::CaptureStderr();
    const Scene s = load_scene(write_gltf(dir, doc));
    const std::string err = testing::internal::GetCapturedStderr();
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->look_from, Point3(0, 0, 5));
    EXPECT_EQ(s.camera->look_at, Point3(0, 0, 4));
    EXPECT_EQ(s.camera->up, Vec3(0, 1, 0));
    EXPECT_NEAR(s.camera->vfov_degrees, 0.6f * 180.0f / 3.14159265f, 1e-4f);
    ASSERT_EQ(s.point_lights.size(), 1u);
    EXPECT_EQ(s.point_lights[0].position, Point3(1, 2, 3));
    EXPECT_EQ(s.point_lights[0].intensity, glm::vec3(4, 2, 1));
    EXPECT_NE(err.find("spot"), std::string::npos) << err;
}

TEST(GltfSynthetic, SceneSelection)
{
    ScratchDir dir;
    Doc doc;
    doc.nodes = R"([{"mesh": 0}, {"mesh": 0, "translation": [0, 0, 7]}])";
    doc.scenes = R"([{"nodes": [0]}, {"nodes": [1]}])";
    const auto p = write_gltf(dir, doc);
    EXPECT_EQ(load_scene(p).vertex(0, 0).z, 0.0f);  // "scene": 0 is the default
    LoadOptions second;
    second.gltf_scene = 1;
    EXPECT_EQ(load_scene(p, second).vertex(0, 0).z, 7.0f);
    LoadOptions bad;
    bad.gltf_scene = 5;
    expect_input_error([&] { load_scene(p, bad); }, {"tri.gltf", "scene 5", "2 scene"});
}

TEST(GltfErrors, AccessorPastItsBuffer)
{
    ScratchDir dir;
    Doc doc;
    doc.position_accessor = R"({"bufferView": 0, "byteOffset": 0, "componentType": 5126, "count": 30, "type": "VEC3"})";
    expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "accessor 0"});
    // The buffer file shorter than the bufferViews need.
    Doc shortbuf;
    expect_input_error([&] { load_scene(write_gltf(dir, shortbuf, std::vector<unsigned char>(40))); }, {"tri.gltf"});
    // Wrong component type for positions.
    Doc ints;
    ints.position_accessor = R"({"bufferView": 0, "componentType": 5125, "count": 3, "type": "VEC3"})";
    expect_input_error([&] { load_scene(write_gltf(dir, ints)); }, {"accessor 0", "UNSIGNED_INT", "VEC3 FLOAT"});
}

TEST(GltfErrors, IndexOutOfRangeAndNonFinite)
{
    ScratchDir dir;
    expect_input_error([&] { load_scene(write_gltf(dir, Doc{}, triangle_bin(0, 1, 5))); },
                       {"tri.gltf", "mesh 0", "accessor 2", "index 5", "3 vertices"});
    std::vector<unsigned char> bin = triangle_bin();
    const float nan = std::nanf("");
    std::memcpy(bin.data() + 16, &nan, 4);  // vertex 1, y
    expect_input_error([&] { load_scene(write_gltf(dir, Doc{}, bin)); }, {"accessor 0", "position 1", "not finite"});
}

TEST(GltfErrors, NodeCycle)
{
    ScratchDir dir;
    Doc doc;
    doc.nodes = R"([{"mesh": 0, "children": [1]}, {"children": [0]}])";
    expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "node"});
}

// A mesh drawn by three nodes (one a child, under rotation and scale) is stored once when the
// node tree is kept as instances; flattening those gives the flattening loader's triangles.
TEST(GltfInstanced, MeshDrawnByThreeNodesIsStoredOnce)
{
    ScratchDir dir;
    Doc doc;
    doc.nodes = R"([{"mesh": 0, "translation": [10, 0, 0], "children": [1]},
                    {"mesh": 0, "rotation": [0, 0, 0.70710678, 0.70710678], "scale": [2, 2, 2]},
                    {"mesh": 0, "translation": [0, 0, -3]}])";
    doc.scenes = R"([{"nodes": [0, 2]}])";
    const auto path = write_gltf(dir, doc);
    const InstancedScene inst = load_gltf_instanced(path);
    const Scene flat = load_scene(path);
    std::printf("instanced: %zu mesh triangles, %zu instances; flattened loader: %zu triangles\n",
                inst.meshes.triangle_count(), inst.instances.size(), flat.triangle_count());
    EXPECT_EQ(inst.meshes.triangle_count(), 1u);
    ASSERT_EQ(inst.mesh_ranges.size(), 1u);
    ASSERT_EQ(inst.instances.size(), 3u);
    const Scene expanded = flatten_instances(inst);
    ASSERT_EQ(expanded.triangle_count(), flat.triangle_count());
    float worst = 0.0f;
    for (std::size_t i = 0; i < flat.positions.size(); ++i)
        worst = std::max(worst, length(expanded.positions[i] - flat.positions[i]));
    std::printf("largest vertex distance, flatten_instances vs load_gltf: %g\n", static_cast<double>(worst));
    EXPECT_LT(worst, 1e-5f);
}

// The corpus file whose 3000 nodes draw one 5.6M-triangle mesh: flattened, the loader refuses
// it before reading a vertex; kept instanced, the mesh is stored once (and then refused for
// its zero area, as the corpus expects of the CLI, which keeps instances).
TEST(GltfInstanced, AbsurdFlattenedTotalIsRefusedOnlyWhenFlattening)
{
    const std::filesystem::path file =
        std::filesystem::path(GC_TEST_SOURCE_DIR) / "tests/data/bad/gltf_instances_absurd_total.gltf";
    expect_input_error([&] { load_scene(file); }, {"gltf_instances_absurd_total.gltf", "mesh instances add up to"});
    const auto loaded = load_gltf_instanced_where_reused(file);
    ASSERT_EQ(loaded.index(), 1u);
    const InstancedScene& s = std::get<InstancedScene>(loaded);
    std::printf("instanced: %zu mesh triangles drawn by %zu instances\n", s.meshes.triangle_count(), s.instances.size());
    EXPECT_EQ(s.instances.size(), 3000u);
    EXPECT_EQ(s.mesh_ranges.size(), 1u);
    expect_input_error([&] { load_scene_keeping_instances(file); }, {"gltf_instances_absurd_total.gltf", "zero area"});
    // Flattening it later (for an integrator that does not trace instances) is refused too,
    // before any memory is taken.
    expect_input_error([&] { flatten_instances(s); },
                       {"gltf_instances_absurd_total.gltf", "3000 instances draw", "copied out flat"});
}

TEST(GltfInstanced, OnlyReusedMeshesComeBackInstanced)
{
    ScratchDir dir;
    Doc doc;
    const auto once = write_gltf(dir, doc);
    EXPECT_EQ(load_gltf_instanced_where_reused(once).index(), 0u);
    doc.nodes = R"([{"mesh": 0}, {"mesh": 0, "translation": [2, 0, 0]}])";
    doc.scenes = R"([{"nodes": [0, 1]}])";
    const auto twice = write_gltf(dir, doc);
    const auto loaded = load_gltf_instanced_where_reused(twice);
    ASSERT_EQ(loaded.index(), 1u);
    EXPECT_EQ(std::get<InstancedScene>(loaded).instances.size(), 2u);
    EXPECT_EQ(std::get<InstancedScene>(loaded).meshes.triangle_count(), 1u);
}

TEST(GltfInstanced, CycleAndBadMeshIndexNameTheFile)
{
    ScratchDir dir;
    Doc doc;
    doc.nodes = R"([{"mesh": 0, "children": [1]}, {"children": [0]}])";
    expect_input_error([&] { load_gltf_instanced(write_gltf(dir, doc)); }, {"tri.gltf", "node 0", "reached twice"});
    doc.nodes = R"([{"mesh": 0}, {"mesh": 5}])";
    doc.scenes = R"([{"nodes": [0, 1]}])";
    expect_input_error([&] { load_gltf_instanced(write_gltf(dir, doc)); }, {"tri.gltf", "mesh index 5"});
}

TEST(GltfErrors, TruncatedGlbEveryLength)
{
    ScratchDir dir;
    const std::vector<unsigned char> glb = make_glb(Doc{});
    ASSERT_NO_THROW(load_scene(dir.write("whole.glb", glb)));
    int errors = 0;
    for (std::size_t n = 0; n < glb.size(); ++n) {
        const auto p = dir.write("cut.glb", std::vector<unsigned char>(glb.begin(), glb.begin() + static_cast<long>(n)));
        try {
            load_scene(p);
        } catch (const InputError& e) {
            ++errors;
            EXPECT_NE(std::string(e.what()).find("cut.glb"), std::string::npos);
        }
    }
    std::printf("  %d of %zu truncations rejected with InputError\n", errors, glb.size());
    EXPECT_EQ(static_cast<std::size_t>(errors), glb.size());

    // A header that claims more than the BIN chunk can hold: tinygltf 2.7 would read past the end.
    std::vector<unsigned char> lying = glb;
    const std::size_t bin_header = lying.size() - 80 - 8;
    lying[bin_header] = 84;  // BIN chunk length 84 > the 80 bytes present
    expect_input_error([&] { load_scene(dir.write("lying.glb", lying)); }, {"lying.glb", "chunk 1"});
}

TEST(GltfErrors, GarbageFiles)
{
    ScratchDir dir;
    std::vector<unsigned char> bytes(2048);
    unsigned state = 777;
    for (unsigned char& b : bytes) b = static_cast<unsigned char>((state = state * 1103515245u + 12345u) >> 16);
    expect_input_error([&] { load_scene(dir.write("garbage.glb", bytes)); }, {"garbage.glb"});
    const std::string msg = expect_input_error([&] { load_scene(dir.write("garbage.gltf", bytes)); }, {"garbage.gltf"});
    for (char ch : msg) EXPECT_TRUE(ch >= 0x20 && ch < 0x7f) << "unprintable byte in the message";
    expect_input_error([&] { load_scene(dir.write("text.gltf", "{\"asset\": ")); }, {"text.gltf"});
    expect_input_error([&] { load_scene(dir.write("empty.gltf", "")); }, {"empty.gltf"});
    expect_input_error([&] { load_scene(dir.write("nomesh.gltf", R"({"asset": {"version": "2.0"}})")); },
                       {"nomesh.gltf", "no triangles"});
}

// --- conformance: what the asset declares (gltf_conformance.h)

TEST(GltfConformance, MajorVersionOtherThan2IsRefused)
{
    ScratchDir dir;
    Doc doc;
    for (const char* version : {"1.0", "3.0", "0.9", "99999999999.0"}) {
        doc.asset = std::string(R"({"version": ")") + version + "\"}";
        expect_input_error([&] { load_scene(write_gltf(dir, doc)); },
                           {"tri.gltf", std::string("glTF version ") + version + " (asset.version) is not supported"});
    }
    // The same asset check inside a (valid, version-2) .glb container.
    doc.asset = R"({"version": "1.0"})";
    expect_input_error([&] { load_scene(dir.write("v1.glb", make_glb(doc))); }, {"v1.glb", "glTF version 1.0"});
}

TEST(GltfConformance, MalformedOrMissingVersionIsRefused)
{
    ScratchDir dir;
    Doc doc;
    for (const char* version : {"2", "2.", ".0", "2.0.1", "v2.0", "2.x", "+2.0", ""}) {
        doc.asset = std::string(R"({"version": ")") + version + "\"}";
        expect_input_error([&] { load_scene(write_gltf(dir, doc)); },
                           {"tri.gltf", std::string("asset.version '") + version + "' is not MAJOR.MINOR"});
    }
    // A hostile version string reaches the message without its terminal escapes, and cut short.
    doc.asset = R"({"version": "\u001b[2J)" + std::string(200, '9') + "\"}";
    const std::string msg = expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "'?[2J999", "...'"});
    EXPECT_EQ(msg.find('\x1b'), std::string::npos);
    EXPECT_LT(msg.size(), 200 + dir.path().string().size());
    doc.asset = R"({"generator": "no version"})";
    expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "asset.version is missing"});
    doc.asset = R"({"version": 2.0})";  // a number, not the string the spec asks for
    expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "asset.version is missing"});
}

TEST(GltfConformance, MinVersionAbove20IsRefused)
{
    ScratchDir dir;
    Doc doc;
    doc.asset = R"({"version": "2.1", "minVersion": "2.1"})";
    expect_input_error([&] { load_scene(write_gltf(dir, doc)); },
                       {"tri.gltf", "asset.minVersion 2.1 asks for a glTF 2.1 loader; this one implements glTF 2.0"});
    doc.asset = R"({"version": "3.0", "minVersion": "3.0"})";  // the major version is reported first
    expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "glTF version 3.0"});
    doc.asset = R"({"version": "2.0", "minVersion": "latest"})";
    expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "asset.minVersion 'latest' is not MAJOR.MINOR"});
}

TEST(GltfConformance, Later2xVersionsLoad)
{
    // The spec's forward compatibility: a 2.0 loader loads 2.x unless minVersion says otherwise.
    ScratchDir dir;
    Doc doc;
    for (const char* asset : {R"({"version": "2.0", "minVersion": "2.0"})", R"({"version": "2.1"})",
                              R"({"version": "2.10", "minVersion": "1.0"})"}) {
        doc.asset = asset;
        EXPECT_EQ(load_scene(write_gltf(dir, doc)).triangle_count(), 1u) << asset;
    }
}

TEST(GltfConformance, UnsupportedRequiredExtensionsAreAllNamed)
{
    ScratchDir dir;
    Doc doc;
    doc.top = R"("extensionsUsed": ["KHR_draco_mesh_compression", "KHR_materials_ior", "EXT_meshopt_compression"],
                 "extensionsRequired": ["KHR_draco_mesh_compression", "KHR_materials_ior", "EXT_meshopt_compression"],)";
    const std::string msg = expect_input_error(
        [&] { load_scene(write_gltf(dir, doc)); },
        {"tri.gltf", "requires glTF extension(s) KHR_draco_mesh_compression, EXT_meshopt_compression, which this loader "
                     "does not implement"});
    for (std::string_view supported : k_supported_gltf_extensions)  // listed as what it does implement
        EXPECT_NE(msg.find(std::string(supported)), std::string::npos) << supported;

    doc.top = R"("extensionsRequired": ["KHR_texture_basisu"],)";
    expect_input_error([&] { load_scene(dir.write("basisu.glb", make_glb(doc))); }, {"basisu.glb", "KHR_texture_basisu"});
}

TEST(GltfConformance, RefusedBeforeBuffersAreRead)
{
    // The declarations are checked first: the missing buffer is never looked for.
    ScratchDir dir;
    Doc doc;
    doc.top = R"("extensionsRequired": ["KHR_draco_mesh_compression"],)";
    doc.buffer_uri = R"("uri": "not_there.bin", )";
    const std::string msg = expect_input_error([&] { load_scene(dir.write("draco.gltf", doc.json())); },
                                               {"draco.gltf", "KHR_draco_mesh_compression"});
    EXPECT_EQ(msg.find("not_there.bin"), std::string::npos) << msg;
}

TEST(GltfConformance, EverySupportedExtensionMayBeRequired)
{
    ScratchDir dir;
    Doc doc;
    std::string names;
    for (std::string_view n : k_supported_gltf_extensions) names += (names.empty() ? "\"" : ", \"") + std::string(n) + "\"";
    doc.top = "\"extensionsUsed\": [" + names + "], \"extensionsRequired\": [" + names + "],";
    testing::internal::CaptureStderr();
    const Scene s = load_scene(write_gltf(dir, doc));
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(s.triangle_count(), 1u);
    EXPECT_EQ(err.find("extension"), std::string::npos) << err;
}

// KHR_materials_sheen: colour (linear), roughness and their textures (the colour sRGB, the
// roughness linear), the specification's defaults (no colour: no sheen).
TEST(GltfMaterialLayers, SheenFactorsTexturesAndDefaults)
{
    ScratchDir dir;
    dir.write("s.ppm", std::string("P6\n1 1\n255\n") + "\x80\x40\x20");
    Doc doc;
    doc.primitive_extra = R"(, "indices": 2, "material": 0)";
    doc.top = R"("materials": [{"name": "velvet", "extensions": {"KHR_materials_sheen": {
                    "sheenColorFactor": [0.3, 0.5, 1.0], "sheenRoughnessFactor": 0.3,
                    "sheenColorTexture": {"index": 0}, "sheenRoughnessTexture": {"index": 1}}}},
                 {"name": "defaults", "extensions": {"KHR_materials_sheen": {}}}],
                 "textures": [{"source": 0}, {"source": 1}], "images": [{"uri": "s.ppm"}, {"uri": "s.ppm"}],
                 "extensionsUsed": ["KHR_materials_sheen"],)";
    const Scene s = load_scene(write_gltf(dir, doc));
    ASSERT_EQ(s.materials.size(), 2u);
    const PbrLayers& v = s.materials[0].layers;
    EXPECT_TRUE(v.sheen_on);
    EXPECT_EQ(v.sheen_color, glm::vec3(0.3f, 0.5f, 1.0f));
    EXPECT_NEAR(v.sheen_roughness, 0.3f, 1e-7f);
    ASSERT_EQ(v.sheen_color_texture.texture, 0);
    ASSERT_EQ(v.sheen_roughness_texture.texture, 1);
    EXPECT_TRUE(s.textures[0].srgb) << "sheenColorTexture is sRGB";
    EXPECT_FALSE(s.textures[1].srgb) << "sheenRoughnessTexture is linear";
    const PbrLayers& d = s.materials[1].layers;
    EXPECT_TRUE(d.sheen_on);
    EXPECT_EQ(d.sheen_color, glm::vec3(0.0f));
    EXPECT_EQ(d.sheen_roughness, 0.0f);
}

// KHR_materials_clearcoat and KHR_materials_specular: factors read into Material::layers,
// defaults from the specifications, malformed values refused naming file, material and key.
TEST(GltfMaterialLayers, FactorsAndDefaults)
{
    ScratchDir dir;
    Doc doc;
    doc.primitive_extra = R"(, "indices": 2, "material": 0)";
    doc.top = R"("materials": [{"name": "coated", "extensions": {
                    "KHR_materials_clearcoat": {"clearcoatFactor": 0.75, "clearcoatRoughnessFactor": 0.25},
                    "KHR_materials_specular": {"specularFactor": 0.5, "specularColorFactor": [1.0, 0.5, 2.0]}}},
                 {"name": "defaults", "extensions": {"KHR_materials_clearcoat": {}, "KHR_materials_specular": {}}},
                 {"name": "plain"}],
                 "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_specular"],)";
    const Scene s = load_scene(write_gltf(dir, doc));
    ASSERT_EQ(s.materials.size(), 3u);
    const PbrLayers& a = s.materials[0].layers;
    EXPECT_TRUE(a.clearcoat_on && a.specular_on && !a.sheen_on);
    EXPECT_EQ(a.clearcoat, 0.75f);
    EXPECT_EQ(a.clearcoat_roughness, 0.25f);
    EXPECT_EQ(a.specular, 0.5f);
    EXPECT_EQ(a.specular_color, glm::vec3(1.0f, 0.5f, 2.0f));
    const PbrLayers& d = s.materials[1].layers;
    EXPECT_TRUE(d.clearcoat_on && d.specular_on);
    EXPECT_EQ(d.clearcoat, 0.0f);
    EXPECT_EQ(d.clearcoat_roughness, 0.0f);
    EXPECT_EQ(d.specular, 1.0f);
    EXPECT_EQ(d.specular_color, glm::vec3(1.0f));
    EXPECT_EQ(s.materials[2].layers, PbrLayers{});
}

TEST(GltfMaterialLayers, MalformedValuesAreRefused)
{
    ScratchDir dir;
    const std::pair<const char*, const char*> cases[] = {
        {R"("KHR_materials_clearcoat": {"clearcoatFactor": "one"})", "clearcoatFactor is not a number"},
        {R"("KHR_materials_clearcoat": {"clearcoatRoughnessFactor": 1.5})", "clearcoatRoughnessFactor = 1.5"},
        {R"("KHR_materials_clearcoat": {"clearcoatTexture": {"texCoord": 0}})", "clearcoatTexture has no non-negative integer index"},
        {R"("KHR_materials_clearcoat": {"clearcoatTexture": {"index": 4}})", "texture 4 out of range"},
        {R"("KHR_materials_specular": {"specularFactor": -0.1})", "specularFactor = -0.1"},
        {R"("KHR_materials_specular": {"specularColorFactor": [1, 1]})", "specularColorFactor is not an array of three numbers"},
        {R"("KHR_materials_specular": {"specularColorFactor": [1, -1, 1]})", "specularColorFactor holds a value"},
        {R"("KHR_materials_volume": {"attenuationDistance": 0})", "KHR_materials_volume: attenuationDistance is not a positive"},
        {R"("KHR_materials_volume": {"attenuationColor": [1, 1.5, 1]})", "attenuationColor holds a value above 1"},
        {R"("KHR_materials_volume": {"attenuationColor": [1, -0.5, 1]})", "attenuationColor holds a value"},
        {R"("KHR_materials_transmission": {"transmissionFactor": 1.5})", "transmissionFactor = 1.5"},
        {R"("KHR_materials_transmission": {"transmissionFactor": 1}, "KHR_materials_ior": {"ior": 0.5})", "ior = 0.5"},
        {R"("KHR_materials_sheen": {"sheenRoughnessFactor": true})", "sheenRoughnessFactor is not a number"},
        {R"("KHR_materials_sheen": {"sheenColorFactor": [1, 1, "x"]})", "sheenColorFactor holds a value"},
    };
    for (const auto& [ext, why] : cases) {
        Doc doc;
        doc.primitive_extra = R"(, "indices": 2, "material": 0)";
        doc.top = std::string(R"("materials": [{"name": "m", "extensions": {)") + ext + "}}],";
        const std::string msg = expect_input_error([&] { load_scene(write_gltf(dir, doc)); }, {"tri.gltf", "material 0 'm'", why});
        std::printf("  %s\n", msg.c_str());
    }
}

TEST(GltfMaterialLayers, SpecularAndCoatSpheres)
{
    // tests/data/scenes/material-layers: plain, tinted specular, specular off, two coats.
    const Scene s = load_scene(test::test_data_scene("material-layers/MaterialLayers.gltf"));
    ASSERT_EQ(s.materials.size(), 5u);
    EXPECT_EQ(s.materials[0].layers, PbrLayers{});
    EXPECT_TRUE(s.materials[1].layers.specular_on && !s.materials[1].layers.clearcoat_on);
    EXPECT_EQ(s.materials[1].layers.specular_color, glm::vec3(1.0f, 0.2f, 0.2f));
    EXPECT_EQ(s.materials[2].layers.specular, 0.0f);
    EXPECT_TRUE(s.materials[3].layers.clearcoat_on && !s.materials[3].layers.specular_on);
    EXPECT_EQ(s.materials[4].layers.clearcoat, 0.5f);
    EXPECT_NEAR(s.materials[4].layers.clearcoat_roughness, 0.4f, 1e-7f);
}

TEST(GltfMaterialLayers, RoughGlassVolumeModel)
{
    // tests/data/scenes/rough-glass-volume (made here): rough transmissive cube with a volume.
    const Scene s = load_scene(test::test_data_scene("rough-glass-volume/RoughGlassVolume.gltf"));
    ASSERT_EQ(s.materials.size(), 2u);
    const Material& glass = s.materials[0];
    std::printf("glass: transmission %.2f roughness %.2f ior %.2f attenuation (%.2f %.2f %.2f) at %.2f\n",
                glass.transmission, glass.roughness, glass.ior, glass.layers.attenuation_color.x,
                glass.layers.attenuation_color.y, glass.layers.attenuation_color.z, glass.layers.attenuation_distance);
    EXPECT_EQ(glass.transmission, 1.0f);
    EXPECT_EQ(glass.roughness, 0.25f);
    EXPECT_EQ(glass.ior, 1.5f);
    EXPECT_TRUE(glass.layers.volume_on);
    EXPECT_NEAR(glass.layers.attenuation_color.y, 0.5f, 1e-7f);
    EXPECT_NEAR(glass.layers.attenuation_distance, 0.6f, 1e-7f);
    EXPECT_EQ(s.materials[1].layers, PbrLayers{});
}

TEST(GltfMaterialLayers, ClearCoatSampleModel)
{
    // Khronos ClearCoatTest (tests/data/scenes/ClearCoatTest): the middle column's materials are
    // coated, the outer ones are not; the coat textures read R (factor) and G (roughness).
    testing::internal::CaptureStderr();
    const Scene s = load_scene(test::test_data_scene("ClearCoatTest/ClearCoatTest.gltf"));
    const std::string err = testing::internal::GetCapturedStderr();
    int coated = 0;
    for (const Material& m : s.materials) {
        const bool should = m.name.size() > 7 && m.name.substr(m.name.size() - 7) == "_Coated";
        EXPECT_EQ(m.layers.clearcoat_on, should) << m.name;
        coated += m.layers.clearcoat_on ? 1 : 0;
        if (m.name == "Simple_Coated") {
            EXPECT_EQ(m.layers.clearcoat, 1.0f);
            EXPECT_NEAR(m.layers.clearcoat_roughness, 0.03f, 1e-7f);
        }
        if (m.name == "Partial_Coated") {
            EXPECT_GE(m.layers.clearcoat_texture.texture, 0);
        }
        if (m.name == "RoughVariations_Coated") {
            EXPECT_GE(m.layers.clearcoat_roughness_texture.texture, 0);
        }
    }
    EXPECT_EQ(coated, 6);
    // The two rows with a coat normal map read it, linear, as the base normal map is read.
    int coat_normals = 0;
    for (const Material& m : s.materials) {
        const int t = m.layers.clearcoat_normal_texture.texture;
        if (t < 0) continue;
        ++coat_normals;
        EXPECT_TRUE(m.layers.clearcoat_on) << m.name;
        EXPECT_FALSE(s.textures[static_cast<std::size_t>(t)].srgb) << m.name;
        EXPECT_TRUE(std::isfinite(m.layers.clearcoat_normal_scale)) << m.name;
    }
    EXPECT_EQ(coat_normals, 2);
    EXPECT_EQ(err.find("clearcoatNormalTexture"), std::string::npos) << err;
}

TEST(GltfConformance, UnsupportedUsedExtensionsGetOneWarning)
{
    ScratchDir dir;
    Doc doc;
    doc.primitive_extra = R"(, "indices": 2, "material": 0)";
    doc.top = R"("materials": [{"extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 1},
                                               "KHR_materials_dispersion": {}, "KHR_materials_ior": {"ior": 1.2}}}],
                 "extensionsUsed": ["KHR_materials_anisotropy", "KHR_materials_iridescence", "KHR_materials_ior"],)";
    testing::internal::CaptureStderr();
    const Scene s = load_scene(write_gltf(dir, doc));
    const std::string err = testing::internal::GetCapturedStderr();
    std::printf("  stderr: %s", err.c_str());
    EXPECT_EQ(s.triangle_count(), 1u);
    EXPECT_NEAR(s.materials[0].ior, 1.2f, 1e-6f);
    EXPECT_NE(err.find("tri.gltf: uses glTF extension(s) KHR_materials_anisotropy, KHR_materials_iridescence, which this "
                       "loader does not implement; ignored"),
              std::string::npos);
    const auto count = [&](const std::string& what) {
        std::size_t n = 0;
        for (auto at = err.find(what); at != std::string::npos; at = err.find(what, at + 1)) ++n;
        return n;
    };
    EXPECT_EQ(count("KHR_materials_iridescence"), 1u) << "declared: named once, by the file's warning";
    EXPECT_EQ(count("KHR_materials_dispersion"), 1u) << "undeclared: still named, by the material's warning";
    EXPECT_EQ(count("KHR_materials_ior"), 0u) << "supported: no warning";
}

TEST(GltfConformance, DeclarationsAreReadFromTheTopLevelOnly)
{
    const auto declared = read_gltf_declarations(R"({"asset": {"version": "2.0", "minVersion": "2.0"},
        "nodes": [{"extensionsRequired": ["NOT_TOP_LEVEL"]}], "extensionsRequired": ["A", 7],
        "extensionsUsed": ["A", "B"], "buffers": [{"uri": "data:,xyz"}]})");
    ASSERT_TRUE(declared.has_value());
    EXPECT_EQ(declared->version, "2.0");
    EXPECT_EQ(declared->min_version, "2.0");
    EXPECT_EQ(declared->extensions_required, (std::vector<std::string>{"A", "7"}));
    EXPECT_EQ(declared->extensions_used, (std::vector<std::string>{"A", "B"}));
    EXPECT_FALSE(read_gltf_declarations("{\"asset\": ").has_value());  // tinygltf reports broken JSON
    EXPECT_FALSE(read_gltf_declarations("[1, 2]").has_value());
    EXPECT_EQ(unsupported_gltf_extensions({"KHR_materials_ior", "X", "X", "KHR_lights_punctual", "Y"}),
              (std::vector<std::string>{"X", "Y"}));
}

// --- every triangle has zero area (scene_checks.h, run by load_scene for every format)

TEST(GltfErrors, EveryTriangleZeroAreaIsRefused)
{
    ScratchDir dir;
    const float collinear[9] = {0, 0, 0, 1, 1, 1, 2, 2, 2};
    std::vector<unsigned char> bin = triangle_bin();
    std::memcpy(bin.data(), collinear, sizeof collinear);
    expect_input_error([&] { load_scene(write_gltf(dir, Doc{}, bin)); },
                       {"tri.gltf", "every triangle has zero area (1 triangle(s)"});
    expect_input_error([&] { load_scene(dir.write("flat.glb", make_glb(Doc{}, bin))); },
                       {"flat.glb", "every triangle has zero area"});

    // With one real triangle beside it the degenerate one is kept, as before.
    Doc doc;
    doc.extra_primitives = R"(, {"attributes": {"POSITION": 3}})";
    doc.extra_accessors = R"(, {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"})";
    doc.extra_buffer_views = R"(, {"buffer": 0, "byteOffset": 80, "byteLength": 36})";
    doc.buffer_length = "116";
    bin.resize(116);
    const float good[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::memcpy(bin.data() + 80, good, sizeof good);
    EXPECT_EQ(load_scene(write_gltf(dir, doc, bin)).triangle_count(), 2u);
}

}  // namespace
}  // namespace gc
