#include "host/scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "host/math/transform.h"
#include "host/scene/gltf_accessor.h"
#include "host/scene/gltf_conformance.h"
#include "host/scene/glb_check.h"
#include "host/scene/gltf_files.h"
#include "host/scene/gltf_images.h"
#include "host/scene/gltf_material_layers.h"
#include "host/scene/scene_checks.h"
#include "host/scene/scene_file.h"
#include "host/scene/texture_io.h"
#include "host/scene/triangle_sink.h"
#include "host/util/error.h"
#include "host/util/log.h"

namespace gc {

namespace {

constexpr double k_pi = 3.14159265358979323846;

// The scene's root nodes; without scenes in the file, every node that is nobody's child.
std::vector<int> root_nodes(const tinygltf::Model& model, int scene_index)
{
    if (scene_index >= 0) return model.scenes[static_cast<std::size_t>(scene_index)].nodes;
    std::vector<int> roots;
    std::vector<char> is_child(model.nodes.size(), 0);
    for (const tinygltf::Node& n : model.nodes)
        for (int c : n.children)
            if (c >= 0 && static_cast<std::size_t>(c) < is_child.size()) is_child[static_cast<std::size_t>(c)] = 1;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
    return roots;
}

// Whether the scene's nodes draw some mesh more than once. Bad indices and nodes met twice
// are skipped here: GltfConverter::convert_scene reports them.
bool reuses_a_mesh(const tinygltf::Model& model, int scene_index)
{
    std::vector<int> uses(model.meshes.size(), 0);
    std::vector<char> seen(model.nodes.size(), 0);
    std::vector<int> stack = root_nodes(model, scene_index);
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        if (n < 0 || static_cast<std::size_t>(n) >= model.nodes.size() || seen[static_cast<std::size_t>(n)]++) continue;
        const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(n)];
        if (node.mesh >= 0 && static_cast<std::size_t>(node.mesh) < uses.size() &&
            ++uses[static_cast<std::size_t>(node.mesh)] > 1)
            return true;
        stack.insert(stack.end(), node.children.begin(), node.children.end());
    }
    return false;
}

class GltfConverter {
public:
    // With `instanced`, each mesh goes into `scene` once, in object space, and every node that
    // draws it becomes an instance of it in `instanced` (whose meshes member the caller fills
    // with `scene` afterwards); without, every node's mesh is flattened into `scene`.
    GltfConverter(const tinygltf::Model& model, const std::string& name, const GltfFileLog& files, Scene& scene,
                  InstancedScene* instanced = nullptr)
        : m_model(model), m_name(name), m_files(files), m_scene(scene), m_instanced(instanced)
    {
    }

    void convert_materials()
    {
        for (std::size_t i = 0; i < m_model.materials.size(); ++i)
            m_scene.materials.push_back(convert_material(m_model.materials[i], static_cast<int>(i)));
        m_uv_sets.resize(m_model.materials.size(), 0);
        for (std::size_t i = 0; i < m_model.materials.size(); ++i) m_uv_sets[i] = uv_set(m_model.materials[i], static_cast<int>(i));
    }

    void convert_scene(int scene_index)
    {
        const std::vector<int> roots = root_nodes(m_model, scene_index);

        // Depth-first in file order, with an explicit stack: a hostile file cannot overflow
        // ours, and a node met twice (a cycle or a shared child) is an error, as the spec says
        // the hierarchy is a set of disjoint trees.
        std::vector<char> visited(m_model.nodes.size(), 0);
        struct Visit { int node; glm::mat4 parent; };
        struct Placed { int node; glm::mat4 world; };
        std::vector<Placed> placed;
        std::vector<Visit> stack;
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::mat4(1.0f)});
        while (!stack.empty()) {
            const Visit v = stack.back();
            stack.pop_back();
            if (v.node < 0 || static_cast<std::size_t>(v.node) >= m_model.nodes.size())
                fail("node index " + std::to_string(v.node) + " out of range (" + std::to_string(m_model.nodes.size()) + " nodes)");
            if (visited[static_cast<std::size_t>(v.node)]++)
                fail("node " + std::to_string(v.node) + " is reached twice (the node hierarchy must be a tree)");
            const tinygltf::Node& node = m_model.nodes[static_cast<std::size_t>(v.node)];
            const glm::mat4 world = v.parent * local_matrix(node, v.node);
            placed.push_back({v.node, world});
            for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back({*it, world});
        }

        // All instances are counted before the first is expanded (see reserve_triangles); kept
        // as instances, each mesh is expanded once.
        std::set<int> counted;
        for (const Placed& p : placed)
            if (const int mesh = m_model.nodes[static_cast<std::size_t>(p.node)].mesh; mesh >= 0)
                if (!m_instanced || counted.insert(mesh).second) reserve_triangles(mesh);
        for (const Placed& p : placed) {
            const tinygltf::Node& node = m_model.nodes[static_cast<std::size_t>(p.node)];
            const Transform to_world(p.world);
            if (node.mesh >= 0 && m_instanced) add_instance(node.mesh, p.world);
            else if (node.mesh >= 0) add_mesh(node.mesh, to_world);
            if (node.camera >= 0) add_camera(node.camera, to_world);
            add_light(node, to_world);
        }
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw InputError(m_name + ": " + what); }

    glm::mat4 local_matrix(const tinygltf::Node& node, int index) const
    {
        glm::mat4 m(1.0f);
        if (node.matrix.size() == 16) {
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) m[c][r] = static_cast<float>(node.matrix[static_cast<std::size_t>(4 * c + r)]);
        } else {
            glm::mat4 t(1.0f), r(1.0f), s(1.0f);
            if (node.translation.size() == 3)
                t = glm::translate(glm::mat4(1.0f), glm::vec3(static_cast<float>(node.translation[0]),
                                                              static_cast<float>(node.translation[1]),
                                                              static_cast<float>(node.translation[2])));
            if (node.rotation.size() == 4) {
                // glTF stores (x, y, z, w); glm::quat's constructor takes w first.
                const glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                                  static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
                r = glm::mat4_cast(glm::normalize(q));
            }
            if (node.scale.size() == 3)
                s = glm::scale(glm::mat4(1.0f), glm::vec3(static_cast<float>(node.scale[0]), static_cast<float>(node.scale[1]),
                                                          static_cast<float>(node.scale[2])));
            m = t * r * s;
        }
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r])) fail("node " + std::to_string(index) + " has a non-finite transform");
        return m;
    }

    // Accessor `index`, checked for `use` (gltf_accessor.h).
    AccessorView view(int index, AccessorUse use, const std::string& where) const
    {
        return gltf_accessor_view(m_model, index, use, m_name, where);
    }

    void add_mesh(int mesh_index, const Transform& to_world)
    {
        if (static_cast<std::size_t>(mesh_index) >= m_model.meshes.size())
            fail("mesh index " + std::to_string(mesh_index) + " out of range (" + std::to_string(m_model.meshes.size()) + " meshes)");
        const tinygltf::Mesh& mesh = m_model.meshes[static_cast<std::size_t>(mesh_index)];
        const bool flip = to_world.swaps_handedness();
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = mesh.primitives[p];
            const std::string where = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
            if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
                if (m_warned_modes.insert(prim.mode).second)
                    log_warning(m_name + ": " + where + ": primitive mode " + std::to_string(prim.mode) +
                                " is not supported (only TRIANGLES); skipped");
                continue;
            }
            add_primitive(prim, where, to_world, flip);
        }
    }

    // Mesh `mesh_index` in object space the first time a node draws it; then an instance of it.
    // A mesh without triangles (only unsupported primitive modes) gets no instance.
    void add_instance(int mesh_index, const glm::mat4& world)
    {
        auto [it, is_new] = m_mesh_ids.try_emplace(mesh_index, 0u);
        if (is_new) {
            const auto first = static_cast<std::uint32_t>(m_scene.triangle_count());
            add_mesh(mesh_index, Transform(glm::mat4(1.0f)));
            const auto count = static_cast<std::uint32_t>(m_scene.triangle_count()) - first;
            it->second = count == 0 ? kNoMesh : static_cast<std::uint32_t>(m_instanced->mesh_ranges.size());
            if (count > 0) m_instanced->mesh_ranges.push_back({first, count});
        }
        if (it->second != kNoMesh) m_instanced->instances.push_back({it->second, world});
    }

    // Instancing multiplies triangles without costing the file a byte: a few hundred bytes of
    // JSON can name thousands of instances of a mesh of millions of (zero-filled) vertices.
    // Every instance is flattened into the scene, so the total is checked from the accessor
    // counts before any instance is expanded.
    void reserve_triangles(int mesh_index)
    {
        if (static_cast<std::size_t>(mesh_index) >= m_model.meshes.size()) return;  // add_mesh reports it
        const tinygltf::Mesh& mesh = m_model.meshes[static_cast<std::size_t>(mesh_index)];
        std::uint64_t triangles = 0;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = mesh.primitives[p];
            if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) continue;
            // view() validates the accessor's counts against its bytes (no data is read), so a
            // bad accessor gets its own precise error here rather than a triangle total.
            const std::string where = "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(p);
            if (prim.indices >= 0) {
                triangles += view(prim.indices, AccessorUse::Index, where).count / 3;
            } else if (const auto pos = prim.attributes.find("POSITION"); pos != prim.attributes.end()) {
                triangles += view(pos->second, AccessorUse::Position, where).count / 3;
            }
        }
        m_planned_triangles += triangles;
        if (std::string why; !flat_triangles_fit(m_planned_triangles, why))
            fail("mesh instances add up to " + std::to_string(m_planned_triangles) + " triangles by instance " +
                 std::to_string(m_instances + 1) + " (mesh " + std::to_string(mesh_index) +
                 "); instances are flattened, which would need " + why);
        ++m_instances;
    }

    void add_primitive(const tinygltf::Primitive& prim, const std::string& where, const Transform& to_world, bool flip)
    {
        const auto pos_it = prim.attributes.find("POSITION");
        if (pos_it == prim.attributes.end()) fail(where + ": no POSITION attribute");
        const AccessorView pos = view(pos_it->second, AccessorUse::Position, where);
        const std::size_t nv = pos.count;

        // One uv set per triangle reaches the device: the one the material's textures read
        // (uv_set), TEXCOORD_0 when the primitive lacks it.
        std::string uv_name = "TEXCOORD_0";
        if (prim.material >= 0 && static_cast<std::size_t>(prim.material) < m_uv_sets.size() &&
            m_uv_sets[static_cast<std::size_t>(prim.material)] != 0) {
            const std::string wanted = "TEXCOORD_" + std::to_string(m_uv_sets[static_cast<std::size_t>(prim.material)]);
            if (prim.attributes.count(wanted)) uv_name = wanted;
            else log_warning(m_name + ": " + where + ": material " + std::to_string(prim.material) + " reads " + wanted +
                             ", which the primitive lacks; TEXCOORD_0 used instead");
        }
        std::optional<AccessorView> nrm, uv;
        if (const auto it = prim.attributes.find("NORMAL"); it != prim.attributes.end())
            nrm = view(it->second, AccessorUse::Normal, where);
        if (const auto it = prim.attributes.find(uv_name); it != prim.attributes.end())
            uv = view(it->second, AccessorUse::TexCoord, where);
        std::optional<AccessorView> tan;
        const auto tan_it = prim.attributes.find("TANGENT");
        if (tan_it != prim.attributes.end()) tan = view(tan_it->second, AccessorUse::Tangent, where);
        if (nrm && nrm->count != nv)
            fail(where + ": NORMAL has " + std::to_string(nrm->count) + " elements, POSITION " + std::to_string(nv));
        if (uv && uv->count != nv)
            fail(where + ": " + uv_name + " has " + std::to_string(uv->count) + " elements, POSITION " + std::to_string(nv));
        if (tan && tan->count != nv)
            fail(where + ": TANGENT has " + std::to_string(tan->count) + " elements, POSITION " + std::to_string(nv));

        std::optional<AccessorView> idx;
        if (prim.indices >= 0) idx = view(prim.indices, AccessorUse::Index, where);
        const std::size_t corners = idx ? idx->count : nv;
        if (corners % 3 != 0)
            fail(where + ": " + std::to_string(corners) + (idx ? " indices" : " vertices") + " is not a multiple of 3");

        std::uint32_t material;
        if (prim.material >= 0) {
            if (static_cast<std::size_t>(prim.material) >= m_model.materials.size())
                fail(where + ": material " + std::to_string(prim.material) + " out of range (" +
                     std::to_string(m_model.materials.size()) + " materials)");
            material = static_cast<std::uint32_t>(prim.material);
        } else {
            material = default_material();
        }
        // Only normal maps read tangents: a TANGENT the material has no use for is not kept.
        const bool with_tangents = tan && m_scene.materials[material].normal_texture >= 0;

        // Transform each vertex once.
        std::vector<Point3> world_pos(nv);
        std::vector<Normal3> world_nrm(nrm ? nv : 0);
        std::vector<glm::vec4> world_tan(with_tangents ? nv : 0);
        const std::string tan_where = tan ? where + ", accessor " + std::to_string(tan_it->second) : std::string();
        for (std::size_t i = 0; i < nv; ++i) {
            const Point3 p(pos.get(i, 0), pos.get(i, 1), pos.get(i, 2));
            if (!is_finite(p))
                fail(where + ", accessor " + std::to_string(pos_it->second) + ": position " + std::to_string(i) + " is not finite");
            world_pos[i] = to_world.apply(p);
            if (nrm) world_nrm[i] = to_world.apply(Normal3(nrm->get(i, 0), nrm->get(i, 1), nrm->get(i, 2)));
            if (with_tangents) world_tan[i] = world_tangent(*tan, i, to_world, flip, tan_where);
        }

        TriangleSink sink(m_scene, corners / 3);
        for (std::size_t t = 0; t < corners / 3; ++t) {
            std::size_t vi[3];
            for (int j = 0; j < 3; ++j) {
                vi[j] = idx ? idx->index(3 * t + static_cast<std::size_t>(j)) : 3 * t + static_cast<std::size_t>(j);
                if (vi[j] >= nv)
                    fail(where + ", accessor " + std::to_string(prim.indices) + ": index " + std::to_string(vi[j]) +
                         " at position " + std::to_string(3 * t + static_cast<std::size_t>(j)) + " out of range (" +
                         std::to_string(nv) + " vertices)");
            }
            if (flip) std::swap(vi[1], vi[2]);
            SinkCorner c[3];
            for (int j = 0; j < 3; ++j) {
                c[j].position = world_pos[vi[j]];
                if (nrm) c[j].normal = world_nrm[vi[j]];
                if (uv) c[j].uv = glm::vec2(uv->get(vi[j], 0), uv->get(vi[j], 1));
                if (with_tangents) c[j].tangent = world_tan[vi[j]];
            }
            sink.add(c, nrm.has_value(), uv.has_value(), material, with_tangents);
        }
    }

    // Tangent i of a TANGENT accessor in world space. The tangent lies in the surface, so it
    // maps like a direction (the linear part, not the normals' inverse transpose), renormalised.
    // B = w * cross(N, T) maps to det(M) * cross(N', T') under M, so a transform that swaps
    // handedness (the one that also flips the winding) flips w. A zero tangent (or one a
    // degenerate scale collapses) is stored as none: that triangle gets generated tangents.
    glm::vec4 world_tangent(const AccessorView& tan, std::size_t i, const Transform& to_world, bool flip,
                            const std::string& where) const
    {
        const glm::vec4 t(tan.get(i, 0), tan.get(i, 1), tan.get(i, 2), tan.get(i, 3));
        if (!std::isfinite(t.x) || !std::isfinite(t.y) || !std::isfinite(t.z) || !std::isfinite(t.w))
            fail(where + ": tangent " + std::to_string(i) + " is not finite");
        const Vec3 d = to_world.apply(Vec3(t.x, t.y, t.z));
        const float len = length(d);
        if (!(len > 0.0f) || !std::isfinite(len)) return glm::vec4(0.0f);
        const float w = (t.w < 0.0f) != flip ? -1.0f : 1.0f;
        return glm::vec4(d.x / len, d.y / len, d.z / len, w);
    }

    void add_camera(int camera_index, const Transform& to_world)
    {
        if (m_scene.camera) return;
        if (static_cast<std::size_t>(camera_index) >= m_model.cameras.size())
            fail("camera index " + std::to_string(camera_index) + " out of range (" + std::to_string(m_model.cameras.size()) + " cameras)");
        const tinygltf::Camera& cam = m_model.cameras[static_cast<std::size_t>(camera_index)];
        if (cam.type != "perspective") return;
        const double yfov = cam.perspective.yfov;
        if (!(yfov > 0.0 && yfov < k_pi)) {
            log_warning(m_name + ": camera " + std::to_string(camera_index) + " has yfov " + std::to_string(yfov) + "; ignored");
            return;
        }
        // glTF cameras look down their local -Z with +Y up.
        Camera c;
        c.look_from = to_world.apply(Point3(0, 0, 0));
        const Vec3 forward = to_world.apply(Vec3(0, 0, -1));
        const Vec3 up = to_world.apply(Vec3(0, 1, 0));
        if (!(length(forward) > 0.0f) || !(length(up) > 0.0f)) {
            log_warning(m_name + ": camera " + std::to_string(camera_index) + " has a degenerate transform; ignored");
            return;
        }
        c.look_at = c.look_from + normalize(forward);
        c.up = normalize(up);
        c.vfov_degrees = static_cast<float>(yfov * 180.0 / k_pi);
        m_scene.camera = c;
    }

    // KHR_lights_punctual. glTF gives point-light intensity in candela (lm/sr); the renderer
    // works in unitless linear RGB "W/sr", so we take 1 cd as 1 W/sr (no 683 lm/W factor):
    // PointLight::intensity = color * intensity.
    void add_light(const tinygltf::Node& node, const Transform& to_world)
    {
        const auto ext = node.extensions.find("KHR_lights_punctual");
        if (ext == node.extensions.end() || !ext->second.Has("light")) return;
        const tinygltf::Value& lv = ext->second.Get("light");
        if (!lv.IsNumber()) fail("KHR_lights_punctual: light index is not a number");
        const int li = lv.GetNumberAsInt();
        if (li < 0 || static_cast<std::size_t>(li) >= m_model.lights.size())
            fail("light index " + std::to_string(li) + " out of range (" + std::to_string(m_model.lights.size()) + " lights)");
        const tinygltf::Light& light = m_model.lights[static_cast<std::size_t>(li)];
        if (light.type != "point") {
            log_warning(m_name + ": light " + std::to_string(li) + " is a " + light.type + " light; only point lights are supported, skipped");
            return;
        }
        glm::vec3 color(1.0f);
        if (light.color.size() == 3)
            color = glm::vec3(static_cast<float>(light.color[0]), static_cast<float>(light.color[1]), static_cast<float>(light.color[2]));
        PointLight pl;
        pl.position = to_world.apply(Point3(0, 0, 0));
        pl.intensity = color * static_cast<float>(light.intensity);
        if (!is_finite(pl.position) || !std::isfinite(pl.intensity.x + pl.intensity.y + pl.intensity.z))
            fail("light " + std::to_string(li) + " has a non-finite position or intensity");
        m_scene.point_lights.push_back(pl);
    }

    static float number(const tinygltf::ExtensionMap& ext, const char* name, const char* key, float fallback)
    {
        const auto it = ext.find(name);
        if (it == ext.end() || !it->second.Has(key)) return fallback;
        const tinygltf::Value& v = it->second.Get(key);
        return v.IsNumber() ? static_cast<float>(v.GetNumberAsDouble()) : fallback;
    }

    Material convert_material(const tinygltf::Material& m, int index)
    {
        const std::string where = "material " + std::to_string(index) + (m.name.empty() ? "" : " '" + m.name + "'");
        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        Material out;
        out.name = m.name.empty() ? "material " + std::to_string(index) : m.name;
        out.type = MaterialType::Pbr;
        if (pbr.baseColorFactor.size() == 4) {
            out.albedo = glm::vec3(static_cast<float>(pbr.baseColorFactor[0]), static_cast<float>(pbr.baseColorFactor[1]),
                                   static_cast<float>(pbr.baseColorFactor[2]));
            out.opacity = static_cast<float>(pbr.baseColorFactor[3]);
        } else {
            out.albedo = glm::vec3(1.0f);
        }
        out.metallic = static_cast<float>(pbr.metallicFactor);
        out.roughness = static_cast<float>(pbr.roughnessFactor);
        if (m.emissiveFactor.size() == 3)
            out.emission = glm::vec3(static_cast<float>(m.emissiveFactor[0]), static_cast<float>(m.emissiveFactor[1]),
                                     static_cast<float>(m.emissiveFactor[2]));
        out.emission *= number(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength", 1.0f);
        out.ior = number(m.extensions, "KHR_materials_ior", "ior", 1.5f);
        out.transmission = number(m.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0f);
        out.double_sided = m.doubleSided;
        out.alpha_cutoff = static_cast<float>(m.alphaCutoff);
        if (m.alphaMode == "MASK") out.alpha_mode = AlphaMode::Mask;
        else if (m.alphaMode == "BLEND") out.alpha_mode = AlphaMode::Blend;
        else out.alpha_mode = AlphaMode::Opaque;

        const float values[] = {out.albedo.x, out.albedo.y, out.albedo.z, out.opacity, out.metallic, out.roughness,
                                out.emission.x, out.emission.y, out.emission.z, out.ior, out.transmission, out.alpha_cutoff};
        for (float v : values)
            if (!std::isfinite(v)) fail(where + ": non-finite factor");
        // Ranges the transmission lobe relies on (gc_bsdf.h): a rough one refracts with the ior.
        if (!(out.transmission >= 0.0f && out.transmission <= 1.0f))
            fail(where + ": KHR_materials_transmission transmissionFactor = " + std::to_string(out.transmission) +
                 " is outside [0, 1]");
        if (out.transmission > 0.0f && !(out.roughness >= 0.0f && out.roughness <= 1.0f))
            fail(where + ": pbrMetallicRoughness roughnessFactor = " + std::to_string(out.roughness) +
                 " is outside [0, 1] on a transmissive material");
        if (out.transmission > 0.0f && !(out.ior >= 1.0f))
            fail(where + ": KHR_materials_ior ior = " + std::to_string(out.ior) + " is below 1 on a transmissive material");

        out.albedo_texture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true, where);
        out.metallic_roughness_texture = texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, false, where);
        out.normal_texture = texture(m.normalTexture.index, m.normalTexture.texCoord, false, where);
        out.albedo_uv = uv_transform(pbr.baseColorTexture.extensions, where + ": baseColorTexture");
        out.metallic_roughness_uv = uv_transform(pbr.metallicRoughnessTexture.extensions, where + ": metallicRoughnessTexture");
        out.normal_uv = uv_transform(m.normalTexture.extensions, where + ": normalTexture");
        out.emission_uv = uv_transform(m.emissiveTexture.extensions, where + ": emissiveTexture");
        out.normal_scale = static_cast<float>(m.normalTexture.scale);
        if (!std::isfinite(out.normal_scale)) fail(where + ": non-finite normalTexture.scale");
        // What the renderer does not model is said once per material, not silently dropped.
        if (m.occlusionTexture.index >= 0)
            log_warning(m_name + ": " + where + ": occlusionTexture is ignored (a path tracer computes occlusion)");
        // Extensions the file declares in extensionsUsed get one warning for the whole file
        // (warn_unsupported_gltf_extensions); this catches the ones it forgot to declare.
        for (const auto& [ext, unused] : m.extensions)
            if (!gltf_extension_supported(ext) && !declared_as_used(ext))
                log_warning(m_name + ": " + where + ": extension " + ext + " is not supported; ignored");
        out.emission_texture = texture(m.emissiveTexture.index, m.emissiveTexture.texCoord, true, where);
        read_layers(m, where, out.layers);
        return out;
    }

    // The KHR_materials_* layers of material m (gltf_material_layers.h).
    void read_layers(const tinygltf::Material& m, const std::string& where, PbrLayers& layers)
    {
        const LayerTextureResolver resolve = [&](const tinygltf::Value& info, bool srgb, const std::string& slot) {
            TextureRef r;
            r.texture = texture(info.Get("index").GetNumberAsInt(), 0, srgb, where + ": " + slot);
            tinygltf::ExtensionMap extensions;
            if (info.Has("extensions") && info.Get("extensions").IsObject())
                for (const std::string& key : info.Get("extensions").Keys()) extensions[key] = info.Get("extensions").Get(key);
            r.uv = uv_transform(extensions, where + ": " + slot);
            return r;
        };
        const std::string context = m_name + ": " + where;
        if (const auto it = m.extensions.find("KHR_materials_clearcoat"); it != m.extensions.end())
            read_clearcoat(it->second, context, resolve, layers);
        if (const auto it = m.extensions.find("KHR_materials_transmission"); it != m.extensions.end())
            read_transmission_texture(it->second, context, resolve, layers);
        if (const auto it = m.extensions.find("KHR_materials_specular"); it != m.extensions.end())
            read_specular(it->second, context, resolve, layers);
        if (const auto it = m.extensions.find("KHR_materials_volume"); it != m.extensions.end())
            read_volume(it->second, context, layers);
        if (const auto it = m.extensions.find("KHR_materials_sheen"); it != m.extensions.end())
            read_sheen(it->second, context, resolve, layers);
    }

    // A textureInfo's KHR_texture_transform (identity without one). The spec gives no
    // fallback for malformed values, so they are refused, naming the slot; values that are
    // merely huge pass (the lookup reads texel 0 for coordinates past 1e7, gc_texture.h).
    UvTransform uv_transform(const tinygltf::ExtensionMap& extensions, const std::string& where) const
    {
        UvTransform t;
        const auto it = extensions.find("KHR_texture_transform");
        if (it == extensions.end()) return t;
        const tinygltf::Value& ext = it->second;
        const std::string ctx = where + ": KHR_texture_transform ";
        if (!ext.IsObject()) fail(ctx + "is not an object");
        auto vec2 = [&](const char* key, glm::vec2 fallback) {
            if (!ext.Has(key)) return fallback;
            const tinygltf::Value& v = ext.Get(key);
            if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
                fail(ctx + key + " is not an array of two numbers");
            const glm::vec2 out(static_cast<float>(v.Get(0).GetNumberAsDouble()), static_cast<float>(v.Get(1).GetNumberAsDouble()));
            if (!std::isfinite(out.x) || !std::isfinite(out.y)) fail(ctx + key + " is not finite (in float)");
            return out;
        };
        t.offset = vec2("offset", t.offset);
        t.scale = vec2("scale", t.scale);
        if (ext.Has("rotation")) {
            const tinygltf::Value& v = ext.Get("rotation");
            if (!v.IsNumber()) fail(ctx + "rotation is not a number");
            t.rotation = static_cast<float>(v.GetNumberAsDouble());
            if (!std::isfinite(t.rotation)) fail(ctx + "rotation is not finite (in float)");
        }
        return t;
    }

    // The TEXCOORD set a textureInfo reads: KHR_texture_transform's texCoord overrides the
    // textureInfo's own.
    int tex_coord(const tinygltf::ExtensionMap& extensions, int own, int material) const
    {
        const auto it = extensions.find("KHR_texture_transform");
        if (it == extensions.end() || !it->second.IsObject() || !it->second.Has("texCoord")) return own;
        const tinygltf::Value& v = it->second.Get("texCoord");
        const double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
        if (!(d >= 0.0 && d <= 31.0) || d != std::floor(d))
            fail("material " + std::to_string(material) + ": KHR_texture_transform texCoord is not an integer in [0, 31]");
        return static_cast<int>(d);
    }

    bool declared_as_used(const std::string& extension) const
    {
        const std::vector<std::string>& used = m_model.extensionsUsed;
        return std::find(used.begin(), used.end(), extension) != used.end();
    }

    static WrapMode wrap(int mode)
    {
        switch (mode) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return WrapMode::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return WrapMode::MirroredRepeat;
        default: return WrapMode::Repeat;
        }
    }

    // The texture-coordinate set a material's textures read. The device stores one uv set per
    // triangle, so a material whose textures name different sets gets the base colour's (else
    // the first textured slot's), with a warning.
    int uv_set(const tinygltf::Material& m, int index)
    {
        const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
        const std::pair<int, int> slots[] = {
            {pbr.baseColorTexture.index, tex_coord(pbr.baseColorTexture.extensions, pbr.baseColorTexture.texCoord, index)},
            {pbr.metallicRoughnessTexture.index,
             tex_coord(pbr.metallicRoughnessTexture.extensions, pbr.metallicRoughnessTexture.texCoord, index)},
            {m.normalTexture.index, tex_coord(m.normalTexture.extensions, m.normalTexture.texCoord, index)},
            {m.emissiveTexture.index, tex_coord(m.emissiveTexture.extensions, m.emissiveTexture.texCoord, index)}};
        int chosen = 0;
        bool found = false;
        bool mixed = false;
        for (const auto& [tex, set] : slots) {
            if (tex < 0) continue;
            if (!found) chosen = set;
            else if (set != chosen) mixed = true;
            found = true;
        }
        if (chosen < 0 || chosen > 31)
            fail("material " + std::to_string(index) + ": texCoord " + std::to_string(chosen) + " out of range");
        if (mixed)
            log_warning(m_name + ": material " + std::to_string(index) + ": its textures read different TEXCOORD sets; only one "
                        "set per triangle is kept, so all use TEXCOORD_" + std::to_string(chosen));
        return chosen;
    }

    // Scene texture for glTF texture `index`, decoded once per colour space.
    int texture(int index, int /*tex_coord: see uv_set*/, bool srgb, const std::string& where)
    {
        if (index < 0) return -1;
        if (static_cast<std::size_t>(index) >= m_model.textures.size())
            fail(where + ": texture " + std::to_string(index) + " out of range (" + std::to_string(m_model.textures.size()) + " textures)");
        const auto key = std::make_pair(index, srgb);
        if (const auto found = m_textures.find(key); found != m_textures.end()) return found->second;

        const tinygltf::Texture& tex = m_model.textures[static_cast<std::size_t>(index)];
        if (tex.source < 0 || static_cast<std::size_t>(tex.source) >= m_model.images.size())
            fail("texture " + std::to_string(index) + ": image " + std::to_string(tex.source) + " out of range (" +
                 std::to_string(m_model.images.size()) + " images)");
        const tinygltf::Image& img = m_model.images[static_cast<std::size_t>(tex.source)];
        const std::string img_name = "image " + std::to_string(tex.source) + (img.uri.empty() ? "" : " '" + img.uri + "'");
        // tinygltf only warns when an external image is missing or unreadable and leaves it empty.
        if (img.image.empty() && !img.uri.empty()) {
            const std::string why = m_files.why_not_read(img.uri);
            fail(img_name + ": " + (why.empty() ? std::string("could not be read") : why) + " (relative to the scene's folder)");
        }
        if (img.width <= 0 || img.height <= 0 || img.component < 1 || img.component > 4 || (img.bits != 8 && img.bits != 16))
            fail(img_name + ": not decoded (" + std::to_string(img.width) + "x" + std::to_string(img.height) + ", " +
                 std::to_string(img.component) + " channels, " + std::to_string(img.bits) + " bits)");
        const std::size_t need = static_cast<std::size_t>(img.width) * static_cast<std::size_t>(img.height) *
                                 static_cast<std::size_t>(img.component) * static_cast<std::size_t>(img.bits / 8);
        if (img.image.size() < need)
            fail(img_name + ": " + std::to_string(img.image.size()) + " bytes of pixels, " + std::to_string(need) + " needed");

        Texture t;
        t.name = m_name + " " + img_name;
        t.width = img.width;
        t.height = img.height;
        t.srgb = srgb;
        t.texels = pack_rgba8(img.image.data(), img.width, img.height, img.component, img.bits);
        if (tex.sampler >= 0) {
            if (static_cast<std::size_t>(tex.sampler) >= m_model.samplers.size())
                fail("texture " + std::to_string(index) + ": sampler " + std::to_string(tex.sampler) + " out of range");
            const tinygltf::Sampler& s = m_model.samplers[static_cast<std::size_t>(tex.sampler)];
            t.wrap_s = wrap(s.wrapS);
            t.wrap_t = wrap(s.wrapT);
            t.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        }
        m_scene.textures.push_back(std::move(t));
        const int out = static_cast<int>(m_scene.textures.size() - 1);
        m_textures.emplace(key, out);
        return out;
    }

    std::uint32_t default_material()
    {
        if (!m_default) {
            m_default = static_cast<std::uint32_t>(m_scene.materials.size());
            m_scene.materials.push_back(Material{});
        }
        return *m_default;
    }

    const tinygltf::Model& m_model;
    const std::string& m_name;
    const GltfFileLog& m_files;
    Scene& m_scene;
    std::optional<std::uint32_t> m_default;
    std::map<std::pair<int, bool>, int> m_textures;
    std::set<int> m_warned_modes;
    std::uint64_t m_planned_triangles = 0; // over every mesh instance so far
    std::uint64_t m_instances = 0;
    InstancedScene* m_instanced = nullptr;
    static constexpr std::uint32_t kNoMesh = 0xffffffffu;
    std::map<int, std::uint32_t> m_mesh_ids; // glTF mesh -> InstancedScene mesh (instanced mode)
    std::vector<int> m_uv_sets; // per glTF material: the TEXCOORD_n its textures read
};

// tinygltf's messages can quote bytes of a garbage file ("last read: '...'"): keep valid
// UTF-8 and printable ASCII, show anything else as \xNN, and drop trailing newlines.
std::string printable(const std::string& s)
{
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (std::size_t i = 0; i < s.size();) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        std::size_t len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
        bool ok = len > 0 && i + len <= s.size() && (len > 1 || c >= 0x20 || c == '\n') && c != 0x7f;
        for (std::size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(s[i + k]) >> 6) == 0x2;
        if (ok) {
            out.append(s, i, len);
            i += len;
        } else {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 0xf];
            ++i;
        }
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
}

void forward_warnings(const std::string& warn, const std::string& name)
{
    std::istringstream lines(warn);
    std::string line;
    while (std::getline(lines, line))
        if (!line.empty()) log_warning(name + ": " + printable(line));
}

}  // namespace

namespace {

// load_gltf and load_gltf_instanced: the file read, checked and converted; `instanced` as
// GltfConverter takes it.
// With `only_where_reused` set, `instanced` is used only when the scene's nodes draw a mesh
// more than once, and *only_where_reused says whether it was.
Scene convert_gltf(const std::filesystem::path& path, const LoadOptions& options, InstancedScene* instanced,
                   bool* only_where_reused = nullptr)
{
    const std::string name = path.string();
    const std::vector<unsigned char> bytes = read_regular_file(path);
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw InputError(name + ": larger than 4 GiB");
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    std::string ext = path.extension().string();
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (ext == ".glb" || binary) check_glb_container(bytes.data(), bytes.size(), name);
    if (bytes.empty()) throw InputError(name + ": empty file");
    const std::string_view json_text =
        binary ? glb_json_chunk(bytes.data(), bytes.size())
               : std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (const std::optional<GltfDeclarations> declared = read_gltf_declarations(json_text))
        check_gltf_declarations(*declared, name);

    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    install_checked_image_decoder(loader, model);
    GltfFileLog files;
    install_regular_file_access(loader, files);
    std::string err, warn;
    const std::string base_dir = path.parent_path().empty() ? std::string(".") : path.parent_path().string();
    const unsigned int size = static_cast<unsigned int>(bytes.size());
    const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes.data(), size, base_dir)
                           : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                                        size, base_dir);
    if (!ok || !err.empty()) {
        std::string why = printable(err);
        if (why.empty()) why = printable(warn);
        throw InputError(name + ": cannot load glTF: " + (why.empty() ? std::string("tinygltf gave no reason") : why));
    }

    int scene_index = -1;
    if (!model.scenes.empty()) {
        scene_index = options.gltf_scene >= 0 ? options.gltf_scene : (model.defaultScene >= 0 ? model.defaultScene : 0);
        if (static_cast<std::size_t>(scene_index) >= model.scenes.size())
            throw InputError(name + ": scene " + std::to_string(scene_index) + " requested, but the file has " +
                             std::to_string(model.scenes.size()) + " scene(s)");
    } else if (options.gltf_scene > 0) {
        throw InputError(name + ": scene " + std::to_string(options.gltf_scene) + " requested, but the file defines no scenes");
    }

    Scene scene;
    scene.source_path = name;
    if (only_where_reused) {
        *only_where_reused = reuses_a_mesh(model, scene_index);
        if (!*only_where_reused) instanced = nullptr;
    }
    GltfConverter converter(model, name, files, scene, instanced);
    converter.convert_materials();
    converter.convert_scene(scene_index);
    // tinygltf's warnings only once the scene is known to load: when it does not, the error
    // already carries the reason (a missing image is a warning to tinygltf).
    forward_warnings(warn, name);
    warn_unsupported_gltf_extensions(model.extensionsUsed, name);
    if (scene.triangle_count() == 0) throw InputError(name + ": no triangles");
    if (scene.materials.empty()) scene.materials.push_back(Material{});
    return scene;
}

}  // namespace

Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options)
{
    return convert_gltf(path, options, nullptr);
}

InstancedScene load_gltf_instanced(const std::filesystem::path& path, const LoadOptions& options)
{
    InstancedScene out;
    out.meshes = convert_gltf(path, options, &out);
    validate_instances(out);
    return out;
}

std::variant<Scene, InstancedScene> load_gltf_instanced_where_reused(const std::filesystem::path& path,
                                                                     const LoadOptions& options)
{
    InstancedScene out;
    bool reused = false;
    Scene scene = convert_gltf(path, options, &out, &reused);
    if (!reused) return scene;
    out.meshes = std::move(scene);
    validate_instances(out);
    return out;
}

}  // namespace gc
