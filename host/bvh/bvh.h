// The BVH module's entry points: scene in, device-layout BVH out, plus quality figures.
//
//     FlatBvh bvh = build_bvh(scene);           // upload bvh.nodes and bvh.triangles
//     BvhStats s = bvh_stats(bvh);              // nodes, leaves, depth, SAH cost
#pragma once

#include <cstddef>

#include "host/bvh/builder.h"
#include "host/bvh/flatten.h"
#include "host/scene/scene.h"

namespace gc {

// Binned SAH build + flatten, timed into FlatBvh::build_seconds. Throws like build_bvh_tree.
FlatBvh build_bvh(const Scene& scene, const BvhBuildOptions& options = {});

struct BvhStats {
    std::size_t nodes = 0;
    std::size_t leaves = 0;
    std::size_t max_depth = 0; // edges from the root to the deepest leaf (a lone root leaf: 0)
    // Standard SAH cost normalised by the root's area (MacDonald and Booth 1990):
    //   (C_trav * sum over inner nodes of SA + C_isect * sum over leaves of SA * count) / SA(root)
    // i.e. the expected cost of a random ray that hits the root box. 0 for the empty BVH.
    float sah_cost = 0.0f;
    double build_seconds = 0.0; // copied from FlatBvh::build_seconds
};

// C_trav and C_isect default to 1 and 1 (the builder's defaults; Embree reports its SAH with
// the same unit costs), so the figure can be set beside Embree's. Pass the build options to
// price the tree with the costs it was built for.
BvhStats bvh_stats(const FlatBvh& bvh, float traversal_cost = 1.0f, float intersection_cost = 1.0f);

}  // namespace gc
