#include "host/bvh/builder.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <exception>
#include <limits>
#include <string>
#include <thread>

#include "host/util/error.h"

namespace gc {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kMaxBins = 128;
// The kernels' stack holds 64 entries, enough for trees of depth <= 63 (root at depth 0).
// Below this depth budget the builder switches from SAH to median splits (see build()).
constexpr std::uint32_t kMaxTreeDepth = 63;
// Subtrees smaller than this are not worth a thread.
constexpr std::uint32_t kMinParallelPrims = 8192;

// Inputs are validated finite, so plain std::min/std::max (inlined compares) replace
// fmin/fmax, which GCC turns into libm calls for their NaN rules.
struct Box {
    float lo[3] = {kInf, kInf, kInf};
    float hi[3] = {-kInf, -kInf, -kInf};

    void grow(const float* plo, const float* phi)
    {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], plo[a]);
            hi[a] = std::max(hi[a], phi[a]);
        }
    }
    void grow(const Box& b) { grow(b.lo, b.hi); }
    void grow_point(const float* p) { grow(p, p); }

    float area() const
    {
        if (lo[0] > hi[0] || lo[1] > hi[1] || lo[2] > hi[2]) return 0.0f;
        const float dx = hi[0] - lo[0];
        const float dy = hi[1] - lo[1];
        const float dz = hi[2] - lo[2];
        return 2.0f * (dx * dy + dy * dz + dz * dx);
    }
};

struct PrimBox {
    float lo[3];
    float hi[3];
};

// Half of each bound rather than half their sum: no overflow near FLT_MAX.
inline void centroid(const PrimBox& b, float* c)
{
    for (int a = 0; a < 3; ++a) c[a] = 0.5f * b.lo[a] + 0.5f * b.hi[a];
}

// Trivially constructible (no member initialisers): find_split runs once per node and resets
// only the bins it uses; constructing all kMaxBins * 3 of them would dominate small nodes.
struct Bin {
    float lo[3];
    float hi[3];
    std::uint32_t count;

    void reset()
    {
        for (int a = 0; a < 3; ++a) {
            lo[a] = kInf;
            hi[a] = -kInf;
        }
        count = 0;
    }
};

// A candidate split: centroids with bin_index(c[axis]) < bin go left.
struct Split {
    int axis = -1;
    int bin = 0;
    float cmin = 0.0f;
    float scale = 0.0f;
    int bins = 0;      // bin count used for this node
    float cost = kInf; // sum over both sides of area * count (not yet normalised)
    std::uint32_t left_count = 0;
};

inline int bin_index(float c, float cmin, float scale, int bins)
{
    // c >= cmin and (c - cmin) * scale <= bins * (1 + eps): no overflow, no negative index.
    const int b = static_cast<int>((c - cmin) * scale);
    return std::min(b, bins - 1);
}

class Builder {
public:
    Builder(const std::vector<PrimBox>& prims, std::vector<std::uint32_t>& indices,
            const BvhBuildOptions& options, int threads)
        : m_prims(prims), m_indices(indices), m_options(options), m_spare_threads(threads - 1)
    {
    }

    // Builds the subtree over m_indices[begin, end) into out[slot] and nodes appended to out.
    void build(std::vector<BvhBuildNode>& out, std::uint32_t slot, std::uint32_t begin, std::uint32_t end,
               std::uint32_t depth)
    {
        Box node_box;
        Box centroid_box;
        for (std::uint32_t i = begin; i < end; ++i) {
            const PrimBox& p = m_prims[m_indices[i]];
            float c[3];
            centroid(p, c);
            node_box.grow(p.lo, p.hi);
            centroid_box.grow_point(c);
        }
        for (int a = 0; a < 3; ++a) {
            out[slot].lo[a] = node_box.lo[a];
            out[slot].hi[a] = node_box.hi[a];
        }
        const std::uint32_t n = end - begin;
        const auto max_leaf = static_cast<std::uint32_t>(m_options.max_leaf_size);

        // Depth guard: SAH may peel off a few triangles per level on pathological input. Once
        // depth + ceil(log2 n) reaches the limit, median splits (which halve n) take over and
        // keep every leaf at depth <= kMaxTreeDepth.
        const bool median_only = depth + static_cast<std::uint32_t>(std::bit_width(n - 1)) >= kMaxTreeDepth;
        if (n == 1 || (median_only && n <= max_leaf)) return make_leaf(out[slot], begin, n);

        Split split;
        if (!median_only) split = find_split(centroid_box, begin, end);
        if (n <= max_leaf) {
            // SAH termination (Wald 2007, eq. 1): a leaf costs C_isect * n; a split costs
            // C_trav + C_isect * (A_L n_L + A_R n_R) / A. A flat or point-like node (A == 0)
            // cannot be priced by area: keep it a leaf.
            const float area = node_box.area();
            const float leaf_cost = m_options.intersection_cost * static_cast<float>(n);
            const float split_cost = area > 0.0f
                                         ? m_options.traversal_cost + m_options.intersection_cost * split.cost / area
                                         : kInf;
            if (split.axis < 0 || leaf_cost <= split_cost) return make_leaf(out[slot], begin, n);
        }

        std::uint32_t mid;
        if (split.axis >= 0) {
            mid = partition(split, begin, end);
        } else {
            mid = median_split(centroid_box, begin, end);
        }

        const auto pair = static_cast<std::uint32_t>(out.size());
        out.resize(out.size() + 2);
        out[slot].first = pair;
        out[slot].count = 0;
        build_children(out, pair, begin, mid, end, depth + 1);
    }

private:
    static void make_leaf(BvhBuildNode& node, std::uint32_t begin, std::uint32_t n)
    {
        node.first = begin;
        node.count = n;
    }

    // The left child may go to another thread; it builds into its own vector, spliced in
    // after the join. Which subtrees run in parallel never changes a decision, only where
    // nodes sit in `out`, and flatten() puts them in canonical order anyway.
    void build_children(std::vector<BvhBuildNode>& out, std::uint32_t pair, std::uint32_t begin, std::uint32_t mid,
                        std::uint32_t end, std::uint32_t depth)
    {
        if (mid - begin < kMinParallelPrims || end - mid < kMinParallelPrims || !acquire_thread()) {
            build(out, pair, begin, mid, depth);
            build(out, pair + 1, mid, end, depth);
            return;
        }
        std::vector<BvhBuildNode> left(1);
        std::exception_ptr left_error;
        std::thread worker([&] {
            try {
                build(left, 0, begin, mid, depth);
            } catch (...) {
                left_error = std::current_exception();
            }
            m_spare_threads.fetch_add(1);
        });
        try {
            build(out, pair + 1, mid, end, depth);
        } catch (...) {
            worker.join();
            throw;
        }
        worker.join();
        if (left_error) std::rethrow_exception(left_error);

        // left[0] goes to out[pair]; left[j], j >= 1, to out[base + j - 1].
        const auto base = static_cast<std::uint32_t>(out.size());
        auto relocate = [base](BvhBuildNode node) {
            if (node.count == 0) node.first = base + node.first - 1;
            return node;
        };
        out[pair] = relocate(left[0]);
        out.reserve(out.size() + left.size() - 1);
        for (std::size_t j = 1; j < left.size(); ++j) out.push_back(relocate(left[j]));
    }

    bool acquire_thread()
    {
        int spare = m_spare_threads.load();
        while (spare > 0) {
            if (m_spare_threads.compare_exchange_weak(spare, spare - 1)) return true;
        }
        return false;
    }

    // Wald 2007: bin centroids on all three axes in one pass, then sweep the bins from both
    // ends to price every boundary. Ties keep the first candidate found (axis x, y, z; right
    // to left), except that an exactly equal cost with a more even count split wins, which
    // keeps zero-area clusters from peeling one triangle per level.
    Split find_split(const Box& cb, std::uint32_t begin, std::uint32_t end) const
    {
        // A node of n < bins triangles gets n bins: resetting and sweeping all bins was most
        // of the build time (most nodes are small), and the SAH barely notices (1M random
        // triangles: 378.6 -> 378.8). A pure function of the node, so still deterministic.
        const int bins =
            static_cast<int>(std::min<std::uint32_t>(static_cast<std::uint32_t>(m_options.bins), end - begin));
        float scale[3];
        bool usable[3];
        for (int a = 0; a < 3; ++a) {
            const float extent = cb.hi[a] - cb.lo[a];
            scale[a] = static_cast<float>(bins) / extent;
            usable[a] = extent > 0.0f && std::isfinite(scale[a]) && scale[a] > 0.0f;
        }
        if (!usable[0] && !usable[1] && !usable[2]) return {};

        Bin bin[3][kMaxBins];
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) bin[a][i].reset();

        for (std::uint32_t i = begin; i < end; ++i) {
            const PrimBox& p = m_prims[m_indices[i]];
            float c[3];
            centroid(p, c);
            for (int a = 0; a < 3; ++a) {
                if (!usable[a]) continue;
                Bin& b = bin[a][bin_index(c[a], cb.lo[a], scale[a], bins)];
                for (int k = 0; k < 3; ++k) {
                    b.lo[k] = std::min(b.lo[k], p.lo[k]);
                    b.hi[k] = std::max(b.hi[k], p.hi[k]);
                }
                ++b.count;
            }
        }

        Split best;
        const std::uint32_t n = end - begin;
        std::uint32_t best_imbalance = n;
        for (int a = 0; a < 3; ++a) {
            if (!usable[a]) continue;
            std::array<float, kMaxBins> left_area;
            std::array<std::uint32_t, kMaxBins> left_count;
            Box acc;
            std::uint32_t count = 0;
            for (int i = 0; i < bins - 1; ++i) {
                acc.grow(bin[a][i].lo, bin[a][i].hi);
                count += bin[a][i].count;
                left_area[i] = acc.area();
                left_count[i] = count;
            }
            acc = Box{};
            count = 0;
            for (int i = bins - 1; i >= 1; --i) {
                acc.grow(bin[a][i].lo, bin[a][i].hi);
                count += bin[a][i].count;
                const std::uint32_t nl = left_count[i - 1];
                if (nl == 0 || count == 0) continue;
                const float cost = left_area[i - 1] * static_cast<float>(nl) + acc.area() * static_cast<float>(count);
                const std::uint32_t imbalance = nl > count ? nl - count : count - nl;
                if (cost < best.cost || (cost == best.cost && imbalance < best_imbalance)) {
                    best.axis = a;
                    best.bin = i;
                    best.cmin = cb.lo[a];
                    best.scale = scale[a];
                    best.bins = bins;
                    best.cost = cost;
                    best.left_count = nl;
                    best_imbalance = imbalance;
                }
            }
        }
        return best;
    }

    // In-place two-way partition written out (not std::partition, whose element order is
    // up to the standard library) so the leaf order is the same with every toolchain.
    std::uint32_t partition(const Split& s, std::uint32_t begin, std::uint32_t end)
    {
        std::uint32_t i = begin;
        std::uint32_t j = end;
        while (i < j) {
            float c[3];
            centroid(m_prims[m_indices[i]], c);
            if (bin_index(c[s.axis], s.cmin, s.scale, s.bins) < s.bin) {
                ++i;
            } else {
                --j;
                std::swap(m_indices[i], m_indices[j]);
            }
        }
        return i;
    }

    // Fallback when binning finds no split (all centroids in one bin, or the depth guard):
    // halve by count along the widest centroid axis. std::stable_sort has one possible result
    // for a strict weak order, so this is deterministic too. With all centroids equal the
    // current order is split in half as it is.
    std::uint32_t median_split(const Box& cb, std::uint32_t begin, std::uint32_t end)
    {
        int axis = -1;
        float widest = 0.0f;
        for (int a = 0; a < 3; ++a) {
            const float extent = cb.hi[a] - cb.lo[a];
            if (extent > widest) {
                widest = extent;
                axis = a;
            }
        }
        if (axis >= 0) {
            std::stable_sort(m_indices.begin() + begin, m_indices.begin() + end,
                             [this, axis](std::uint32_t x, std::uint32_t y) {
                                 float cx[3];
                                 float cy[3];
                                 centroid(m_prims[x], cx);
                                 centroid(m_prims[y], cy);
                                 return cx[axis] < cy[axis];
                             });
        }
        return begin + (end - begin) / 2;
    }

    const std::vector<PrimBox>& m_prims;
    std::vector<std::uint32_t>& m_indices;
    const BvhBuildOptions& m_options;
    std::atomic<int> m_spare_threads;
};

void check_options(const BvhBuildOptions& o)
{
    auto fail = [](const std::string& what) { throw UsageError("BVH build options: " + what); };
    if (o.bins < 2 || o.bins > kMaxBins)
        fail("bins = " + std::to_string(o.bins) + " is out of range [2, " + std::to_string(kMaxBins) + "]");
    if (o.max_leaf_size < 1 || o.max_leaf_size > kBvhMaxLeafCap)
        fail("max_leaf_size = " + std::to_string(o.max_leaf_size) + " is out of range [1, " +
             std::to_string(kBvhMaxLeafCap) + "]");
    if (!(o.traversal_cost >= 0.0f) || !(o.intersection_cost > 0.0f) || !std::isfinite(o.traversal_cost) ||
        !std::isfinite(o.intersection_cost))
        fail("SAH costs must be finite, traversal_cost >= 0 and intersection_cost > 0 (got " +
             std::to_string(o.traversal_cost) + ", " + std::to_string(o.intersection_cost) + ")");
    if (o.threads < 0) fail("threads = " + std::to_string(o.threads) + " must be >= 0 (0: all cores)");
}

std::string scene_name(const Scene& scene)
{
    return scene.source_path.empty() ? std::string("<scene built in memory>") : scene.source_path;
}

}  // namespace

BvhTree build_bvh_tree(const Scene& scene, const BvhBuildOptions& options)
{
    check_options(options);
    const std::size_t count = scene.triangle_count();
    if (scene.positions.size() != 3 * count)
        throw InputError(scene_name(scene) + ": scene has " + std::to_string(count) + " triangles but " +
                         std::to_string(scene.positions.size()) + " vertex positions (expected 3 per triangle)");
    // Node indices are 32-bit and a tree has up to 2n - 1 nodes.
    if (count >= (std::size_t{1} << 31))
        throw InputError(scene_name(scene) + ": " + std::to_string(count) +
                         " triangles are more than the BVH's 32-bit indices can address (2^31 - 1)");

    BvhTree tree;
    if (count == 0) return tree;

    std::vector<PrimBox> prims(count);
    for (std::size_t t = 0; t < count; ++t) {
        PrimBox& p = prims[t];
        for (int a = 0; a < 3; ++a) {
            p.lo[a] = kInf;
            p.hi[a] = -kInf;
        }
        for (int corner = 0; corner < 3; ++corner) {
            const Point3 v = scene.vertex(t, corner);
            if (!is_finite(v))
                throw InputError(scene_name(scene) + ": triangle " + std::to_string(t) +
                                 " has a non-finite vertex coordinate (NaN or infinity)");
            for (int a = 0; a < 3; ++a) {
                p.lo[a] = std::min(p.lo[a], v[a]);
                p.hi[a] = std::max(p.hi[a], v[a]);
            }
        }
    }

    tree.prim_indices.resize(count);
    for (std::size_t t = 0; t < count; ++t) tree.prim_indices[t] = static_cast<std::uint32_t>(t);

    int threads = options.threads;
    if (threads == 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    // A tree has about 2n / (leaf size) nodes; reserving that avoids most regrowth.
    tree.nodes.reserve(2 * count / static_cast<std::size_t>(options.max_leaf_size) + 1);
    tree.nodes.resize(1);
    Builder builder(prims, tree.prim_indices, options, threads);
    builder.build(tree.nodes, 0, 0, static_cast<std::uint32_t>(count), 0);
    tree.nodes.shrink_to_fit();
    return tree;
}

}  // namespace gc
