// The device layout of a BVH: GcBvhNode[] and GcTriangle[] exactly as the kernels read them
// (kernels/shared/gc_types.h, traversed by kernels/shared/gc_traverse.h).
#pragma once

#include <vector>

#include "gc_types.h"
#include "host/bvh/builder.h"
#include "host/scene/scene.h"

namespace gc {

// Nodes in depth-first order with sibling pairs adjacent: node 0 is the root, an inner
// node's children are nodes[first] and nodes[first + 1], and a left child's whole subtree
// comes before its right sibling's children. Triangles are in leaf order (each leaf's
// triangles contiguous, leaves in the same depth-first order), with the scene triangle
// index in v0.w and the GC_TRI_* flags in v1.w.
//
// The empty scene flattens to one leaf with empty bounds (lo = +inf, hi = -inf, first = 0,
// count = 1) over one zero-area dummy triangle at the origin whose scene index is
// GC_INVALID: both buffers are non-empty (OpenCL has no zero-sized buffers) and every ray
// misses (see gc_traverse.h).
struct FlatBvh {
    BigArray<dev::GcBvhNode> nodes;
    BigArray<dev::GcTriangle> triangles;
    double build_seconds = 0.0; // wall time of build_bvh (tree + flatten); 0 if not timed
    double tree_seconds = 0.0;  // of which the tree (build_bvh_tree); the rest is flatten
    double bounds_seconds = 0.0; // of which the tree's triangle-bounds pass (BvhTree::bounds_seconds)

    // Triangles of the scene (0 for the empty scene's dummy).
    std::size_t scene_triangle_count() const;
};

FlatBvh flatten(const BvhTree& tree, const Scene& scene);

// True when traversal must ask the alpha test (gc_alpha.h) about scene triangle `tri`: its
// material is alphaMode MASK and either textured or with a factor below the cutoff. An
// untextured MASK material at or above the cutoff is solid everywhere and is not flagged.
bool triangle_alpha_tested(const Scene& scene, std::size_t tri);

}  // namespace gc
