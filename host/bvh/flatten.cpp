#include "host/bvh/flatten.h"

#include <algorithm>
#include <bit>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "gc_accessors.h"
#include "host/util/host_threads.h"

namespace gc {
namespace {

dev::GcBvhNode make_node(const float* lo, const float* hi, std::uint32_t first, std::uint32_t count)
{
    dev::GcBvhNode node;
    node.lo = dev::float4(lo[0], lo[1], lo[2], std::bit_cast<float>(first));
    node.hi = dev::float4(hi[0], hi[1], hi[2], std::bit_cast<float>(count));
    return node;
}

dev::GcTriangle make_triangle(const Point3& v0, const Point3& v1, const Point3& v2, std::uint32_t prim,
                              std::uint32_t flags = 0u)
{
    dev::GcTriangle tri;
    tri.v0 = dev::float4(v0.x, v0.y, v0.z, std::bit_cast<float>(prim));
    tri.v1 = dev::float4(v1.x, v1.y, v1.z, std::bit_cast<float>(flags));
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

constexpr std::size_t kTriangleChunk = 65536; // below this a thread costs more than it saves

// Triangle i of the flat layout is scene triangle prim_indices[i] (see flatten()), made on up
// to `max_threads` threads. Each is a pure function of the scene, so chunks on several threads
// give the same bytes as one loop.
void make_triangles(const BvhTree& tree, const Scene& scene, BigArray<dev::GcTriangle>& out, std::size_t max_threads)
{
    const std::size_t n = tree.prim_indices.size();
    out.resize(n);
    auto fill = [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
            const std::uint32_t prim = tree.prim_indices[i];
            const std::uint32_t flags = triangle_alpha_tested(scene, prim) ? GC_TRI_ALPHA_TESTED : 0u;
            out[i] = make_triangle(scene.vertex(prim, 0), scene.vertex(prim, 1), scene.vertex(prim, 2), prim, flags);
        }
    };
    const std::size_t threads =
        std::min<std::size_t>(std::max<std::size_t>(1, max_threads), (n + kTriangleChunk - 1) / kTriangleChunk);
    std::vector<std::thread> workers;
    for (std::size_t t = 1; t < threads; ++t) workers.emplace_back(fill, n * t / threads, n * (t + 1) / threads);
    fill(0, n / threads);
    for (std::thread& w : workers) w.join();
}

// The nodes in depth-first order: a pre-order walk with an explicit stack of (tree node,
// output slot). An inner node reserves its children's pair when it is visited; pushing right
// before left makes the left subtree complete before the right child's pair is reserved. The
// builder lays leaves' ranges of prim_indices out in the same order (a left subtree's range
// before its right sibling's), so the triangles are prim_indices' order, made apart from this
// walk; the walk checks that promise leaf by leaf.
BigArray<dev::GcBvhNode> flatten_nodes(const BvhTree& tree)
{
    BigArray<dev::GcBvhNode> nodes;
    nodes.reserve(tree.nodes.size());
    nodes.emplace_back();
    std::uint32_t next_triangle = 0;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> stack;
    stack.emplace_back(0u, 0u);
    while (!stack.empty()) {
        const auto [src, dst] = stack.back();
        stack.pop_back();
        const BvhBuildNode& node = tree.nodes[src];
        if (node.count > 0) {
            if (node.first != next_triangle)
                throw std::logic_error("flatten: BVH leaf over triangles " + std::to_string(node.first) +
                                       " is not in depth-first order (expected " + std::to_string(next_triangle) +
                                       "); host/bvh/builder.cpp broke its BvhTree promise");
            next_triangle += node.count;
            nodes[dst] = make_node(node.lo, node.hi, node.first, node.count);
        } else {
            const auto pair = static_cast<std::uint32_t>(nodes.size());
            nodes.resize(nodes.size() + 2);
            nodes[dst] = make_node(node.lo, node.hi, pair, 0);
            stack.emplace_back(node.first + 1, pair + 1);
            stack.emplace_back(node.first, pair);
        }
    }
    return nodes;
}

}  // namespace

bool triangle_alpha_tested(const Scene& scene, std::size_t tri)
{
    const Material& m = scene.materials[scene.material_ids[tri]];
    return m.alpha_mode == AlphaMode::Mask && (m.albedo_texture >= 0 || !(m.opacity >= m.alpha_cutoff));
}

std::size_t FlatBvh::scene_triangle_count() const
{
    if (triangles.size() == 1 && dev::gc_triangle_prim(triangles[0]) == GC_INVALID) return 0;
    return triangles.size();
}

FlatBvh flatten(const BvhTree& tree, const Scene& scene)
{
    if (tree.nodes.empty()) return empty_bvh();

    // The node walk is serial and needs nothing from the triangles, so for a large scene the
    // triangles are made on the other cores meanwhile. 5.2M triangles on 2 cores: 0.35-0.44 s
    // one after the other (1.0 core busy on average), 0.22-0.25 s overlapped.
    FlatBvh flat;
    const auto cores = static_cast<std::size_t>(host_thread_count());
    if (cores < 2 || tree.prim_indices.size() < kTriangleChunk) {
        make_triangles(tree, scene, flat.triangles, cores);
        flat.nodes = flatten_nodes(tree);
        return flat;
    }
    std::exception_ptr triangle_error;
    std::thread triangles([&] {
        try {
            make_triangles(tree, scene, flat.triangles, cores - 1);
        } catch (...) {
            triangle_error = std::current_exception();
        }
    });
    try {
        flat.nodes = flatten_nodes(tree);
    } catch (...) {
        triangles.join();
        throw;
    }
    triangles.join();
    if (triangle_error) std::rethrow_exception(triangle_error);
    return flat;
}

}  // namespace gc
