#include "host/bvh/flatten.h"

#include <bit>
#include <limits>
#include <utility>

#include "gc_accessors.h"

namespace gc {
namespace {

dev::GcBvhNode make_node(const float* lo, const float* hi, std::uint32_t first, std::uint32_t count)
{
    dev::GcBvhNode node;
    node.lo = dev::float4(lo[0], lo[1], lo[2], std::bit_cast<float>(first));
    node.hi = dev::float4(hi[0], hi[1], hi[2], std::bit_cast<float>(count));
    return node;
}

dev::GcTriangle make_triangle(const Point3& v0, const Point3& v1, const Point3& v2, std::uint32_t prim)
{
    dev::GcTriangle tri;
    tri.v0 = dev::float4(v0.x, v0.y, v0.z, std::bit_cast<float>(prim));
    tri.v1 = dev::float4(v1.x, v1.y, v1.z, 0.0f);
    tri.v2 = dev::float4(v2.x, v2.y, v2.z, 0.0f);
    return tri;
}

FlatBvh empty_bvh()
{
    constexpr float inf = std::numeric_limits<float>::infinity();
    const float lo[3] = {inf, inf, inf};
    const float hi[3] = {-inf, -inf, -inf};
    FlatBvh flat;
    flat.nodes.push_back(make_node(lo, hi, 0, 1));
    flat.triangles.push_back(make_triangle(Point3(), Point3(), Point3(), GC_INVALID));
    return flat;
}

}  // namespace

std::size_t FlatBvh::scene_triangle_count() const
{
    if (triangles.size() == 1 && dev::gc_triangle_prim(triangles[0]) == GC_INVALID) return 0;
    return triangles.size();
}

FlatBvh flatten(const BvhTree& tree, const Scene& scene)
{
    if (tree.nodes.empty()) return empty_bvh();

    FlatBvh flat;
    flat.nodes.reserve(tree.nodes.size());
    flat.triangles.reserve(tree.prim_indices.size());
    flat.nodes.emplace_back();

    // Pre-order walk with an explicit stack of (tree node, output slot). An inner node
    // reserves its children's pair when it is visited; pushing right before left makes the
    // left subtree complete before the right child's pair is reserved.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;
    stack.emplace_back(0u, 0u);
    while (!stack.empty()) {
        const auto [src, dst] = stack.back();
        stack.pop_back();
        const BvhBuildNode& node = tree.nodes[src];
        if (node.count > 0) {
            const auto first = static_cast<std::uint32_t>(flat.triangles.size());
            for (std::uint32_t i = 0; i < node.count; ++i) {
                const std::uint32_t prim = tree.prim_indices[node.first + i];
                flat.triangles.push_back(
                    make_triangle(scene.vertex(prim, 0), scene.vertex(prim, 1), scene.vertex(prim, 2), prim));
            }
            flat.nodes[dst] = make_node(node.lo, node.hi, first, node.count);
        } else {
            const auto pair = static_cast<std::uint32_t>(flat.nodes.size());
            flat.nodes.resize(flat.nodes.size() + 2);
            flat.nodes[dst] = make_node(node.lo, node.hi, pair, 0);
            stack.emplace_back(node.first + 1, pair + 1);
            stack.emplace_back(node.first, pair);
        }
    }
    return flat;
}

}  // namespace gc
