#include "host/bvh/instance_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "host/bvh/bvh.h"
#include "host/bvh/widen.h"

namespace gc {
namespace {

// Mesh `r` of `src` as a scene of its own (the builder's input), materials and all.
Scene mesh_scene(const Scene& src, const MeshRange& r)
{
    Scene s;
    s.materials = src.materials;
    s.source_path = src.source_path;
    const std::size_t b = r.first_triangle;
    const std::size_t e = b + r.triangle_count;
    s.positions.assign(src.positions.begin() + 3 * b, src.positions.begin() + 3 * e);
    s.normals.assign(src.normals.begin() + 3 * b, src.normals.begin() + 3 * e);
    if (!src.uvs.empty()) s.uvs.assign(src.uvs.begin() + 3 * b, src.uvs.begin() + 3 * e);
    s.material_ids.assign(src.material_ids.begin() + b, src.material_ids.begin() + e);
    s.has_vertex_normals.assign(src.has_vertex_normals.begin() + b, src.has_vertex_normals.begin() + e);
    return s;
}

// The instance's world box: the mesh box's eight corners through the transform in double,
// widened by 2^-16 of its largest coordinate and rounded outward to float. The object-space
// ray carries the rounding of its own transform, so its hits may lie a little outside the
// exact world box; the widening keeps the top level from culling them (it is far above the
// few ulps the transform rounds by, and costs only a sliver of extra box hits).
void world_box(const glm::mat4& m, const Bounds3& object, float lo[3], float hi[3])
{
    const glm::dmat4 md(m);
    glm::dvec3 l(std::numeric_limits<double>::infinity());
    glm::dvec3 h(-std::numeric_limits<double>::infinity());
    for (int c = 0; c < 8; ++c) {
        const glm::dvec4 p((c & 1) ? object.hi.x : object.lo.x, (c & 2) ? object.hi.y : object.lo.y,
                           (c & 4) ? object.hi.z : object.lo.z, 1.0);
        const glm::dvec3 w(md * p);
        l = glm::min(l, w);
        h = glm::max(h, w);
    }
    double extent = 0.0;
    for (int a = 0; a < 3; ++a) extent = std::max({extent, std::fabs(l[a]), std::fabs(h[a])});
    const double pad = extent * 0x1p-16;
    for (int a = 0; a < 3; ++a) {
        lo[a] = std::nextafter(static_cast<float>(l[a] - pad), -std::numeric_limits<float>::infinity());
        hi[a] = std::nextafter(static_cast<float>(h[a] + pad), std::numeric_limits<float>::infinity());
    }
}

std::uint32_t prim_of(const dev::GcTriangle& t) { return dev::gc_as_uint(t.v0.w); }

// Renumbers a mesh tree's triangles from mesh-local to scene-of-meshes indices (the
// empty-tree dummy, GC_INVALID, stays as it is).
void offset_prims(FlatBvh& bvh, std::uint32_t first)
{
    for (dev::GcTriangle& t : bvh.triangles)
        if (prim_of(t) != GC_INVALID) t.v0.w = dev::gc_as_float(prim_of(t) + first);
}

std::uint32_t checked_u32(std::size_t n, const char* what)
{
    if (n > std::numeric_limits<std::uint32_t>::max() - 1u)
        throw std::length_error(std::string("instanced BVH: too many ") + what + " for 32-bit indices");
    return static_cast<std::uint32_t>(n);
}

// Concatenates per-mesh (nodes, tris) and sets each instance's bases to its mesh's.
template <class Node, class Tri, class Layout>
InstancedBvhOf<Node, Tri> assemble(const InstanceBvhParts& parts, Layout lay_out)
{
    InstancedBvhOf<Node, Tri> out;
    out.tlas = parts.tlas;
    out.instances = parts.instances;
    std::vector<std::uint32_t> node_base(parts.meshes.size());
    std::vector<std::uint32_t> tri_base(parts.meshes.size());
    for (std::size_t m = 0; m < parts.meshes.size(); ++m) {
        const auto [nodes, tris] = lay_out(parts.meshes[m]);
        node_base[m] = checked_u32(out.nodes.size(), "nodes");
        tri_base[m] = checked_u32(out.tris.size(), "triangles");
        out.nodes.insert(out.nodes.end(), nodes.begin(), nodes.end());
        out.tris.insert(out.tris.end(), tris.begin(), tris.end());
    }
    for (dev::GcInstance& inst : out.instances) {
        if (inst.id == GC_INVALID) continue;  // the empty scene's dummy
        inst.node_base = node_base[inst.mesh];
        inst.tri_base = tri_base[inst.mesh];
    }
    if (out.nodes.empty()) {  // no meshes: one empty tree keeps the buffers non-empty
        const FlatBvh empty = flatten(BvhTree{}, Scene{});
        const auto [nodes, tris] = lay_out(empty);
        out.nodes.assign(nodes.begin(), nodes.end());
        out.tris.assign(tris.begin(), tris.end());
    }
    return out;
}

}  // namespace

InstanceBvhParts build_instance_bvh(const InstancedScene& scene, const BvhBuildOptions& options)
{
    InstanceBvhParts parts;
    std::vector<Bounds3> mesh_bounds;
    for (const MeshRange& r : scene.mesh_ranges) {
        const Scene mesh = mesh_scene(scene.meshes, r);
        mesh_bounds.push_back(mesh.bounds());
        parts.meshes.push_back(build_bvh(mesh, options));
        offset_prims(parts.meshes.back(), r.first_triangle);
    }

    // The top level: one degenerate "triangle" per instance spanning its world box (corners
    // lo, hi, lo), which is all the builder reads; flatten's triangle order is the leaf order.
    Scene boxes;
    boxes.source_path = scene.meshes.source_path;
    boxes.materials.resize(1);
    const std::size_t n = scene.instances.size();
    boxes.positions.resize(3 * n);
    boxes.normals.assign(3 * n, Normal3(0.0f, 0.0f, 1.0f));
    boxes.material_ids.assign(n, 0u);
    boxes.has_vertex_normals.assign(n, 0u);
    for (std::size_t i = 0; i < n; ++i) {
        const Instance& inst = scene.instances[i];
        if (inst.mesh >= scene.mesh_ranges.size()) throw std::logic_error("build_instance_bvh: run validate_instances first");
        float lo[3];
        float hi[3];
        world_box(inst.object_to_world, mesh_bounds[inst.mesh], lo, hi);
        boxes.positions[3 * i] = Point3(lo[0], lo[1], lo[2]);
        boxes.positions[3 * i + 1] = Point3(hi[0], hi[1], hi[2]);
        boxes.positions[3 * i + 2] = Point3(lo[0], lo[1], lo[2]);
    }
    BvhBuildOptions top = options;
    top.max_leaf_size = 2;
    top.intersection_cost = 4.0f;
    const FlatBvh tlas = build_bvh(boxes, top);
    parts.tlas = tlas.nodes;

    parts.instances.resize(tlas.triangles.size());
    for (std::size_t k = 0; k < tlas.triangles.size(); ++k) {
        dev::GcInstance& d = parts.instances[k];
        const std::uint32_t id = prim_of(tlas.triangles[k]);
        d.id = id;
        d.mesh = 0u;
        d.node_base = 0u;
        d.tri_base = 0u;
        const glm::mat4 w = id == GC_INVALID ? glm::mat4(1.0f) : world_to_object(scene.instances[id].object_to_world);
        if (id != GC_INVALID) d.mesh = scene.instances[id].mesh;
        // glm is column-major: row r is (w[0][r], w[1][r], w[2][r], w[3][r]).
        dev::float4* rows[3] = {&d.row0, &d.row1, &d.row2};
        for (int r = 0; r < 3; ++r) *rows[r] = dev::make_float4(w[0][r], w[1][r], w[2][r], w[3][r]);
    }
    return parts;
}

InstancedBvh assemble_binary(const InstanceBvhParts& parts)
{
    return assemble<dev::GcBvhNode, dev::GcTriangle>(parts, [](const FlatBvh& b) {
        return std::pair<const BigArray<dev::GcBvhNode>&, const BigArray<dev::GcTriangle>&>(b.nodes, b.triangles);
    });
}

InstancedBvh4 assemble_wide(const InstanceBvhParts& parts)
{
    return assemble<dev::GcBvh4Node, dev::GcTriangle4>(parts, [](const FlatBvh& b) {
        WideBvh w = widen(b);
        return std::pair<BigArray<dev::GcBvh4Node>, BigArray<dev::GcTriangle4>>(std::move(w.nodes), std::move(w.blocks));
    });
}

InstancedBvh8 assemble_wide8(const InstanceBvhParts& parts)
{
    return assemble<dev::GcBvh8Node, dev::GcTriangle4>(parts, [](const FlatBvh& b) {
        Wide8Bvh w = widen8(b);
        return std::pair<BigArray<dev::GcBvh8Node>, BigArray<dev::GcTriangle4>>(std::move(w.nodes), std::move(w.blocks));
    });
}

}  // namespace gc
