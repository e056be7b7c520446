// Binned SAH BVH2 builder (Wald 2007, "On fast construction of SAH-based bounding volume
// hierarchies", IEEE RT'07): at each node the triangles' centroids are binned along each
// axis, the surface area heuristic is evaluated at every bin boundary, and the cheapest
// split wins, unless a leaf is cheaper.
//
// Output is a BvhTree, the intermediate form flatten() turns into the device layout. The
// tree is a pure function of the scene and the options: the thread count changes which
// thread builds which subtree and how a node's triangles are reordered on the way, never a
// decision or a leaf's order, so every machine builds the same BVH.
#pragma once

#include <cstdint>

#include "host/bvh/big_array.h"
#include "host/scene/scene.h"

namespace gc {

// Hard cap on BvhBuildOptions::max_leaf_size: the kernels loop over a leaf's triangles, and
// long leaves make the SIMD lanes of a GPU wait for each other.
inline constexpr int kBvhMaxLeafCap = 16;

struct BvhBuildOptions {
    int bins = 32;                 // per axis, 2..256
    int max_leaf_size = 4;         // leaves hold at most this many triangles, 1..kBvhMaxLeafCap
    // SAH constants: cost of one inner-node visit and of one triangle test, in the same unit.
    // 1 and 1 is the common textbook choice (and Embree's default for its SAH builders), so
    // bvh_stats' sah_cost compares with Embree's quality figure out of the box.
    float traversal_cost = 1.0f;
    float intersection_cost = 1.0f;
    int threads = 0;               // 0: host_thread_count() (every core unless --threads)
};

// A node of the build tree, with the same meaning as GcBvhNode: an inner node's children are
// nodes[first] (left) and nodes[first + 1] (right); a leaf (count > 0) holds
// prim_indices[first .. first + count). The order of nodes in the vector is arbitrary (it
// depends on which thread built what), and a few zeroed slots may be unreferenced (threads
// take node slots in blocks); flatten() walks from the root into canonical depth-first order.
struct BvhBuildNode {
    float lo[3];
    float hi[3];
    std::uint32_t first;
    std::uint32_t count; // 0: inner node
};

// Leaves' ranges of prim_indices follow the depth-first order of the tree (a left child's
// range comes before its right sibling's, and together they make their parent's), which
// flatten() relies on.
struct BvhTree {
    BigArray<BvhBuildNode> nodes; // root at 0; empty for an empty scene
    BigArray<std::uint32_t> prim_indices;    // scene triangle indices in leaf order
    double bounds_seconds = 0.0; // wall time of the triangle-bounds pass that starts the build
};

// Throws UsageError for options out of range and InputError for a scene with non-finite
// vertex coordinates or an inconsistent triangle count (naming scene.source_path).
BvhTree build_bvh_tree(const Scene& scene, const BvhBuildOptions& options = {});

}  // namespace gc
