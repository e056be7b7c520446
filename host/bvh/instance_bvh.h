// The two-level BVH of an InstancedScene (host/scene/instances.h), in the arrays
// kernels/shared/gc_instance.h reads: a top-level BVH2 over the instances' world bounds, the
// instances in its leaf order, and every mesh's bottom-level tree, built once per mesh and
// concatenated in the device's layout (BVH2, BVH4 or BVH8). Memory grows with instances
// (a GcInstance and about one top-level node each) and with distinct meshes, not with the
// triangles the instances draw.
//
//     const InstanceBvhParts parts = build_instance_bvh(scene);
//     InstancedBvh8 bvh = assemble_wide8(parts);   // upload its four arrays
#pragma once

#include <cstddef>
#include <vector>

#include "gc_instance.h"
#include "host/bvh/big_array.h"
#include "host/bvh/builder.h"
#include "host/bvh/flatten.h"
#include "host/scene/instances.h"

namespace gc {

template <class Node, class Tri>
struct InstancedBvhOf {
    BigArray<dev::GcBvhNode> tlas;      // top level; leaves index `instances`
    BigArray<dev::GcInstance> instances; // in the top level's leaf order, bases into nodes/tris
    BigArray<Node> nodes;               // every mesh's tree, mesh after mesh
    BigArray<Tri> tris;

    // Bytes of the per-instance arrays (top level + instances) and of the meshes' trees.
    std::size_t instance_bytes() const
    {
        return tlas.size() * sizeof(dev::GcBvhNode) + instances.size() * sizeof(dev::GcInstance);
    }
    std::size_t mesh_bytes() const { return nodes.size() * sizeof(Node) + tris.size() * sizeof(Tri); }
};
using InstancedBvh = InstancedBvhOf<dev::GcBvhNode, dev::GcTriangle>;
using InstancedBvh4 = InstancedBvhOf<dev::GcBvh4Node, dev::GcTriangle4>;
using InstancedBvh8 = InstancedBvhOf<dev::GcBvh8Node, dev::GcTriangle4>;

// What every layout is assembled from: the top level and instances (bases still unset) and
// each mesh's BVH2, its triangles numbered in the scene of meshes.
struct InstanceBvhParts {
    BigArray<dev::GcBvhNode> tlas;
    BigArray<dev::GcInstance> instances;
    std::vector<FlatBvh> meshes;
};

// `scene` must have passed validate_instances. The meshes' trees use `options`; the top level
// is built with leaves of at most two instances and an intersection cost of four node
// visits, since opening an instance costs a whole bottom-level descent.
InstanceBvhParts build_instance_bvh(const InstancedScene& scene, const BvhBuildOptions& options = {});

InstancedBvh assemble_binary(const InstanceBvhParts& parts);
InstancedBvh4 assemble_wide(const InstanceBvhParts& parts);
InstancedBvh8 assemble_wide8(const InstanceBvhParts& parts);

}  // namespace gc
