// The BVH4 layout CPUs traverse (GcBvh4Node + GcTriangle4, kernels/shared/gc_traverse4.h),
// collapsed from the BVH2 that every other device reads. Both give the same hits: the
// collapse only regroups boxes and triangles, and traversal results do not depend on the
// tree (tie rule in gc_traverse.h).
//
//     FlatBvh bvh = build_bvh(scene);
//     WideBvh wide = widen(bvh);   // upload wide.nodes and wide.blocks
#pragma once

#include "gc_types.h"
#include "host/bvh/big_array.h"
#include "host/bvh/flatten.h"

namespace gc {

// Nodes in depth-first order (a node before its children, a child's subtree before its next
// sibling's), node 0 the root; GcTriangle4 blocks in the order their leaves are met. The
// empty scene gives a root with four empty slots over one dummy block (prim GC_INVALID in
// every lane), so both buffers are non-empty and every ray misses.
template <class Node>
struct WideBvhOf {
    BigArray<Node> nodes;
    BigArray<dev::GcTriangle4> blocks;
};
using WideBvh = WideBvhOf<dev::GcBvh4Node>;
using Wide8Bvh = WideBvhOf<dev::GcBvh8Node>;  // for 8-wide SIMD (gc_traverse8.h)

// Collapse rules (after Embree's BVH4 builders, and Wald et al. 2008, "Getting rid of
// packets"): a BVH2 subtree with at most wide_leaf_triangles triangles (four, one block; in
// the BVH8 eight from 65536 scene triangles on, sixteen from 2^20) becomes one leaf, tested
// block by block instead of a box test per node; a larger BVH2 leaf becomes a leaf of
// ceil(count / 4) blocks; an inner node takes its two children and repeatedly opens the
// child with the largest surface area that is not such a leaf, until it has four. The BVH4
// is never deeper than the BVH2, so gc_traverse4.h's stack bound holds.
//
// `threads` (0: all cores) only changes how fast: large trees are collapsed in subtrees on
// several threads and spliced into the serial walk's order, the same bytes.
WideBvh widen(const FlatBvh& bvh, int threads = 0);  // 0: host_thread_count()
Wide8Bvh widen8(const FlatBvh& bvh, int threads = 0);  // the same rules with eight children per node

// The largest BVH2 subtree that becomes one leaf in a `width`-wide BVH of a scene of
// `scene_triangles` triangles (widen.cpp says why; docs/decisions/bvh8-leaf-size.md has the
// figures).
std::uint32_t wide_leaf_triangles(std::uint32_t width, std::size_t scene_triangles);

// Bytes the layout occupies on a device.
template <class Node>
std::size_t wide_bvh_bytes(const WideBvhOf<Node>& bvh)
{
    return bvh.nodes.size() * sizeof(Node) + bvh.blocks.size() * sizeof(dev::GcTriangle4);
}

}  // namespace gc
