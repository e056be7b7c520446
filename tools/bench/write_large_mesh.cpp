// geocold-large-mesh: writes the benchmark's generated scene (large_mesh.h) as an OBJ and its
// MTL, so that geocold-cl can render it (tools/device/multi-device-run.sh's third scene).
// Positions shared by several triangles are written once; the file has no normals, as the
// scene's triangles have none (the loader then uses each face's own).
//
//     geocold-large-mesh out.obj [--grid N] [--levels L]
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <unordered_map>

#include "tools/bench/large_mesh.h"

namespace {

struct PositionKey {
    std::uint32_t x, y, z;
    bool operator==(const PositionKey&) const = default;
};

struct PositionHash {
    std::size_t operator()(const PositionKey& k) const
    {
        std::uint64_t h = k.x * 0x9e3779b97f4a7c15ull;
        h ^= (h >> 29) + k.y * 0xbf58476d1ce4e5b9ull;
        h ^= (h >> 31) + k.z * 0x94d049bb133111ebull;
        return static_cast<std::size_t>(h ^ (h >> 32));
    }
};

PositionKey key_of(const gc::Point3& p)
{
    PositionKey k;
    std::memcpy(&k.x, &p.x, 4);
    std::memcpy(&k.y, &p.y, 4);
    std::memcpy(&k.z, &p.z, 4);
    return k;
}

bool write_mtl(const gc::Scene& scene, const std::string& path)
{
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    for (const gc::Material& m : scene.materials) {
        std::fprintf(f, "newmtl %s\nKd %.9g %.9g %.9g\n", m.name.c_str(), m.albedo.x, m.albedo.y, m.albedo.z);
        if (m.is_emissive()) std::fprintf(f, "Ke %.9g %.9g %.9g\n", m.emission.x, m.emission.y, m.emission.z);
        std::fputc('\n', f);
    }
    return std::fclose(f) == 0;
}

bool write_obj(const gc::Scene& scene, const std::string& path, const std::string& mtl_name)
{
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) return false;
    std::fprintf(f, "# geocold-large-mesh: %zu triangles\nmtllib %s\n", scene.triangle_count(), mtl_name.c_str());
    std::unordered_map<PositionKey, std::uint32_t, PositionHash> index;
    index.reserve(scene.positions.size() / 2);
    std::uint32_t current_material = UINT32_MAX;
    for (std::size_t tri = 0; tri < scene.triangle_count(); ++tri) {
        std::uint32_t corners[3];
        for (int c = 0; c < 3; ++c) {
            const gc::Point3 p = scene.vertex(tri, c);
            const auto [it, added] = index.try_emplace(key_of(p), static_cast<std::uint32_t>(index.size() + 1));
            if (added) std::fprintf(f, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
            corners[c] = it->second;
        }
        if (scene.material_ids[tri] != current_material) {
            current_material = scene.material_ids[tri];
            std::fprintf(f, "usemtl %s\n", scene.materials[current_material].name.c_str());
        }
        std::fprintf(f, "f %u %u %u\n", corners[0], corners[1], corners[2]);
    }
    return std::fclose(f) == 0;
}

}  // namespace

constexpr const char* k_usage = "Usage: geocold-large-mesh OUT.obj [--grid N (1-64)] [--levels L (1-8)]\n";

int main(int argc, char** argv)
{
    std::string out;
    int grid = 8;
    int levels = 6;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if ((a == "--grid" || a == "--levels") && i + 1 < argc) {
            const int v = std::atoi(argv[++i]);
            if (v < 1 || v > (a == "--grid" ? 64 : 8)) {
                std::fprintf(stderr, "geocold-large-mesh: %s out of range\n", a.c_str());
                return 2;
            }
            (a == "--grid" ? grid : levels) = v;
        } else if (out.empty() && !a.starts_with("-")) {
            out = a;
        } else {
            std::fputs(k_usage, stderr);
            return 2;
        }
    }
    if (out.empty() || std::filesystem::path(out).extension() != ".obj") {
        std::fputs(k_usage, stderr);
        return 2;
    }
    const gc::Scene scene = gc::bench::make_large_mesh(grid, levels);
    const std::filesystem::path obj(out);
    const std::filesystem::path mtl = std::filesystem::path(obj).replace_extension(".mtl");
    // Written beside the target and renamed, so that a failure leaves no half-written scene.
    const std::string obj_tmp = out + ".tmp";
    const std::string mtl_tmp = mtl.string() + ".tmp";
    if (!write_mtl(scene, mtl_tmp) || !write_obj(scene, obj_tmp, mtl.filename().string())) {
        std::fprintf(stderr, "geocold-large-mesh: %s: cannot write\n", out.c_str());
        std::remove(obj_tmp.c_str());
        std::remove(mtl_tmp.c_str());
        return 1;
    }
    std::filesystem::rename(mtl_tmp, mtl);
    std::filesystem::rename(obj_tmp, obj);
    std::printf("%s: %zu triangles\n", out.c_str(), scene.triangle_count());
    return 0;
}
