#include "host/scene/instances.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "host/scene/scene_checks.h"
#include "host/util/error.h"

namespace gc {
namespace {

bool is_finite_affine(const glm::mat4& m)
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return m[0][3] == 0.0f && m[1][3] == 0.0f && m[2][3] == 0.0f && m[3][3] == 1.0f;
}

// (m0 x + m1 y) + m2 z + m3 w per coordinate: the order gc_instance.h uses on the device.
glm::vec3 apply(const glm::mat4& m, const glm::vec3& p, float w)
{
    glm::vec3 out;
    for (int r = 0; r < 3; ++r) out[r] = ((m[0][r] * p.x + m[1][r] * p.y) + m[2][r] * p.z) + m[3][r] * w;
    return out;
}

Normal3 unit_or_zero(const glm::vec3& v)
{
    const float len = glm::length(v);
    return len > 0.0f && std::isfinite(len) ? Normal3(v / len) : Normal3(0.0f, 0.0f, 0.0f);
}

}  // namespace

std::size_t InstancedScene::instanced_triangle_count() const
{
    std::size_t total = 0;
    for (const Instance& inst : instances)
        if (inst.mesh < mesh_ranges.size()) total += mesh_ranges[inst.mesh].triangle_count;
    return total;
}

void validate_instances(const InstancedScene& scene)
{
    const std::string file = scene.meshes.name_for_messages();
    const std::size_t tris = scene.meshes.triangle_count();
    for (std::size_t m = 0; m < scene.mesh_ranges.size(); ++m) {
        const MeshRange& r = scene.mesh_ranges[m];
        if (r.triangle_count == 0 || std::size_t{r.first_triangle} + r.triangle_count > tris)
            throw InputError(file + ": mesh " + std::to_string(m) + " spans triangles " +
                             std::to_string(r.first_triangle) + " + " + std::to_string(r.triangle_count) +
                             ", but the scene has " + std::to_string(tris) + " (a mesh must be non-empty and inside)");
    }
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        if (inst.mesh >= scene.mesh_ranges.size())
            throw InputError(file + ": instance " + std::to_string(i) + " refers to mesh " + std::to_string(inst.mesh) +
                             ", but there are " + std::to_string(scene.mesh_ranges.size()) + " meshes");
        const double det = glm::determinant(glm::dmat3(glm::dmat4(inst.object_to_world)));
        if (!is_finite_affine(inst.object_to_world) || !(std::fabs(det) > 0.0) || !std::isfinite(det))
            throw InputError(file + ": instance " + std::to_string(i) +
                             " has a transform that is not a finite, invertible affine map");
    }
}

namespace {

// Appends triangles `first` .. `end` of `src` (one instance's, in mesh order, or the ones
// `pick` lists when given) through the instance's transform `m` to `out`, in world space (see
// flatten_instances for the arithmetic and `winding`).
void append_instance(Scene& out, const Scene& src, std::uint32_t first, std::uint32_t end, const glm::mat4& m,
                     MirroredWinding winding, const std::vector<std::uint32_t>* pick = nullptr)
{
    const glm::mat3 normal_map = glm::transpose(glm::mat3(world_to_object(m)));
    const bool swap = winding == MirroredWinding::FrontStaysFront && glm::determinant(glm::mat3(m)) < 0.0f;
    static constexpr int kKept[3] = {0, 1, 2};
    static constexpr int kSwapped[3] = {0, 2, 1};
    const int* corners = swap ? kSwapped : kKept;
    for (std::uint32_t i = first; i < end; ++i) {
        const std::uint32_t t = pick ? (*pick)[i] : i;
        for (int c : {corners[0], corners[1], corners[2]}) {
            const std::size_t k = 3 * std::size_t{t} + c;
            out.positions.push_back(Point3(apply(m, src.positions[k].glm(), 1.0f)));
            out.normals.push_back(unit_or_zero(normal_map * src.normals[k].glm()));
            if (!src.uvs.empty()) out.uvs.push_back(src.uvs[k]);
            if (!src.tangents.empty()) {
                const glm::vec4 tg = src.tangents[k];
                const Normal3 dir = unit_or_zero(apply(m, glm::vec3(tg), 0.0f));
                out.tangents.push_back(glm::vec4(dir.x, dir.y, dir.z, swap ? -tg.w : tg.w));
            }
        }
        out.material_ids.push_back(src.material_ids[t]);
        out.has_vertex_normals.push_back(src.has_vertex_normals[t]);
    }
}

}  // namespace

Scene flatten_instances(const InstancedScene& scene, MirroredWinding winding)
{
    validate_instances(scene);
    const std::size_t total = scene.instanced_triangle_count();
    if (std::string why; !flat_triangles_fit(total, why))
        throw InputError(scene.meshes.name_for_messages() + ": its " + std::to_string(scene.instances.size()) +
                         " instances draw " + std::to_string(total) + " triangles; copied out flat they would need " +
                         why);
    const Scene& src = scene.meshes;
    Scene out;
    out.materials = src.materials;
    out.textures = src.textures;
    out.point_lights = src.point_lights;
    out.camera = src.camera;
    out.source_path = src.source_path;
    out.positions.reserve(3 * total);
    out.normals.reserve(3 * total);
    out.material_ids.reserve(total);
    out.has_vertex_normals.reserve(total);
    if (!src.uvs.empty()) out.uvs.reserve(3 * total);
    if (!src.tangents.empty()) out.tangents.reserve(3 * total);
    for (const Instance& inst : scene.instances) {
        const MeshRange& r = scene.mesh_ranges[inst.mesh];
        append_instance(out, src, r.first_triangle, r.first_triangle + r.triangle_count, inst.object_to_world, winding);
    }
    return out;
}

Scene with_world_emitters(const InstancedScene& scene)
{
    validate_instances(scene);
    Scene out = scene.meshes;
    const Scene& src = scene.meshes;
    // Each mesh's emissive triangles, listed once: a million instances of a mesh without one
    // then cost a million empty appends, not a look at every triangle they draw.
    const std::vector<std::uint32_t> emissive = src.emissive_triangles();
    std::vector<std::uint32_t> first(scene.mesh_ranges.size()), end(scene.mesh_ranges.size());
    for (std::size_t m = 0; m < scene.mesh_ranges.size(); ++m) {
        const MeshRange& r = scene.mesh_ranges[m];
        const auto lo = std::lower_bound(emissive.begin(), emissive.end(), r.first_triangle);
        const auto hi = std::lower_bound(lo, emissive.end(), r.first_triangle + r.triangle_count);
        first[m] = static_cast<std::uint32_t>(lo - emissive.begin());
        end[m] = static_cast<std::uint32_t>(hi - emissive.begin());
    }
    std::uint64_t drawn = 0;
    for (const Instance& inst : scene.instances) drawn += end[inst.mesh] - first[inst.mesh];
    if (std::string why; !flat_triangles_fit(src.triangle_count() + drawn, why))
        throw InputError(src.name_for_messages() + ": its instances draw " + std::to_string(drawn) +
                         " emissive triangles, each kept in world space for light sampling, which would need " + why);
    for (const Instance& inst : scene.instances)
        if (first[inst.mesh] < end[inst.mesh])
            append_instance(out, src, first[inst.mesh], end[inst.mesh], inst.object_to_world,
                            MirroredWinding::FrontStaysFront, &emissive);
    return out;
}

Bounds3 world_bounds(const InstancedScene& scene)
{
    std::vector<Bounds3> mesh_bounds(scene.mesh_ranges.size());
    for (std::size_t m = 0; m < scene.mesh_ranges.size(); ++m) {
        const MeshRange& r = scene.mesh_ranges[m];
        for (std::size_t k = 3 * std::size_t{r.first_triangle}; k < 3 * std::size_t{r.first_triangle + r.triangle_count}; ++k)
            mesh_bounds[m] = unite(mesh_bounds[m], scene.meshes.positions[k]);
    }
    Bounds3 b;
    for (const Instance& inst : scene.instances) {
        const Bounds3& mb = mesh_bounds[inst.mesh];
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p((corner & 1) ? mb.hi.x : mb.lo.x, (corner & 2) ? mb.hi.y : mb.lo.y,
                              (corner & 4) ? mb.hi.z : mb.lo.z);
            b = unite(b, Point3(apply(inst.object_to_world, p, 1.0f)));
        }
    }
    return b;
}

}  // namespace gc
