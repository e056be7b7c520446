#include "host/bvh/widen.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gc_accessors.h"

namespace gc {
namespace {

constexpr std::uint32_t kBlockLanes = 4;

struct Bvh2View {
    const FlatBvh& bvh;
    // Per BVH2 node: its subtree's triangles, [tri_first, tri_end) in bvh.triangles.
    BigArray<std::uint32_t> tri_first;
    BigArray<std::uint32_t> tri_end;
    // Sizes for reserving the output once. Every wide inner node opens a BVH2 node that does
    // not become a leaf, so their number bounds the wide nodes; every child of such a node
    // that does become a leaf is one wide leaf, so their blocks are all the blocks.
    std::size_t inner_bound = 0;
    std::size_t block_count = 0;

    bool is_leaf(std::uint32_t n) const { return dev::gc_node_is_leaf(bvh.nodes[n]); }
    std::uint32_t first(std::uint32_t n) const { return dev::gc_node_first(bvh.nodes[n]); }
    std::uint32_t triangles(std::uint32_t n) const { return tri_end[n] - tri_first[n]; }
    // A subtree tested as one leaf: a BVH2 leaf, or any subtree that fits one block.
    bool becomes_leaf(std::uint32_t n) const { return is_leaf(n) || triangles(n) <= kBlockLanes; }
    float area(std::uint32_t n) const
    {
        const dev::GcBvhNode& node = bvh.nodes[n];
        const float dx = node.hi.x - node.lo.x;
        const float dy = node.hi.y - node.lo.y;
        const float dz = node.hi.z - node.lo.z;
        return dx * dy + dy * dz + dz * dx;
    }
};

// Fills tri_first/tri_end bottom-up and counts inner_bound and block_count. Children always follow their
// parent in the flat order (flatten's depth-first layout), so one backward sweep sees children
// before parents; every entry is written.
void compute_ranges(Bvh2View& view)
{
    const std::size_t n = view.bvh.nodes.size();
    view.tri_first.resize(n);
    view.tri_end.resize(n);
    for (std::size_t i = n; i-- > 0;) {
        const auto node = static_cast<std::uint32_t>(i);
        const std::uint32_t first = view.first(node);
        if (view.is_leaf(node)) {
            view.tri_first[i] = first;
            view.tri_end[i] = first + dev::gc_node_count(view.bvh.nodes[i]);
        } else {
            view.tri_first[i] = std::min(view.tri_first[first], view.tri_first[first + 1]);
            view.tri_end[i] = std::max(view.tri_end[first], view.tri_end[first + 1]);
        }
        if (!view.becomes_leaf(node)) {
            ++view.inner_bound;
            for (const std::uint32_t child : {first, first + 1})
                if (view.becomes_leaf(child)) view.block_count += (view.triangles(child) + kBlockLanes - 1) / kBlockLanes;
        }
    }
}

dev::GcTriangle4 empty_block()
{
    dev::GcTriangle4 block{};
    block.prim = dev::uint4(GC_INVALID);
    block.flags = dev::uint4(0u);
    return block;
}

void set_slot(dev::GcBvh4Node& node, int slot, const dev::GcBvhNode& box, std::uint32_t child)
{
    node.lo_x[slot] = box.lo.x;
    node.lo_y[slot] = box.lo.y;
    node.lo_z[slot] = box.lo.z;
    node.hi_x[slot] = box.hi.x;
    node.hi_y[slot] = box.hi.y;
    node.hi_z[slot] = box.hi.z;
    node.child[slot] = child;
}

void set_slot(dev::GcBvh8Node& node, int slot, const dev::GcBvhNode& box, std::uint32_t child)
{
    const bool upper = slot >= 4;
    const int k = slot & 3;
    (upper ? node.lo_x1 : node.lo_x0)[k] = box.lo.x;
    (upper ? node.lo_y1 : node.lo_y0)[k] = box.lo.y;
    (upper ? node.lo_z1 : node.lo_z0)[k] = box.lo.z;
    (upper ? node.hi_x1 : node.hi_x0)[k] = box.hi.x;
    (upper ? node.hi_y1 : node.hi_y0)[k] = box.hi.y;
    (upper ? node.hi_z1 : node.hi_z0)[k] = box.hi.z;
    (upper ? node.child1 : node.child0)[k] = child;
}

// A node whose every slot is empty (bounds +inf .. -inf, child GC_INVALID), pads 0: the
// same set_slot that fills real slots writes the empty ones.
template <class Node, std::uint32_t Width>
Node empty_node()
{
    constexpr float inf = std::numeric_limits<float>::infinity();
    dev::GcBvhNode empty_box;
    empty_box.lo = dev::float4(inf, inf, inf, 0.0f);
    empty_box.hi = dev::float4(-inf, -inf, -inf, 0.0f);
    Node node{};
    for (std::uint32_t k = 0; k < Width; ++k) set_slot(node, static_cast<int>(k), empty_box, GC_INVALID);
    return node;
}

template <class Node, std::uint32_t Width>
class Widener {
public:
    explicit Widener(const Bvh2View& view, WideBvhOf<Node>& out) : m_view(view), m_out(out) {}

    // Emits the blocks of BVH2 subtree `n` and returns its leaf reference.
    std::uint32_t leaf(std::uint32_t n)
    {
        const std::uint32_t first_tri = m_view.tri_first[n];
        const std::uint32_t count = m_view.triangles(n);
        const std::uint32_t blocks = (count + kBlockLanes - 1) / kBlockLanes;
        const std::size_t first_block = m_out.blocks.size();
        if (blocks == 0 || blocks > GC_BVH4_LEAF_MAX_BLOCKS)
            throw std::logic_error("wide BVH: a leaf of " + std::to_string(count) + " triangles does not fit one reference");
        if (first_block + blocks - 1 > GC_BVH4_LEAF_FIRST_MASK)
            throw std::length_error("wide BVH: more than " + std::to_string(GC_BVH4_LEAF_FIRST_MASK + 1u) +
                                    " triangle blocks");
        for (std::uint32_t b = 0; b < blocks; ++b) {
            dev::GcTriangle4 block = empty_block();
            for (std::uint32_t lane = 0; lane < kBlockLanes; ++lane) {
                const std::uint32_t i = b * kBlockLanes + lane;
                if (i >= count) break;
                const dev::GcTriangle& tri = m_view.bvh.triangles[first_tri + i];
                block.v0x[lane] = tri.v0.x;
                block.v0y[lane] = tri.v0.y;
                block.v0z[lane] = tri.v0.z;
                block.v1x[lane] = tri.v1.x;
                block.v1y[lane] = tri.v1.y;
                block.v1z[lane] = tri.v1.z;
                block.v2x[lane] = tri.v2.x;
                block.v2y[lane] = tri.v2.y;
                block.v2z[lane] = tri.v2.z;
                block.prim[lane] = dev::gc_triangle_prim(tri);
                block.flags[lane] = dev::gc_triangle_flags(tri);
            }
            m_out.blocks.push_back(block);
        }
        return GC_BVH4_LEAF | ((blocks - 1) << GC_BVH4_LEAF_COUNT_SHIFT) | static_cast<std::uint32_t>(first_block);
    }

    // Emits the BVH4 node for BVH2 inner node `n` (and its subtree) and returns its index.
    std::uint32_t inner(std::uint32_t n)
    {
        std::uint32_t children[Width];
        std::uint32_t count = 0;
        children[count++] = m_view.first(n);
        children[count++] = m_view.first(n) + 1;
        while (count < Width) {
            int widest = -1;
            for (std::uint32_t k = 0; k < count; ++k) {
                if (m_view.becomes_leaf(children[k])) continue;
                if (widest < 0 || m_view.area(children[k]) > m_view.area(children[static_cast<std::uint32_t>(widest)]))
                    widest = static_cast<int>(k);
            }
            if (widest < 0) break;
            // Open it in place: its two children take its slot and the next, keeping the
            // BVH2's left-to-right order.
            const std::uint32_t opened = children[widest];
            for (std::uint32_t k = count; k > static_cast<std::uint32_t>(widest) + 1; --k) children[k] = children[k - 1];
            children[widest] = m_view.first(opened);
            children[widest + 1] = m_view.first(opened) + 1;
            ++count;
        }
        const auto index = static_cast<std::uint32_t>(m_out.nodes.size());
        if (index > ~GC_BVH4_LEAF) throw std::length_error("wide BVH: too many nodes");
        m_out.nodes.push_back(empty_node<Node, Width>());
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t c = children[k];
            const std::uint32_t ref = m_view.becomes_leaf(c) ? leaf(c) : inner(c);
            set_slot(m_out.nodes[index], static_cast<int>(k), m_view.bvh.nodes[c], ref);
        }
        return index;
    }

private:
    const Bvh2View& m_view;
    WideBvhOf<Node>& m_out;
};

template <class Node, std::uint32_t Width>
WideBvhOf<Node> widen_tree(const FlatBvh& bvh)
{
    WideBvhOf<Node> out;
    if (bvh.nodes.empty() || bvh.scene_triangle_count() == 0) {
        out.nodes.push_back(empty_node<Node, Width>());
        out.blocks.push_back(empty_block());
        return out;
    }
    Bvh2View view{bvh, {}, {}, 0, 0};
    compute_ranges(view);
    out.nodes.reserve(view.inner_bound + 1);
    out.blocks.reserve(std::max<std::size_t>(view.block_count, 1));
    Widener<Node, Width> widener(view, out);
    if (view.becomes_leaf(0)) {
        // A root that is one leaf still needs an inner root: traversal starts at node 0.
        out.nodes.push_back(empty_node<Node, Width>());
        const std::uint32_t ref = widener.leaf(0);
        set_slot(out.nodes[0], 0, bvh.nodes[0], ref);
        return out;
    }
    widener.inner(0);  // emits the root first, as node 0
    if (out.blocks.size() != view.block_count)
        throw std::logic_error("wide BVH: " + std::to_string(out.blocks.size()) + " blocks emitted, " +
                               std::to_string(view.block_count) + " counted");
    return out;
}

// The largest |coordinate| of the BVH2 root's bounds (0 for the empty scene), whose bits the
// wide root carries for the traversal's margin (gc_ray_with_extent_margin).
float scene_extent(const FlatBvh& bvh)
{
    if (bvh.nodes.empty() || bvh.scene_triangle_count() == 0) return 0.0f;
    const dev::GcBvhNode& root = bvh.nodes[0];
    float extent = 0.0f;
    for (const float c : {root.lo.x, root.lo.y, root.lo.z, root.hi.x, root.hi.y, root.hi.z})
        extent = std::max(extent, std::fabs(c));
    return extent;
}

void set_extent(dev::GcBvh4Node& root, float extent)
{
    root.pad.x = std::bit_cast<std::uint32_t>(extent);
}

void set_extent(dev::GcBvh8Node& root, float extent)
{
    root.pad0.x = std::bit_cast<std::uint32_t>(extent);
}

template <class Node, std::uint32_t Width>
WideBvhOf<Node> widen_to(const FlatBvh& bvh)
{
    WideBvhOf<Node> out = widen_tree<Node, Width>(bvh);
    set_extent(out.nodes[0], scene_extent(bvh));
    return out;
}

}  // namespace

WideBvh widen(const FlatBvh& bvh)
{
    return widen_to<dev::GcBvh4Node, 4>(bvh);
}

Wide8Bvh widen8(const FlatBvh& bvh)
{
    return widen_to<dev::GcBvh8Node, 8>(bvh);
}

}  // namespace gc
