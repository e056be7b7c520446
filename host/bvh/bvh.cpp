#include "host/bvh/bvh.h"

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "gc_accessors.h"

namespace gc {
namespace {

double surface_area(const dev::GcBvhNode& node)
{
    const double dx = double(node.hi.x) - double(node.lo.x);
    const double dy = double(node.hi.y) - double(node.lo.y);
    const double dz = double(node.hi.z) - double(node.lo.z);
    if (dx < 0.0 || dy < 0.0 || dz < 0.0) return 0.0; // empty bounds
    return 2.0 * (dx * dy + dy * dz + dz * dx);
}

}  // namespace

FlatBvh build_bvh(const Scene& scene, const BvhBuildOptions& options)
{
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    const BvhTree tree = build_bvh_tree(scene, options);
    const auto tree_done = Clock::now();
    FlatBvh flat = flatten(tree, scene);
    flat.tree_seconds = std::chrono::duration<double>(tree_done - start).count();
    flat.bounds_seconds = tree.bounds_seconds;
    flat.build_seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return flat;
}

BvhStats bvh_stats(const FlatBvh& bvh, float traversal_cost, float intersection_cost)
{
    BvhStats stats;
    stats.build_seconds = bvh.build_seconds;
    if (bvh.nodes.empty()) return stats;
    stats.nodes = bvh.nodes.size();

    // Sums in double: a 5M-triangle tree adds millions of terms.
    double inner_area = 0.0;
    double leaf_area_count = 0.0;
    std::vector<std::pair<std::uint32_t, std::size_t>> stack{{0u, 0u}};
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        const dev::GcBvhNode& node = bvh.nodes[index];
        if (dev::gc_node_is_leaf(node)) {
            ++stats.leaves;
            stats.max_depth = std::max(stats.max_depth, depth);
            leaf_area_count += surface_area(node) * double(dev::gc_node_count(node));
        } else {
            inner_area += surface_area(node);
            stack.emplace_back(dev::gc_node_first(node), depth + 1);
            stack.emplace_back(dev::gc_node_first(node) + 1, depth + 1);
        }
    }
    const double root_area = surface_area(bvh.nodes[0]);
    if (root_area > 0.0)
        stats.sah_cost =
            float((double(traversal_cost) * inner_area + double(intersection_cost) * leaf_area_count) / root_area);
    return stats;
}

}  // namespace gc
