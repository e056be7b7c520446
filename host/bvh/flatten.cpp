#include "host/bvh/flatten.h"

#include <algorithm>
#include <bit>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>
#include <utility>

#include "gc_accessors.h"
#include "host/bvh/task_pool.h"
#include "host/util/error.h"
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

constexpr std::size_t kTriangleChunk = 16384; // below this a thread costs more than it saves
// Trees with fewer nodes are walked on one thread.
constexpr std::size_t kParallelNodes = std::size_t{1} << 16;
// The parallel walk hands out the subtrees below this depth (at most 2^8 of them).
constexpr std::uint32_t kCutDepth = 8;

// Triangle i of the flat layout is scene triangle prim_indices[i] (see flatten()). Each is a
// pure function of the scene, so chunks on several threads give the same bytes as one loop.
void make_triangles(const BvhTree& tree, const Scene& scene, dev::GcTriangle* out, std::size_t begin, std::size_t end)
{
    for (std::size_t i = begin; i < end; ++i) {
        const std::uint32_t prim = tree.prim_indices[i];
        const std::uint32_t flags = triangle_alpha_tested(scene, prim) ? GC_TRI_ALPHA_TESTED : 0u;
        out[i] = make_triangle(scene.vertex(prim, 0), scene.vertex(prim, 1), scene.vertex(prim, 2), prim, flags);
    }
}

[[noreturn]] void leaf_out_of_order(std::uint32_t first, std::uint32_t expected)
{
    throw std::logic_error("flatten: BVH leaf over triangles " + std::to_string(first) +
                           " is not in depth-first order (expected " + std::to_string(expected) +
                           "); host/bvh/builder.cpp broke its BvhTree promise");
}

// The nodes in depth-first order: a pre-order walk with an explicit stack of (tree node,
// output slot). An inner node reserves its children's pair when it is visited; pushing right
// before left makes the left subtree complete before the right child's pair is reserved. The
// builder lays leaves' ranges of prim_indices out in the same order (a left subtree's range
// before its right sibling's), so the triangles are prim_indices' order, made apart from this
// walk; the walk checks that promise leaf by leaf.
//
// The walk of the subtree under tree node `src`, written at slot `dst`, its pairs from
// `next_pair` on and its leaves expected from triangle `next_triangle` on. Nodes at depth
// `cut_depth` below it that are inner are not entered but handed to `at_cut` (with their
// slot), which returns how many inner nodes and triangles their subtrees hold. Returns the
// slot after the last pair the walk reserved.
template <class AtCut>
std::uint32_t walk(const BvhTree& tree, dev::GcBvhNode* nodes, std::uint32_t src, std::uint32_t dst,
                   std::uint32_t next_pair, std::uint32_t next_triangle, std::uint32_t cut_depth, const AtCut& at_cut)
{
    struct Visit {
        std::uint32_t src;
        std::uint32_t dst;
        std::uint32_t depth;
    };
    std::vector<Visit> stack{{src, dst, 0u}};
    while (!stack.empty()) {
        const Visit v = stack.back();
        stack.pop_back();
        const BvhBuildNode& node = tree.nodes[v.src];
        if (node.count > 0) {
            if (node.first != next_triangle) leaf_out_of_order(node.first, next_triangle);
            next_triangle += node.count;
            nodes[v.dst] = make_node(node.lo, node.hi, node.first, node.count);
        } else if (v.depth == cut_depth) {
            nodes[v.dst] = make_node(node.lo, node.hi, next_pair, 0);
            const auto [inner, triangles] = at_cut(v.src, v.dst, next_pair, next_triangle);
            next_pair += 2 * inner; // each inner node of the subtree reserves one pair
            next_triangle += triangles;
        } else {
            const std::uint32_t pair = next_pair;
            next_pair += 2;
            nodes[v.dst] = make_node(node.lo, node.hi, pair, 0);
            stack.push_back({node.first + 1, pair + 1, v.depth + 1});
            stack.push_back({node.first, pair, v.depth + 1});
        }
    }
    return next_pair;
}

// Inner nodes and triangles of the subtree under `src`.
std::pair<std::uint32_t, std::uint32_t> subtree_size(const BvhTree& tree, std::uint32_t src)
{
    std::uint32_t inner = 0;
    std::uint32_t triangles = 0;
    std::vector<std::uint32_t> stack{src};
    while (!stack.empty()) {
        const BvhBuildNode& node = tree.nodes[stack.back()];
        stack.pop_back();
        if (node.count > 0) {
            triangles += node.count;
        } else {
            ++inner;
            stack.push_back(node.first + 1);
            stack.push_back(node.first);
        }
    }
    return {inner, triangles};
}

constexpr std::uint32_t kNoCut = std::numeric_limits<std::uint32_t>::max();

[[noreturn]] std::pair<std::uint32_t, std::uint32_t> no_cut(std::uint32_t, std::uint32_t, std::uint32_t, std::uint32_t)
{
    throw std::logic_error("flatten: a walk without cuts reached one");
}

// The node layout on one thread, or with a pool the same bytes in parallel: the inner nodes
// at kCutDepth are the roots of subtrees that are first sized on all threads; the top of
// the tree is then walked with those sizes (each such subtree's pairs are one contiguous run
// in the serial walk's order too, so its run starts where the serial walk would reach it);
// last, the subtrees are walked on all threads from the slots the top walk gave them. On
// many cores a serial walk of a huge tree is a large share of the whole build
// (docs/decisions/bvh-build-many-cores.md).
BigArray<dev::GcBvhNode> flatten_nodes(const BvhTree& tree, TaskPool* pool)
{
    // The builder's array may hold a few unreferenced slots, so it bounds the count from above;
    // the walk gives the exact one.
    BigArray<dev::GcBvhNode> nodes(tree.nodes.size());
    std::uint32_t end = 0;
    if (!pool || tree.nodes.size() < kParallelNodes) {
        end = walk(tree, nodes.data(), 0u, 0u, 1u, 0u, kNoCut, no_cut);
    } else {
        // The cut subtrees' roots in the order the top walk meets them (left before right).
        std::vector<std::uint32_t> cuts;
        std::vector<std::pair<std::uint32_t, std::uint32_t>> stack{{0u, 0u}}; // (node, depth)
        while (!stack.empty()) {
            const auto [src, depth] = stack.back();
            stack.pop_back();
            const BvhBuildNode& node = tree.nodes[src];
            if (node.count > 0) continue;
            if (depth == kCutDepth) {
                cuts.push_back(src);
                continue;
            }
            stack.emplace_back(node.first + 1, depth + 1);
            stack.emplace_back(node.first, depth + 1);
        }
        std::vector<std::pair<std::uint32_t, std::uint32_t>> sizes(cuts.size());
        pool->for_each(cuts.size(), [&](std::size_t c) { sizes[c] = subtree_size(tree, cuts[c]); });
        struct Placed {
            std::uint32_t src;
            std::uint32_t dst;
            std::uint32_t next_pair;
            std::uint32_t next_triangle;
        };
        std::vector<Placed> placed;
        end = walk(tree, nodes.data(), 0u, 0u, 1u, 0u, kCutDepth,
                   [&](std::uint32_t src, std::uint32_t dst, std::uint32_t pair, std::uint32_t triangle) {
                       const std::size_t c = placed.size();
                       if (c >= cuts.size() || cuts[c] != src) throw std::logic_error("flatten: cut subtrees out of order");
                       placed.push_back({src, dst, pair, triangle});
                       return sizes[c];
                   });
        pool->for_each(placed.size(), [&](std::size_t c) {
            const Placed& p = placed[c];
            walk(tree, nodes.data(), p.src, p.dst, p.next_pair, p.next_triangle, kNoCut, no_cut);
        });
    }
    nodes.resize(end);
    return nodes;
}

}  // namespace

bool triangle_alpha_tested(const Scene& scene, std::size_t tri)
{
    // Loaders only write valid indices, but a Scene made in code may not: this is the first
    // read of a triangle's material on the way to the device, so it is checked here.
    const std::uint32_t id = scene.material_ids[tri];
    if (id >= scene.materials.size())
        throw InputError(scene.name_for_messages() + ": triangle " + std::to_string(tri) + " has material " +
                         std::to_string(id) + ", but the scene has " + std::to_string(scene.materials.size()));
    const Material& m = scene.materials[id];
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

    FlatBvh flat;
    const std::size_t n = tree.prim_indices.size();
    flat.triangles.resize(n);
    const int threads = host_thread_count();
    if (threads < 2 || n < kTriangleChunk) {
        make_triangles(tree, scene, flat.triangles.data(), 0, n);
        flat.nodes = flatten_nodes(tree, nullptr);
        return flat;
    }
    // The triangles (a gather from the scene's vertices) go to the pool in chunks, and its
    // threads take them up whenever the node layout leaves them idle.
    TaskPool pool(threads);
    TaskGroup triangles;
    for (std::size_t begin = 0; begin < n; begin += kTriangleChunk)
        pool.spawn(triangles, [&tree, &scene, &flat, begin, n] {
            make_triangles(tree, scene, flat.triangles.data(), begin, std::min(n, begin + kTriangleChunk));
        });
    try {
        flat.nodes = flatten_nodes(tree, &pool);
    } catch (...) {
        try {
            pool.wait(triangles); // they refer to `flat`
        } catch (...) {
        }
        throw;
    }
    pool.wait(triangles);
    return flat;
}

}  // namespace gc
