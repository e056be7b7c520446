#include "host/bvh/widen.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gc_accessors.h"
#include "host/bvh/task_pool.h"
#include "host/util/host_threads.h"

namespace gc {
namespace {

constexpr std::uint32_t kBlockLanes = 4;

// The largest BVH2 subtree that becomes one wide leaf, tested block by block instead of
// through a node of its own: one block's worth, except in the BVH8 of a large scene. There a
// node visit is mostly a cache miss, and fewer, fuller leaves save more node visits than
// their extra triangle tests cost: the larger the tree, the longer the leaves that pay. In a
// small scene, whose tree stays in L1, longer leaves only add triangle tests. The thresholds
// are where the BVH8 outgrows a core's L2 and most L3 caches; the BVH4 (CPUs without 8-wide
// SIMD) keeps one block. Figures: docs/decisions/bvh8-leaf-size.md.
constexpr std::uint32_t kLargeSceneTriangles = 65536;    // its BVH8 is beyond a core's L2
constexpr std::uint32_t kLargeSceneLeafTriangles = 2 * kBlockLanes;
constexpr std::uint32_t kHugeSceneTriangles = 1u << 20;  // ~170 MB: beyond most L3 caches
constexpr std::uint32_t kHugeSceneLeafTriangles = 4 * kBlockLanes;

struct Bvh2View {
    const FlatBvh& bvh;
    // Per BVH2 node: its subtree's triangles, [tri_first, tri_end) in bvh.triangles.
    BigArray<std::uint32_t> tri_first;
    BigArray<std::uint32_t> tri_end;
    // Per BVH2 node: the blocks its subtree collapses into. A node that becomes a leaf is its
    // own blocks; any other has exactly the wide leaves of its two children, since opening
    // only ever replaces a node that does not become a leaf by its two children.
    BigArray<std::uint32_t> blocks_below;
    // Every wide inner node opens a BVH2 node that does not become a leaf, so their number
    // bounds the wide nodes (the output is reserved once, not regrown).
    std::size_t inner_bound = 0;
    // Subtrees of at most this many triangles become one wide leaf (wide_leaf_triangles).
    std::uint32_t leaf_triangles = kBlockLanes;

    bool is_leaf(std::uint32_t n) const { return dev::gc_node_is_leaf(bvh.nodes[n]); }
    std::uint32_t first(std::uint32_t n) const { return dev::gc_node_first(bvh.nodes[n]); }
    std::uint32_t triangles(std::uint32_t n) const { return tri_end[n] - tri_first[n]; }
    // A subtree tested as one leaf: a BVH2 leaf, or any subtree of at most leaf_triangles.
    bool becomes_leaf(std::uint32_t n) const { return is_leaf(n) || triangles(n) <= leaf_triangles; }
    float area(std::uint32_t n) const
    {
        const dev::GcBvhNode& node = bvh.nodes[n];
        const float dx = node.hi.x - node.lo.x;
        const float dy = node.hi.y - node.lo.y;
        const float dz = node.hi.z - node.lo.z;
        return dx * dy + dy * dz + dz * dx;
    }
};

// The blocks of BVH2 subtree `n` as one wide leaf.
std::uint32_t block_count(const Bvh2View& view, std::uint32_t n)
{
    return (view.triangles(n) + kBlockLanes - 1) / kBlockLanes;
}

// block_count for a subtree about to become a wide leaf, which one reference must address.
std::uint32_t leaf_blocks(const Bvh2View& view, std::uint32_t n)
{
    const std::uint32_t blocks = block_count(view, n);
    if (blocks == 0 || blocks > GC_BVH4_LEAF_MAX_BLOCKS)
        throw std::logic_error("wide BVH: a leaf of " + std::to_string(view.triangles(n)) +
                               " triangles does not fit one reference");
    return blocks;
}

// One node's entries of the per-node arrays, from its children's (a leaf: from itself).
// Returns 1 if the node does not become a leaf (it counts towards inner_bound), else 0.
std::size_t compute_node_range(Bvh2View& view, std::uint32_t node)
{
    const std::uint32_t first = view.first(node);
    if (view.is_leaf(node)) {
        view.tri_first[node] = first;
        view.tri_end[node] = first + dev::gc_node_count(view.bvh.nodes[node]);
    } else {
        view.tri_first[node] = std::min(view.tri_first[first], view.tri_first[first + 1]);
        view.tri_end[node] = std::max(view.tri_end[first], view.tri_end[first + 1]);
    }
    if (view.becomes_leaf(node)) {
        view.blocks_below[node] = block_count(view, node);
        return 0;
    }
    view.blocks_below[node] = view.blocks_below[first] + view.blocks_below[first + 1];
    return 1;
}

// Subtrees whose descendants span fewer node slots than this are swept on one thread.
constexpr std::uint32_t kSerialRangeNodes = 65536;

// The entries of `node` and of its descendants, which flatten's depth-first layout puts at
// slots [below, below_end): an inner node's pair first, then the left child's descendants,
// then the right child's, each contiguous. Within such a range children follow their parent,
// so a backward sweep sees children before parents; large ranges are split at the right
// child's pair and swept on the pool. Returns the count towards inner_bound.
std::size_t compute_ranges_below(Bvh2View& view, TaskPool* pool, std::uint32_t node, std::uint32_t below,
                                 std::uint32_t below_end)
{
    std::size_t inner = 0;
    if (view.is_leaf(node) || pool == nullptr || below_end - below < kSerialRangeNodes) {
        for (std::uint32_t i = below_end; i-- > below;) inner += compute_node_range(view, i);
    } else {
        const std::uint32_t left = view.first(node);
        const std::uint32_t right = left + 1;
        // The right child's descendants start at its pair; a leaf has none, so the left's
        // run to the end.
        const std::uint32_t split = view.is_leaf(right) ? below_end : view.first(right);
        if (left != below || split < left + 2 || split > below_end)
            throw std::logic_error("wide BVH: the BVH2 is not in depth-first order");
        // The right child's run as a task, the left one here; fork_join waits for both before
        // an exception leaves this frame, which the task refers to.
        std::size_t side_inner[2] = {0, 0};
        pool->fork_join([&] { side_inner[0] = compute_ranges_below(view, pool, left, left + 2, split); },
                        [&] { side_inner[1] = compute_ranges_below(view, pool, right, split, below_end); });
        inner = side_inner[0] + side_inner[1];
    }
    return inner + compute_node_range(view, node);
}

// Fills the per-node arrays bottom-up and counts inner_bound, on `pool` if there is one.
void compute_ranges(Bvh2View& view, TaskPool* pool)
{
    const std::size_t n = view.bvh.nodes.size();
    view.tri_first.resize(n);
    view.tri_end.resize(n);
    view.blocks_below.resize(n);
    view.inner_bound = compute_ranges_below(view, pool, 0, 1, static_cast<std::uint32_t>(n));
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

// The reference a wide node keeps to a leaf of `blocks` blocks starting at `first_block`.
std::uint32_t leaf_ref(std::size_t first_block, std::uint32_t blocks)
{
    return GC_BVH4_LEAF | ((blocks - 1) << GC_BVH4_LEAF_COUNT_SHIFT) | static_cast<std::uint32_t>(first_block);
}

// Writes the blocks of BVH2 subtree `n` (a wide leaf) to out[0 .. block_count(n)).
void write_blocks(const Bvh2View& view, std::uint32_t n, dev::GcTriangle4* out)
{
    const std::uint32_t first_tri = view.tri_first[n];
    const std::uint32_t count = view.triangles(n);
    for (std::uint32_t b = 0; b < block_count(view, n); ++b) {
        dev::GcTriangle4 block = empty_block();
        for (std::uint32_t lane = 0; lane < kBlockLanes; ++lane) {
            const std::uint32_t i = b * kBlockLanes + lane;
            if (i >= count) break;
            const dev::GcTriangle& tri = view.bvh.triangles[first_tri + i];
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
        out[b] = block;
    }
}

// The BVH2 nodes that become the slots of the wide node for inner BVH2 node `n`: its two
// children, then repeatedly the child with the largest surface area that is not a leaf opened
// in place (its two children take its slot and the next, keeping the BVH2's left-to-right
// order), until there are Width. Returns how many.
template <std::uint32_t Width>
std::uint32_t collapse_children(const Bvh2View& view, std::uint32_t n, std::uint32_t (&children)[Width])
{
    std::uint32_t count = 0;
    children[count++] = view.first(n);
    children[count++] = view.first(n) + 1;
    while (count < Width) {
        int widest = -1;
        for (std::uint32_t k = 0; k < count; ++k) {
            if (view.becomes_leaf(children[k])) continue;
            if (widest < 0 || view.area(children[k]) > view.area(children[static_cast<std::uint32_t>(widest)]))
                widest = static_cast<int>(k);
        }
        if (widest < 0) break;
        const std::uint32_t opened = children[widest];
        for (std::uint32_t k = count; k > static_cast<std::uint32_t>(widest) + 1; --k) children[k] = children[k - 1];
        children[widest] = view.first(opened);
        children[widest + 1] = view.first(opened) + 1;
        ++count;
    }
    return count;
}

// The collapse of one subtree, depth first: wide nodes appended to `nodes`, blocks written
// to blocks[first_block, end_block) (the subtree's place in the whole BVH, so leaf references
// are final). The range comes from blocks_below; a collapse that would leave it, or not fill
// it (done()), is a bug here and throws rather than write out of bounds.
template <class Node, std::uint32_t Width>
class Widener {
public:
    Widener(const Bvh2View& view, BigArray<Node>& nodes, dev::GcTriangle4* blocks, std::size_t first_block,
            std::size_t end_block)
        : m_view(view), m_nodes(nodes), m_blocks(blocks), m_next_block(first_block), m_end_block(end_block)
    {
    }

    void done() const
    {
        if (m_next_block != m_end_block)
            throw std::logic_error("wide BVH: a subtree's blocks end at " + std::to_string(m_next_block) +
                                   ", counted to end at " + std::to_string(m_end_block));
    }

    // Emits the blocks of BVH2 subtree `n` and returns its leaf reference.
    std::uint32_t leaf(std::uint32_t n)
    {
        const std::uint32_t blocks = leaf_blocks(m_view, n);
        const std::size_t first_block = m_next_block;
        if (first_block + blocks > m_end_block) done();
        write_blocks(m_view, n, m_blocks + first_block);
        m_next_block += blocks;
        return leaf_ref(first_block, blocks);
    }

    // Emits the wide node for BVH2 inner node `n` (and its subtree) and returns its index in
    // `nodes`.
    std::uint32_t inner(std::uint32_t n)
    {
        std::uint32_t children[Width];
        const std::uint32_t count = collapse_children<Width>(m_view, n, children);
        const auto index = static_cast<std::uint32_t>(m_nodes.size());
        m_nodes.push_back(empty_node<Node, Width>());
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t c = children[k];
            const std::uint32_t ref = m_view.becomes_leaf(c) ? leaf(c) : inner(c);
            set_slot(m_nodes[index], static_cast<int>(k), m_view.bvh.nodes[c], ref);
        }
        return index;
    }

private:
    const Bvh2View& m_view;
    BigArray<Node>& m_nodes;
    dev::GcTriangle4* m_blocks;
    std::size_t m_next_block;
    const std::size_t m_end_block;
};

// Node and block counts must fit the references (gc_types.h): block indices in
// GC_BVH4_LEAF_FIRST_MASK, node indices below GC_BVH4_LEAF. Checked before anything is
// written, from the exact block count and the bound on the node count.
void check_reference_range(std::size_t node_bound, std::size_t blocks)
{
    if (blocks > std::size_t{GC_BVH4_LEAF_FIRST_MASK} + 1u)
        throw std::length_error("wide BVH: " + std::to_string(blocks) + " triangle blocks, more than the " +
                                std::to_string(GC_BVH4_LEAF_FIRST_MASK + 1u) + " a leaf reference can address");
    if (node_bound > std::size_t{GC_BVH4_LEAF})
        throw std::length_error("wide BVH: up to " + std::to_string(node_bound) + " nodes, more than the " +
                                std::to_string(GC_BVH4_LEAF) + " an inner reference can address");
}

// A child reference of a subtree collapsed on its own, moved to where the subtree's nodes
// start in the whole BVH. Leaf references are already final (its blocks were written in
// place); empty slots stay GC_INVALID.
std::uint32_t rebase(std::uint32_t ref, std::size_t node_base)
{
    if (ref == GC_INVALID || (ref & GC_BVH4_LEAF) != 0u) return ref;
    return ref + static_cast<std::uint32_t>(node_base);
}

void rebase_children(dev::GcBvh4Node& node, std::size_t node_base)
{
    for (int k = 0; k < 4; ++k) node.child[k] = rebase(node.child[k], node_base);
}

void rebase_children(dev::GcBvh8Node& node, std::size_t node_base)
{
    for (int k = 0; k < 4; ++k) {
        node.child0[k] = rebase(node.child0[k], node_base);
        node.child1[k] = rebase(node.child1[k], node_base);
    }
}

// The collapse on several threads, with the bytes of the serial one. The top of the tree is
// walked as Widener would, but a child subtree of at most `subtree_triangles` triangles is set
// aside as a piece of its own. The pieces are kept in the serial walk's order, so prefix sums
// of their sizes give where each goes: block counts are known before anything is collapsed
// (blocks_below), so every piece writes its blocks in place; node counts are not, so the
// subtrees collapse into node arrays of their own, copied to their places afterwards with
// their inner references moved. Every step but the top walk runs on the pool.
template <class Node, std::uint32_t Width>
class SplicedCollapse {
public:
    SplicedCollapse(const Bvh2View& view, std::uint32_t subtree_triangles)
        : m_view(view), m_subtree_triangles(subtree_triangles)
    {
    }

    void run(TaskPool& pool, WideBvhOf<Node>& out)
    {
        walk_top(0);
        std::vector<std::size_t> subtrees;
        std::size_t blocks = 0;
        for (std::size_t p = 0; p < m_pieces.size(); ++p) {
            m_pieces[p].block_base = blocks;
            blocks += m_pieces[p].blocks;
            if (m_pieces[p].kind == Kind::Subtree) subtrees.push_back(p);
        }
        check_reference_range(m_view.inner_bound + 1, blocks);
        out.blocks.resize(blocks);
        for (const Piece& piece : m_pieces)
            if (piece.kind == Kind::Leaf) write_blocks(m_view, piece.bvh2, &out.blocks[piece.block_base]);

        std::vector<BigArray<Node>> subtree_nodes(subtrees.size());
        pool.for_each(subtrees.size(), [&](std::size_t t) {
            Piece& piece = m_pieces[subtrees[t]];
            // A subtree's wide nodes open distinct BVH2 nodes of more than four triangles
            // each, nested or disjoint: fewer than half its triangles.
            subtree_nodes[t].reserve(m_view.triangles(piece.bvh2) / 2 + 1);
            Widener<Node, Width> widener(m_view, subtree_nodes[t], out.blocks.data(), piece.block_base,
                                         piece.block_base + piece.blocks);
            widener.inner(piece.bvh2);
            widener.done();
            piece.nodes = subtree_nodes[t].size();
        });

        std::size_t nodes = 0;
        for (Piece& piece : m_pieces) {
            piece.node_base = nodes;
            nodes += piece.nodes;
        }
        out.nodes.resize(nodes);
        for (const Piece& piece : m_pieces)
            if (piece.kind == Kind::Inner) out.nodes[piece.node_base] = empty_node<Node, Width>();
        for (const Slot& slot : m_slots) {
            const Piece& child = m_pieces[slot.child_piece];
            const std::uint32_t ref = child.kind == Kind::Leaf
                                          ? leaf_ref(child.block_base, static_cast<std::uint32_t>(child.blocks))
                                          : static_cast<std::uint32_t>(child.node_base);
            set_slot(out.nodes[m_pieces[slot.parent_piece].node_base], slot.index, m_view.bvh.nodes[child.bvh2], ref);
        }
        pool.for_each(subtrees.size(), [&](std::size_t t) {
            const std::size_t base = m_pieces[subtrees[t]].node_base;
            BigArray<Node>& part = subtree_nodes[t];
            for (std::size_t i = 0; i < part.size(); ++i) {
                Node node = part[i];
                rebase_children(node, base);
                out.nodes[base + i] = node;
            }
            part = BigArray<Node>();  // give the memory back as soon as it is copied
        });
    }

private:
    enum class Kind { Inner, Leaf, Subtree };
    struct Piece {
        Kind kind;
        std::uint32_t bvh2;         // the BVH2 node it comes from
        std::size_t nodes = 0;      // wide nodes and blocks it holds
        std::size_t blocks = 0;
        std::size_t node_base = 0;  // where they go in the whole BVH
        std::size_t block_base = 0;
    };
    // Slot `index` of the wide node of piece `parent_piece` refers to piece `child_piece`.
    struct Slot {
        std::size_t parent_piece;
        int index;
        std::size_t child_piece;
    };

    void walk_top(std::uint32_t n)
    {
        const std::size_t self = m_pieces.size();
        m_pieces.push_back(Piece{Kind::Inner, n, 1, 0});
        std::uint32_t children[Width];
        const std::uint32_t count = collapse_children<Width>(m_view, n, children);
        for (std::uint32_t k = 0; k < count; ++k) {
            const std::uint32_t c = children[k];
            const std::size_t at = m_pieces.size();
            if (m_view.becomes_leaf(c)) {
                m_pieces.push_back(Piece{Kind::Leaf, c, 0, leaf_blocks(m_view, c)});
            } else if (m_view.triangles(c) <= m_subtree_triangles) {
                m_pieces.push_back(Piece{Kind::Subtree, c, 0, m_view.blocks_below[c]});
            } else {
                walk_top(c);
            }
            m_slots.push_back(Slot{self, static_cast<int>(k), at});
        }
    }

    const Bvh2View& m_view;
    const std::uint32_t m_subtree_triangles;
    std::vector<Piece> m_pieces;  // in the serial walk's order
    std::vector<Slot> m_slots;
};

// Subtrees handed out as tasks hold at least this many triangles (fewer cost more to hand
// out than they save), and there are about 8 per thread for the balance.
constexpr std::uint32_t kMinSubtreeTriangles = 16384;

template <class Node, std::uint32_t Width>
WideBvhOf<Node> widen_tree(const FlatBvh& bvh, int threads)
{
    WideBvhOf<Node> out;
    if (bvh.nodes.empty() || bvh.scene_triangle_count() == 0) {
        out.nodes.push_back(empty_node<Node, Width>());
        out.blocks.push_back(empty_block());
        return out;
    }
    if (threads == 0) threads = host_thread_count();
    // One pool for the range sweep and the collapse, for trees large enough to share out.
    const std::size_t triangles = bvh.triangles.size();
    std::optional<TaskPool> pool;
    if (threads > 1 && triangles >= 4 * std::size_t{kMinSubtreeTriangles}) pool.emplace(threads);
    Bvh2View view{bvh, {}, {}, {}, 0, wide_leaf_triangles(Width, bvh.scene_triangle_count())};
    compute_ranges(view, pool ? &*pool : nullptr);
    const std::size_t blocks = view.blocks_below[0];
    if (view.becomes_leaf(0)) {
        // A root that is one leaf still needs an inner root: traversal starts at node 0.
        out.nodes.push_back(empty_node<Node, Width>());
        out.blocks.resize(blocks);
        Widener<Node, Width> widener(view, out.nodes, out.blocks.data(), 0, blocks);
        set_slot(out.nodes[0], 0, bvh.nodes[0], widener.leaf(0));
        widener.done();
        return out;
    }
    if (pool) {
        const auto per_task = static_cast<std::uint32_t>(triangles / (8 * static_cast<std::size_t>(threads)));
        SplicedCollapse<Node, Width>(view, std::max(kMinSubtreeTriangles, per_task)).run(*pool, out);
        return out;
    }
    check_reference_range(view.inner_bound + 1, blocks);
    out.nodes.reserve(view.inner_bound + 1);
    out.blocks.resize(blocks);
    Widener<Node, Width> widener(view, out.nodes, out.blocks.data(), 0, blocks);
    widener.inner(0);  // the root first, as node 0
    widener.done();
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
WideBvhOf<Node> widen_to(const FlatBvh& bvh, int threads)
{
    if (threads < 0) throw std::invalid_argument("widen: threads = " + std::to_string(threads) + " (0: all cores)");
    WideBvhOf<Node> out = widen_tree<Node, Width>(bvh, threads);
    set_extent(out.nodes[0], scene_extent(bvh));
    return out;
}

}  // namespace

std::uint32_t wide_leaf_triangles(std::uint32_t width, std::size_t scene_triangles)
{
    if (width != 8) return kBlockLanes;
    if (scene_triangles >= kHugeSceneTriangles) return kHugeSceneLeafTriangles;
    return scene_triangles >= kLargeSceneTriangles ? kLargeSceneLeafTriangles : kBlockLanes;
}

WideBvh widen(const FlatBvh& bvh, int threads)
{
    return widen_to<dev::GcBvh4Node, 4>(bvh, threads);
}

Wide8Bvh widen8(const FlatBvh& bvh, int threads)
{
    return widen_to<dev::GcBvh8Node, 8>(bvh, threads);
}

}  // namespace gc
