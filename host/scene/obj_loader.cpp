#include "host/scene/obj_loader.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <tiny_obj_loader.h>

#include "host/scene/energy_conservation.h"
#include "host/scene/obj_validate.h"
#include "host/scene/scene_file.h"
#include "host/scene/texture_io.h"
#include "host/scene/triangle_sink.h"
#include "host/util/error.h"
#include "host/util/log.h"

namespace gc {

namespace {

std::string read_text_file(const std::filesystem::path& path)
{
    const std::vector<unsigned char> bytes = read_regular_file(path);
    return std::string(bytes.begin(), bytes.end());
}

// Opens mtllib files relative to the .obj's folder with std::filesystem (tinyobjloader's own
// reader splits its search path at ':'), validates their numbers (tinyobjloader reads "nan" and
// garbage as 0), and remembers which .mtl defined each material. An error cannot be thrown
// through tinyobjloader, so it is kept and rethrown by load_obj.
class MtlReader : public tinyobj::MaterialReader {
public:
    MtlReader(std::filesystem::path dir, std::string obj_name) : m_dir(std::move(dir)), m_obj_name(std::move(obj_name)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* material_map, std::string* warn, std::string* err) override
    {
        const std::filesystem::path file = m_dir / name;
        // Only regular files: a library named /dev/stdin or a FIFO would block forever.
        if (!why_not_regular_file(file).empty()) return false;  // load_obj has warned already
        std::string text;
        try {
            text = read_text_file(file);
            validate_mtl_text(text, file.string());
        } catch (const InputError& e) {
            // "scene.obj: lib.mtl:4: ..." names both the scene the user gave and the culprit.
            if (!m_error) m_error = std::make_exception_ptr(InputError(m_obj_name + ": " + e.what()));
            return false;
        }
        std::istringstream in(text);
        const std::size_t first = materials->size();
        tinyobj::LoadMtl(material_map, materials, &in, warn, err);
        for (std::size_t i = first; i < materials->size(); ++i) m_source.push_back(file);
        return true;
    }

    // Rethrows the first error met in a library, if any.
    void rethrow_error() const
    {
        if (m_error) std::rethrow_exception(m_error);
    }

    // The .mtl that defined material i (texture paths are relative to it).
    std::filesystem::path source_of(std::size_t i) const { return i < m_source.size() ? m_source[i] : m_dir / "?"; }

private:
    std::filesystem::path m_dir;
    std::string m_obj_name;
    std::vector<std::filesystem::path> m_source;
    std::exception_ptr m_error;
};

bool finite3(const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

MaterialType type_for_illum(int illum, const std::string& where)
{
    switch (illum) {
    case 0: case 1: case 2: case 10: return MaterialType::Lambert;
    case 3: case 5: case 8: return MaterialType::Mirror;
    case 4: case 6: case 7: case 9: return MaterialType::Dielectric;
    default:
        log_warning(where + ": illum " + std::to_string(illum) + " is not supported; using Lambert");
        return MaterialType::Lambert;
    }
}

class ObjConverter {
public:
    ObjConverter(const std::filesystem::path& path, const LoadOptions& options, Scene& scene)
        : m_name(path.string()), m_options(options), m_scene(scene)
    {
    }

    void convert_materials(const std::vector<tinyobj::material_t>& mtls, const MtlReader& reader)
    {
        for (std::size_t i = 0; i < mtls.size(); ++i) m_scene.materials.push_back(convert(mtls[i], reader.source_of(i)));
    }

    // The index of the "default" material, added the first time a face needs it.
    std::uint32_t default_material()
    {
        if (!m_default) {
            m_default = static_cast<std::uint32_t>(m_scene.materials.size());
            m_scene.materials.push_back(Material{});
        }
        return *m_default;
    }

private:
    Material convert(const tinyobj::material_t& m, const std::filesystem::path& mtl_file)
    {
        const std::string where = m_name + ": material '" + m.name + "' (" + mtl_file.filename().string() + ")";
        if (!finite3(m.diffuse) || !finite3(m.specular) || !finite3(m.emission) || !std::isfinite(m.shininess) ||
            !std::isfinite(m.ior) || !std::isfinite(m.dissolve))
            throw InputError(where + ": non-finite Kd/Ks/Ke/Ns/Ni/d value");
        Material out;
        out.name = m.name;
        out.albedo = {m.diffuse[0], m.diffuse[1], m.diffuse[2]};
        out.specular = {m.specular[0], m.specular[1], m.specular[2]};
        out.emission = glm::max(glm::vec3(m.emission[0], m.emission[1], m.emission[2]), glm::vec3(0.0f));
        out.phong_exponent = std::max(m.shininess, 0.0f);
        out.ior = m.ior;
        out.opacity = std::clamp(m.dissolve, 0.0f, 1.0f);
        out.type = type_for_illum(m.illum, where);
        const bool has_specular = m.specular[0] > 0.0f || m.specular[1] > 0.0f || m.specular[2] > 0.0f;
        if (m.illum == 2 && has_specular && !m_options.phong_as_lambert) {
            out.type = MaterialType::Phong;
            if (enforce_energy_conservation(out))
                log_warning(where + ": Kd + Ks exceeds 1; both scaled down to conserve energy");
        }
        if (!m.diffuse_texname.empty()) out.albedo_texture = texture(m.diffuse_texname, mtl_file);
        return out;
    }

    int texture(std::string name, const std::filesystem::path& mtl_file)
    {
        std::replace(name.begin(), name.end(), '\\', '/');  // files written on Windows
        const std::filesystem::path file = mtl_file.parent_path() / name;
        const auto found = m_textures.find(file.string());
        if (found != m_textures.end()) return found->second;
        m_scene.textures.push_back(load_texture_file(file, true, m_name + " (via " + mtl_file.filename().string() + ")"));
        const int index = static_cast<int>(m_scene.textures.size() - 1);
        m_textures.emplace(file.string(), index);
        return index;
    }

    std::string m_name;
    const LoadOptions& m_options;
    Scene& m_scene;
    std::optional<std::uint32_t> m_default;
    std::map<std::string, int> m_textures;
};

// Our own warnings replace tinyobjloader's about missing libraries, and "both d and Tr" is
// noise (d wins, which is what we want); the rest pass through once.
void forward_warnings(const std::string& warn, const std::string& obj_name)
{
    std::set<std::string> seen;
    std::istringstream lines(warn);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.empty() || line == "." || line.find("Failed to load material file") != std::string::npos ||
            line.find("not found in a path") != std::string::npos ||
            line.find("Both `d` and `Tr` parameters defined") != std::string::npos)
            continue;
        if (seen.insert(line).second) log_warning(obj_name + ": " + line);
    }
}

}  // namespace

Scene load_obj(const std::filesystem::path& path, const LoadOptions& options)
{
    const std::string name = path.string();
    const std::string text = read_text_file(path);
    const ObjScan scan = validate_obj_text(text, name);
    if (scan.triangles == 0) throw InputError(name + ": no triangles");
    // tinyobjloader stops at the first mtllib file it can open, so check them all here.
    std::set<std::string> warned;
    for (const std::string& lib : scan.material_libraries) {
        const std::string why = why_not_regular_file(path.parent_path() / lib);
        if (!why.empty() && warned.insert(lib).second)
            log_warning(name + ": material library '" + lib + "' " + (why == "file not found" ? "not found" : why) +
                        "; using the default material");
    }

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> mtls;
    std::string warn, err;
    MtlReader reader(path.parent_path(), name);
    std::istringstream in(text);
    // triangulate = false: we fan-triangulate ourselves (tinyobjloader splits quads along the
    // shorter diagonal), so the triangles match the references' fan triangulation.
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &mtls, &warn, &err, &in, &reader, false, false);
    reader.rethrow_error();
    forward_warnings(warn, name);
    if (!ok || !err.empty()) throw InputError(name + ": " + (err.empty() ? std::string("cannot parse") : err));

    Scene scene;
    scene.source_path = name;
    ObjConverter converter(path, options, scene);
    converter.convert_materials(mtls, reader);

    const std::size_t nv = attrib.vertices.size() / 3;
    const std::size_t nn = attrib.normals.size() / 3;
    const std::size_t nt = attrib.texcoords.size() / 2;
    TriangleSink sink(scene, scan.triangles);

    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& mesh = shape.mesh;
        std::size_t offset = 0;
        for (std::size_t f = 0; f < mesh.num_face_vertices.size(); ++f) {
            const std::size_t n = mesh.num_face_vertices[f];
            if (offset + n > mesh.indices.size()) throw InputError(name + ": internal: face indices out of step");
            const int mtl = f < mesh.material_ids.size() ? mesh.material_ids[f] : -1;
            const std::uint32_t material = (mtl >= 0 && static_cast<std::size_t>(mtl) < mtls.size())
                                               ? static_cast<std::uint32_t>(mtl)
                                               : converter.default_material();
            for (std::size_t k = 1; k + 1 < n; ++k) {
                const tinyobj::index_t corner[3] = {mesh.indices[offset], mesh.indices[offset + k],
                                                    mesh.indices[offset + k + 1]};
                SinkCorner c[3];
                bool normals = true;
                bool uvs = true;
                for (int j = 0; j < 3; ++j) {
                    const tinyobj::index_t& ix = corner[j];
                    // obj_validate already rejected bad indices; this guards the arrays anyway.
                    if (ix.vertex_index < 0 || static_cast<std::size_t>(ix.vertex_index) >= nv ||
                        (ix.normal_index >= 0 && static_cast<std::size_t>(ix.normal_index) >= nn) ||
                        (ix.texcoord_index >= 0 && static_cast<std::size_t>(ix.texcoord_index) >= nt))
                        throw InputError(name + ": face index out of range");
                    const float* p = &attrib.vertices[3 * static_cast<std::size_t>(ix.vertex_index)];
                    c[j].position = Point3(p[0], p[1], p[2]);
                    if (ix.normal_index >= 0) {
                        const float* v = &attrib.normals[3 * static_cast<std::size_t>(ix.normal_index)];
                        c[j].normal = Normal3(v[0], v[1], v[2]);
                    } else {
                        normals = false;
                    }
                    if (ix.texcoord_index >= 0) {
                        const float* t = &attrib.texcoords[2 * static_cast<std::size_t>(ix.texcoord_index)];
                        c[j].uv = glm::vec2(t[0], 1.0f - t[1]);
                    } else {
                        uvs = false;
                    }
                }
                sink.add(c, normals, uvs, material);
            }
            offset += n;
        }
    }
    if (scene.triangle_count() == 0) throw InputError(name + ": no triangles");
    if (scene.materials.empty()) converter.default_material();
    return scene;
}

}  // namespace gc
