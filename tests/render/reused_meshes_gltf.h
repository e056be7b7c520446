// A glTF whose nodes reuse its meshes, for the tests of instanced rendering (OpenCL:
// tests/render/instanced_render_test.cpp; the Vulkan reference: tests/vk): a floor once, a
// cube three times (one turned 30 degrees about y, one mirrored in x and scaled) and an area
// light twice (one mirrored), so light sampling, normals and windings all go through the
// instances' transforms.
#pragma once

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gc::test {

// Non-indexed triangles with per-corner normals: the .bin's positions, then its normals.
struct MeshData {
    std::vector<float> positions;
    std::vector<float> normals;
    void add(glm::vec3 a, glm::vec3 b, glm::vec3 c)
    {
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (const glm::vec3& p : {a, b, c}) {
            positions.insert(positions.end(), {p.x, p.y, p.z});
            normals.insert(normals.end(), {n.x, n.y, n.z});
        }
    }
    void quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d)  // counter-clockwise seen from the front
    {
        add(a, b, c);
        add(a, c, d);
    }
};

inline MeshData floor_mesh()
{
    MeshData m;
    m.quad({-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3});  // faces +y
    return m;
}

inline MeshData cube_mesh()
{
    MeshData m;
    const float h = 0.5f;
    m.quad({-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h});      // +z
    m.quad({h, -h, -h}, {-h, -h, -h}, {-h, h, -h}, {h, h, -h});  // -z
    m.quad({h, -h, h}, {h, -h, -h}, {h, h, -h}, {h, h, h});      // +x
    m.quad({-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h});  // -x
    m.quad({-h, h, h}, {h, h, h}, {h, h, -h}, {-h, h, -h});      // +y
    m.quad({-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h});  // -y
    return m;
}

inline MeshData light_mesh()
{
    MeshData m;
    m.quad({-0.4f, 0, -0.4f}, {0.4f, 0, -0.4f}, {0.4f, 0, 0.4f}, {-0.4f, 0, 0.4f});  // faces -y
    return m;
}

// Floor once, the cube three times (one turned 30 degrees about y, one mirrored in x and
// scaled), the light twice (one mirrored in x): a .gltf and its .bin in `dir`.
inline std::filesystem::path write_reused_meshes_gltf(const std::filesystem::path& dir)
{
    const MeshData meshes[3] = {floor_mesh(), cube_mesh(), light_mesh()};
    std::vector<unsigned char> bin;
    std::string accessors, views, gltf_meshes;
    for (int i = 0; i < 3; ++i) {
        const std::size_t count = meshes[i].positions.size() / 3;
        for (const std::vector<float>* data : {&meshes[i].positions, &meshes[i].normals}) {
            const std::size_t offset = bin.size();
            bin.resize(offset + data->size() * sizeof(float));
            std::memcpy(bin.data() + offset, data->data(), data->size() * sizeof(float));
            glm::vec3 lo(1e30f), hi(-1e30f);
            for (std::size_t k = 0; k < count; ++k)
                for (int c = 0; c < 3; ++c) {
                    lo[c] = std::min(lo[c], (*data)[3 * k + c]);
                    hi[c] = std::max(hi[c], (*data)[3 * k + c]);
                }
            const int view = static_cast<int>(views.empty() ? 0 : std::count(views.begin(), views.end(), '{'));
            views += std::string(views.empty() ? "" : ", ") + "{\"buffer\": 0, \"byteOffset\": " + std::to_string(offset) +
                     ", \"byteLength\": " + std::to_string(data->size() * sizeof(float)) + "}";
            accessors += std::string(accessors.empty() ? "" : ", ") + "{\"bufferView\": " + std::to_string(view) +
                         ", \"componentType\": 5126, \"count\": " + std::to_string(count) + ", \"type\": \"VEC3\"" +
                         (data == &meshes[i].positions
                              ? ", \"min\": [" + std::to_string(lo.x) + "," + std::to_string(lo.y) + "," +
                                    std::to_string(lo.z) + "], \"max\": [" + std::to_string(hi.x) + "," +
                                    std::to_string(hi.y) + "," + std::to_string(hi.z) + "]"
                              : std::string()) +
                         "}";
        }
        gltf_meshes += std::string(i ? ", " : "") + "{\"primitives\": [{\"attributes\": {\"POSITION\": " +
                       std::to_string(2 * i) + ", \"NORMAL\": " + std::to_string(2 * i + 1) +
                       "}, \"material\": " + std::to_string(i) + "}]}";
    }
    const std::string json = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2, 3, 4, 5]}],
      "nodes": [
        {"mesh": 0},
        {"mesh": 1, "translation": [-1.4, 0.5, 0.2]},
        {"mesh": 1, "translation": [0.2, 0.5, -0.6], "rotation": [0, 0.25881905, 0, 0.96592583]},
        {"mesh": 1, "translation": [1.5, 0.35, 0.6], "scale": [-0.7, 0.7, 0.7]},
        {"mesh": 2, "translation": [-0.8, 2.2, 0.3]},
        {"mesh": 2, "translation": [0.9, 2.0, -0.2], "scale": [-1, 1, 1]}],
      "meshes": [)" + gltf_meshes + R"(],
      "materials": [
        {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0, "roughnessFactor": 1}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.1, 1], "metallicFactor": 0, "roughnessFactor": 0.4}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0, "roughnessFactor": 1},
         "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}}],
      "extensionsUsed": ["KHR_materials_emissive_strength"],
      "accessors": [)" + accessors + R"(], "bufferViews": [)" + views + R"(],
      "buffers": [{"uri": "reused.bin", "byteLength": )" + std::to_string(bin.size()) + "}]}";
    std::ofstream(dir / "reused.bin", std::ios::binary).write(reinterpret_cast<const char*>(bin.data()),
                                                              static_cast<std::streamsize>(bin.size()));
    std::ofstream(dir / "reused.gltf") << json;
    return dir / "reused.gltf";
}

}  // namespace gc::test
