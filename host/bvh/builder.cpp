#include "host/bvh/builder.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/bvh/simd4.h"
#include "host/bvh/task_pool.h"
#include "host/util/error.h"
#include "host/util/host_threads.h"

namespace gc {
namespace {

using simd::Vec4;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr int kMaxBins = 128;
// The kernels' stack holds 64 entries, enough for trees of depth <= 63 (root at depth 0).
// Below this depth budget the builder switches from SAH to median splits (see build()).
constexpr std::uint32_t kMaxTreeDepth = 63;
// Work sizes, in triangles. None of them changes a decision, only which thread does what.
// Subtrees smaller than the task size (m_min_task_prims) stay on their thread: the scene's
// triangles over 32 per thread, within [512, 4096]. Small enough that the last subtrees even
// out across the threads; large enough that a huge scene does not crowd the pool's queue.
// A fixed size left many cores idle at the end of mid-size builds
// (docs/decisions/bvh-build-many-cores.md).
constexpr std::uint32_t kMinTaskFloor = 512;
constexpr std::uint32_t kMinTaskCeiling = 4096;
constexpr std::uint32_t kTasksPerThread = 32;
// Nodes of m_parallel_bin_prims triangles and more are binned (and, on four or more threads,
// partitioned) in parallel chunks, a node of that size in kMinStableChunks of them. The size
// is the scene's triangles per thread, within [16384, 32768]: a node needs threads of its own
// only near the top, where the tree has fewer subtrees than threads. Measured fastest on
// mid-size and huge scenes alike: docs/decisions/bvh-build-many-cores.md.
constexpr std::uint32_t kParallelBinFloor = 16384;
constexpr std::uint32_t kParallelBinCeiling = 32768;
constexpr std::uint32_t kSplitBinPrims = 128;       // from here on, bin into two sets (add_split)
constexpr std::uint32_t kPrimChunk = 16384;         // chunk of the triangle-bounds pass
// A node binned in at least kMinStableChunks parallel chunks is also partitioned in them
// (partition_stable); the rest in place on one thread (partition). Which one runs depends on
// the thread count, but what they decide does not: both send the same triangles to each
// side, only in another order, and nothing the builder keeps depends on that order (the bins
// are minima, maxima and counts; each leaf's triangles are sorted by index in make_leaf; the
// median split orders by centroid, then index). So the tree stays a pure function of the
// scene and the options. Two chunks do not pay for the out-of-place pass
// (docs/decisions/bvh-build-many-cores.md).
constexpr std::uint32_t kMinStableChunks = 4;
// Node slots a thread takes from the shared array at a time; even, since nodes come in
// sibling pairs, so a block is used up exactly before the next one is taken.
constexpr std::uint32_t kNodeBlock = 256;

// A triangle's bounds, the unit the builder partitions in place (no index indirection in
// the hot loops). w of `lo` holds the bits of the scene triangle index, w of `hi` is 0.
struct alignas(16) PrimRef {
    float lo[4];
    float hi[4];
};

std::uint32_t prim_of(const PrimRef& r)
{
    std::uint32_t prim;
    std::memcpy(&prim, &r.lo[3], sizeof prim);
    return prim;
}

struct Box4 {
    Vec4 lo = simd::splat(kInf);
    Vec4 hi = simd::splat(-kInf);

    void grow(Vec4 l, Vec4 h)
    {
        lo = simd::min(lo, l);
        hi = simd::max(hi, h);
    }
    void grow(const Box4& b) { grow(b.lo, b.hi); }
    void grow_point(Vec4 p) { grow(p, p); }

    // Surface area; 0 for an empty box (lo > hi on some axis). Inputs are finite or the
    // empty box's infinities, so hi - lo is negative exactly when lo > hi.
    float area() const
    {
        alignas(16) float d[4];
        simd::store(d, hi - lo);
        if (d[0] < 0.0f || d[1] < 0.0f || d[2] < 0.0f) return 0.0f;
        return 2.0f * (d[0] * d[1] + d[1] * d[2] + d[2] * d[0]);
    }
    void store(BvhBuildNode& node) const
    {
        alignas(16) float l[4];
        alignas(16) float h[4];
        simd::store(l, lo);
        simd::store(h, hi);
        for (int a = 0; a < 3; ++a) {
            node.lo[a] = l[a];
            node.hi[a] = h[a];
        }
    }
};

// Surface areas of three non-empty boxes, one per lane (w: 0), with the arithmetic of
// Box4::area: 2 * (dx * dy + dy * dz + dz * dx).
inline Vec4 areas(const Box4* box)
{
    Vec4 dx;
    Vec4 dy;
    Vec4 dz;
    simd::transpose3(box[0].hi - box[0].lo, box[1].hi - box[1].lo, box[2].hi - box[2].lo, dx, dy, dz);
    return simd::splat(2.0f) * (dx * dy + dy * dz + dz * dx);
}

// Loads a reference's corners, w lanes cleared (the index bits are no number).
inline void load(const PrimRef& r, Vec4& lo, Vec4& hi)
{
    lo = simd::xyz(simd::load(r.lo));
    hi = simd::load(r.hi);
}

// Half of each bound rather than half their sum: no overflow near FLT_MAX. Lane for lane the
// same arithmetic as 0.5f * lo + 0.5f * hi in scalar code.
inline Vec4 centroid(Vec4 lo, Vec4 hi)
{
    const Vec4 half = simd::splat(0.5f);
    return lo * half + hi * half;
}

// Centroid -> bin per axis: min((c - cmin) * scale, bins - 1), truncated. c >= cmin, so the
// index is never negative; an axis that cannot be binned has scale 0 and maps to bin 0.
struct BinMap {
    Vec4 cmin;
    Vec4 scale;
    Vec4 top;
    int bins = 0;
    bool usable[3] = {false, false, false};

    void index(Vec4 c, std::int32_t* out) const // out: 16-byte aligned, 4 entries
    {
        simd::truncate(simd::min((c - cmin) * scale, top), out);
    }
};

// Trivially constructible: only the `bins` entries in use are reset, which matters for the
// many small nodes near the leaves.
struct BinSet {
    Vec4 lo[3][kMaxBins];
    Vec4 hi[3][kMaxBins];
    std::uint32_t count[3][kMaxBins];

    void reset(int bins)
    {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                lo[a][i] = simd::splat(kInf);
                hi[a][i] = simd::splat(-kInf);
                count[a][i] = 0;
            }
    }
    void add(const PrimRef& ref, const BinMap& map)
    {
        Vec4 l;
        Vec4 h;
        load(ref, l, h);
        alignas(16) std::int32_t b[4];
        map.index(centroid(l, h), b);
        for (int a = 0; a < 3; ++a) {
            lo[a][b[a]] = simd::min(lo[a][b[a]], l);
            hi[a][b[a]] = simd::max(hi[a][b[a]], h);
            ++count[a][b[a]];
        }
    }
    void add(const PrimRef* refs, std::uint32_t begin, std::uint32_t end, const BinMap& map)
    {
        for (std::uint32_t i = begin; i < end; ++i) add(refs[i], map);
    }
    // As add(), alternating between this set and `spare` (reset here) and merging at the end:
    // neighbouring triangles often share a bin, and one set makes each update wait for the
    // previous one's store; two sets let two such chains run side by side.
    void add_split(const PrimRef* refs, std::uint32_t begin, std::uint32_t end, const BinMap& map, BinSet& spare)
    {
        spare.reset(map.bins);
        std::uint32_t i = begin;
        for (; i + 1 < end; i += 2) {
            add(refs[i], map);
            spare.add(refs[i + 1], map);
        }
        if (i < end) add(refs[i], map);
        merge(spare, map.bins);
    }
    // Min, max and integer sums: the merged bins do not depend on how the range was cut.
    void merge(const BinSet& other, int bins)
    {
        for (int a = 0; a < 3; ++a)
            for (int i = 0; i < bins; ++i) {
                lo[a][i] = simd::min(lo[a][i], other.lo[a][i]);
                hi[a][i] = simd::max(hi[a][i], other.hi[a][i]);
                count[a][i] += other.count[a][i];
            }
    }
};

// A candidate split: centroids with map.index(c)[axis] < bin go left.
struct Split {
    int axis = -1;
    int bin = 0;
    BinMap map;
    float cost = kInf; // sum over both sides of area * count (not yet normalised)
    Box4 left_box;     // bounds of the triangles on each side, the union of their bins
    Box4 right_box;
    // For a node binned in kMinStableChunks or more chunks (and so partitioned stably): how
    // many of each chunk's triangles go left, in chunk order (chunk_begin() cuts the node);
    // partition_stable places each chunk's runs by these counts before it reads a triangle.
    std::vector<std::uint32_t> chunk_lefts;
};

// The node's triangles [begin, begin + n) cut into `chunks` runs: where run c begins. The
// binning and the stable partition of a node cut it alike.
inline std::uint32_t chunk_begin(std::uint32_t begin, std::uint32_t n, std::uint32_t c, std::uint32_t chunks)
{
    return begin + static_cast<std::uint32_t>(std::uint64_t{n} * c / chunks);
}

// Whether split `s` sends reference `r` to the left child; `centre` gets r's centroid, which
// the children's centroid bounds are made of.
inline bool goes_left(const Split& s, const PrimRef& r, Vec4& centre)
{
    Vec4 lo;
    Vec4 hi;
    load(r, lo, hi);
    centre = centroid(lo, hi);
    alignas(16) std::int32_t b[4];
    s.map.index(centre, b);
    return b[s.axis] < s.bin;
}

// A node to build: its slot in the node array, its triangles refs[begin, end), its depth and
// bounds (of the triangles and of their centroids), known from the parent's partition.
// `refs` is the reference array or the scratch array, whichever the node's triangles lie in
// (partition_stable moves a node's triangles from one into the other).
struct NodeJob {
    std::uint32_t slot;
    std::uint32_t begin;
    std::uint32_t end;
    std::uint32_t depth;
    Box4 box;
    Box4 cbox;
    PrimRef* refs;
};

class Builder {
public:
    Builder(BigArray<PrimRef>& refs, BvhTree& tree, const BvhBuildOptions& options, TaskPool& pool)
        : m_refs(refs), m_tree(tree), m_options(options), m_pool(pool),
          m_arenas(static_cast<std::size_t>(pool.threads()))
    {
        // partition_stable's other array: node ranges are disjoint, so one array serves every
        // node being partitioned at the same time.
        m_parallel_bin_prims = std::clamp<std::uint32_t>(
            static_cast<std::uint32_t>(refs.size() / static_cast<std::size_t>(pool.threads())), kParallelBinFloor,
            kParallelBinCeiling);
        if (pool.threads() >= static_cast<int>(kMinStableChunks) && refs.size() >= m_parallel_bin_prims)
            m_scratch.resize(refs.size());
        // Written leaf by leaf (make_leaf), every entry once.
        m_tree.prim_indices.resize(refs.size());
        m_min_task_prims = std::clamp<std::uint32_t>(
            static_cast<std::uint32_t>(refs.size() / (static_cast<std::size_t>(pool.threads()) * kTasksPerThread)),
            kMinTaskFloor, kMinTaskCeiling);
        // A tree over n triangles has at most 2n - 1 nodes; each thread may leave the rest of
        // its last block unused. The array is not initialised, so unused capacity costs no
        // memory traffic.
        const std::size_t n = refs.size();
        m_tree.nodes.resize(2 * n - 1 + static_cast<std::size_t>(pool.threads()) * kNodeBlock);
    }

    void build_root(const Box4& box, const Box4& cbox)
    {
        build(NodeJob{0, 0, static_cast<std::uint32_t>(m_refs.size()), 0, box, cbox, m_refs.data()});
        // Slots left in the threads' last blocks are never referenced; zero them so the
        // array holds no uninitialised bytes, then drop the unused tail.
        const std::uint32_t used = m_next_block.load();
        for (const Arena& a : m_arenas)
            if (a.next < a.end) std::memset(&m_tree.nodes[a.next], 0, (a.end - a.next) * sizeof(BvhBuildNode));
        m_tree.nodes.resize(used);
    }

private:
    struct alignas(64) Arena { // per thread, on its own cache line
        std::uint32_t next = 0;
        std::uint32_t end = 0;
    };

    std::uint32_t allocate_pair()
    {
        Arena& a = m_arenas[static_cast<std::size_t>(m_pool.worker_index())];
        if (a.next == a.end) {
            a.next = m_next_block.fetch_add(kNodeBlock);
            a.end = a.next + kNodeBlock;
        }
        const std::uint32_t pair = a.next;
        a.next += 2;
        return pair;
    }

    void build(const NodeJob& job)
    {
        BvhBuildNode& node = m_tree.nodes[job.slot];
        job.box.store(node);
        const std::uint32_t n = job.end - job.begin;
        const auto max_leaf = static_cast<std::uint32_t>(m_options.max_leaf_size);

        // Depth guard: SAH may peel off a few triangles per level on pathological input. Once
        // depth + ceil(log2 n) reaches the limit, median splits (which halve n) take over and
        // keep every leaf at depth <= kMaxTreeDepth.
        const bool median_only =
            job.depth + static_cast<std::uint32_t>(std::bit_width(n - 1)) >= kMaxTreeDepth;
        if (n == 1 || (median_only && n <= max_leaf)) return make_leaf(node, job);

        Split split;
        if (!median_only) split = find_split(job);
        if (n <= max_leaf) {
            // SAH termination (Wald 2007, eq. 1): a leaf costs C_isect * n; a split costs
            // C_trav + C_isect * (A_L n_L + A_R n_R) / A. A flat or point-like node (A == 0)
            // cannot be priced by area: keep it a leaf.
            const float area = job.box.area();
            const float leaf_cost = m_options.intersection_cost * static_cast<float>(n);
            const float split_cost = area > 0.0f
                                         ? m_options.traversal_cost + m_options.intersection_cost * split.cost / area
                                         : kInf;
            if (split.axis < 0 || leaf_cost <= split_cost) return make_leaf(node, job);
        }

        const std::uint32_t pair = allocate_pair();
        node.first = pair;
        node.count = 0;
        NodeJob left{pair, job.begin, 0, job.depth + 1, {}, {}, job.refs};
        NodeJob right{pair + 1, 0, job.end, job.depth + 1, {}, {}, job.refs};
        if (split.axis >= 0) {
            left.end = split.chunk_lefts.empty() ? partition(split, job, left, right)
                                                 : partition_stable(split, job, left, right);
        } else {
            left.end = median_split(job, left, right);
        }
        right.begin = left.end;

        if (m_pool.threads() > 1 && left.end - left.begin >= m_min_task_prims &&
            right.end - right.begin >= m_min_task_prims) {
            // The right child as a task, the left one here. fork_join waits for the task
            // before an exception from either side leaves this frame: the task uses the
            // builder, which that exception would otherwise destroy under it.
            m_pool.fork_join([&] { build(left); }, [&] { build(right); });
        } else {
            build(left);
            build(right);
        }
    }

    // Also writes the leaf's entries of prim_indices, while its references are in cache, in
    // ascending order: the partitions leave a leaf's triangles in an order that depends on
    // which scheme ran (see partition_stable), and a leaf holds a few (insertion sort).
    void make_leaf(BvhBuildNode& node, const NodeJob& job)
    {
        node.first = job.begin;
        node.count = job.end - job.begin;
        std::uint32_t* out = m_tree.prim_indices.data();
        for (std::uint32_t i = job.begin; i < job.end; ++i) {
            const std::uint32_t prim = prim_of(job.refs[i]);
            std::uint32_t j = i;
            for (; j > job.begin && out[j - 1] > prim; --j) out[j] = out[j - 1];
            out[j] = prim;
        }
    }

    // Wald 2007: bin centroids on all three axes in one pass, then sweep the bins from both
    // ends to price every boundary. Ties keep the first candidate found (axis x, y, z; right
    // to left), except that an exactly equal cost with a more even count split wins, which
    // keeps zero-area clusters from peeling one triangle per level.
    Split find_split(const NodeJob& job)
    {
        const std::uint32_t n = job.end - job.begin;
        // A node of n < 2 * bins triangles gets n / 2 bins (at least 2): resetting and
        // sweeping the bins is most of the work in the many small nodes, and the SAH barely
        // notices (all 32 bins -> n bins -> n / 2 bins: 1M random triangles 378.6 -> 378.8 ->
        // 379.7, the dragon 43.43 -> 43.47). A pure function of the node, so deterministic.
        const int bins = static_cast<int>(std::min<std::uint32_t>(static_cast<std::uint32_t>(m_options.bins),
                                                                  std::max<std::uint32_t>(2, n / 2)));
        BinMap map;
        map.bins = bins;
        alignas(16) float cmin[4];
        alignas(16) float cmax[4];
        simd::store(cmin, job.cbox.lo);
        simd::store(cmax, job.cbox.hi);
        float scale[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        for (int a = 0; a < 3; ++a) {
            const float extent = cmax[a] - cmin[a];
            const float s = static_cast<float>(bins) / extent;
            map.usable[a] = extent > 0.0f && std::isfinite(s) && s > 0.0f;
            if (map.usable[a]) scale[a] = s;
        }
        if (!map.usable[0] && !map.usable[1] && !map.usable[2]) return Split();
        map.cmin = simd::make(cmin[0], cmin[1], cmin[2], 0.0f);
        map.scale = simd::make(scale[0], scale[1], scale[2], 0.0f);
        map.top = simd::splat(static_cast<float>(bins - 1));

        BinSet local;
        ChunkBins chunked;
        const BinSet& bin = bin_node(job, map, local, chunked);

        // Sweep all three axes at once: per boundary, the three axes' boxes are grown and
        // their areas computed in one vector. The winner is the lexicographic minimum of
        // (cost, count imbalance, position in the order axis x, y, z, each right to left),
        // so the choice does not depend on the order the candidates are priced in. An axis
        // that cannot be binned has everything in bin 0, hence no candidate; a side with no
        // triangles is skipped before its (meaningless) area is read.
        alignas(16) float left_area[kMaxBins][4];
        std::uint32_t left_count[kMaxBins][3];
        {
            Box4 acc[3];
            std::uint32_t count[3] = {0, 0, 0};
            for (int i = 0; i < bins - 1; ++i) {
                for (int a = 0; a < 3; ++a) {
                    acc[a].grow(bin.lo[a][i], bin.hi[a][i]);
                    count[a] += bin.count[a][i];
                    left_count[i][a] = count[a];
                }
                simd::store(left_area[i], areas(acc));
            }
        }
        Split best;
        std::uint32_t best_imbalance = n;
        int best_order = 0;
        Box4 acc[3];
        std::uint32_t count[3] = {0, 0, 0};
        for (int i = bins - 1; i >= 1; --i) {
            for (int a = 0; a < 3; ++a) {
                acc[a].grow(bin.lo[a][i], bin.hi[a][i]);
                count[a] += bin.count[a][i];
            }
            alignas(16) float right_area[4];
            simd::store(right_area, areas(acc));
            for (int a = 0; a < 3; ++a) {
                const std::uint32_t nl = left_count[i - 1][a];
                const std::uint32_t nr = count[a];
                if (nl == 0 || nr == 0) continue;
                const float cost =
                    left_area[i - 1][a] * static_cast<float>(nl) + right_area[a] * static_cast<float>(nr);
                const std::uint32_t imbalance = nl > nr ? nl - nr : nr - nl;
                const int order = a * kMaxBins + (bins - 1 - i);
                if (cost < best.cost ||
                    (cost == best.cost &&
                     (imbalance < best_imbalance || (imbalance == best_imbalance && order < best_order)))) {
                    best.axis = a;
                    best.bin = i;
                    best.cost = cost;
                    best_imbalance = imbalance;
                    best_order = order;
                }
            }
        }
        if (best.axis >= 0) {
            for (int i = 0; i < bins; ++i)
                (i < best.bin ? best.left_box : best.right_box).grow(bin.lo[best.axis][i], bin.hi[best.axis][i]);
            if (chunked.chunks >= kMinStableChunks) {
                best.chunk_lefts.assign(chunked.chunks, 0);
                for (std::uint32_t c = 0; c < chunked.chunks; ++c)
                    for (int i = 0; i < best.bin; ++i) best.chunk_lefts[c] += chunked.sets[c].count[best.axis][i];
            }
        }
        best.map = map;
        return best;
    }

    // The per-chunk bins of a node binned in chunks (chunks == 0: binned in one piece).
    struct ChunkBins {
        std::unique_ptr<BinSet[]> sets;
        std::uint32_t chunks = 0;
    };

    // Bins the node's triangles into `local` (returned), a large node in chunks on several
    // threads whose sets are merged into it and kept in `chunked`.
    const BinSet& bin_node(const NodeJob& job, const BinMap& map, BinSet& local, ChunkBins& chunked)
    {
        const std::uint32_t n = job.end - job.begin;
        const auto chunks = static_cast<std::uint32_t>(
            std::min<std::uint32_t>(static_cast<std::uint32_t>(m_pool.threads()),
                                    n / (m_parallel_bin_prims / kMinStableChunks)));
        if (n < m_parallel_bin_prims || chunks < 2) {
            local.reset(map.bins);
            if (n < kSplitBinPrims) {
                local.add(job.refs, job.begin, job.end, map);
            } else {
                BinSet spare;
                local.add_split(job.refs, job.begin, job.end, map, spare);
            }
            return local;
        }
        chunked.sets = std::make_unique<BinSet[]>(chunks);
        chunked.chunks = chunks;
        BinSet* sets = chunked.sets.get();
        m_pool.for_each(chunks, [&, n, chunks, sets](std::size_t c) {
            const auto chunk = static_cast<std::uint32_t>(c);
            BinSet spare;
            sets[c].reset(map.bins);
            sets[c].add_split(job.refs, chunk_begin(job.begin, n, chunk, chunks),
                              chunk_begin(job.begin, n, chunk + 1, chunks), map, spare);
        });
        local.reset(map.bins);
        for (std::uint32_t c = 0; c < chunks; ++c) local.merge(sets[c], map.bins);
        return local;
    }

    static void grow(NodeJob& side, Vec4 lo, Vec4 hi, Vec4 c)
    {
        side.box.grow(lo, hi);
        side.cbox.grow_point(c);
    }

    // In-place two-way partition written out (not std::partition, whose element order is up
    // to the standard library) so the leaf order is the same with every toolchain. Without
    // branches on the side (Lomuto's scheme, always swapping): the sides of neighbouring
    // triangles are unpredictable, and mispredictions cost more than the extra stores. The
    // children's centroid bounds are gathered on the way; their boxes come from the bins.
    std::uint32_t partition(const Split& s, const NodeJob& job, NodeJob& left, NodeJob& right)
    {
        PrimRef* refs = job.refs;
        Box4 cbox[2]; // [0]: right, [1]: left
        std::uint32_t i = job.begin;
        for (std::uint32_t k = job.begin; k < job.end; ++k) {
            Vec4 c;
            const int left_side = goes_left(s, refs[k], c) ? 1 : 0;
            cbox[left_side].grow_point(c);
            // refs[i, k) go right: swapping refs[k] to i keeps that true either way.
            const PrimRef r = refs[k];
            refs[k] = refs[i];
            refs[i] = r;
            i += static_cast<std::uint32_t>(left_side);
        }
        left.box = s.left_box;
        left.cbox = cbox[1];
        right.box = s.right_box;
        right.cbox = cbox[0];
        return i;
    }

    // The partition of a large node, on several threads: a stable one (the left triangles
    // first, each side in its previous order), whose result is unique, so the chunks do not
    // change it. Lomuto's in-place scheme below cannot be cut into chunks: the order it leaves
    // the right side in depends on the whole scan before, so with it the top levels'
    // partitions would run on one thread each while the other cores wait.
    //
    // The node's triangles move into the other array (m_refs <-> m_scratch), where its
    // children are then built, so each reference is read once and written once. The binning
    // chunks' left counts (split.chunk_lefts) place each chunk's left and right runs before a
    // triangle is read; each chunk then writes both runs forward, gathering the centroid
    // bounds of both sides; copying the result back would cost a second pass over the node
    // (docs/decisions/bvh-build-many-cores.md). On one thread the out-of-place pass costs more
    // than Lomuto's, so only nodes binned in kMinStableChunks or more chunks (on as many
    // threads) come here.
    std::uint32_t partition_stable(const Split& s, const NodeJob& job, NodeJob& left, NodeJob& right)
    {
        const std::uint32_t n = job.end - job.begin;
        const auto chunks = static_cast<std::uint32_t>(s.chunk_lefts.size());
        // Per chunk c: its first triangle first[c], and where its left and its right run
        // begin, left_at[c] and right_at[c]. Prefix sums, so a run ends where the next
        // chunk's begins, and entry [chunks] is the end of each side.
        std::vector<std::uint32_t> first(chunks + 1);
        std::vector<std::uint32_t> left_at(chunks + 1);
        std::vector<std::uint32_t> right_at(chunks + 1);
        for (std::uint32_t c = 0; c <= chunks; ++c) first[c] = chunk_begin(job.begin, n, c, chunks);
        left_at[0] = job.begin;
        for (std::uint32_t c = 0; c < chunks; ++c) left_at[c + 1] = left_at[c] + s.chunk_lefts[c];
        right_at[0] = left_at[chunks];
        for (std::uint32_t c = 0; c < chunks; ++c)
            right_at[c + 1] = right_at[c] + (first[c + 1] - first[c] - s.chunk_lefts[c]);
        struct Run {
            Box4 cbox[2]; // [0]: right, [1]: left
            bool as_binned = true;
        };
        std::vector<Run> runs(chunks);
        const PrimRef* from = job.refs;
        PrimRef* to = job.refs == m_refs.data() ? m_scratch.data() : m_refs.data();
        m_pool.for_each(chunks, [&](std::size_t c) {
            Run& run = runs[c];
            std::uint32_t at[2] = {right_at[c], left_at[c]}; // [0]: right, [1]: left
            const std::uint32_t stop[2] = {right_at[c + 1], left_at[c + 1]};
            for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
                Vec4 centre;
                const int side = goes_left(s, from[k], centre) ? 1 : 0;
                // The bins sorted each reference with this arithmetic, so a run never outgrows
                // its place; should that ever break, the guard keeps the chunk out of its
                // neighbours' runs.
                if (at[side] == stop[side]) {
                    run.as_binned = false;
                    return;
                }
                run.cbox[side].grow_point(centre);
                to[at[side]++] = from[k];
            }
        });
        for (const Run& run : runs) {
            if (!run.as_binned) throw std::logic_error("BVH builder: a stable partition disagrees with its bins");
            left.cbox.grow(run.cbox[1]);
            right.cbox.grow(run.cbox[0]);
        }
        left.box = s.left_box;
        right.box = s.right_box;
        left.refs = to;
        right.refs = to;
        return left_at[chunks];
    }

    // Fallback when binning finds no split (all centroids in one bin, or the depth guard):
    // halve by count along the widest centroid axis.
    std::uint32_t median_split(const NodeJob& job, NodeJob& left, NodeJob& right)
    {
        alignas(16) float cmin[4];
        alignas(16) float cmax[4];
        simd::store(cmin, job.cbox.lo);
        simd::store(cmax, job.cbox.hi);
        int axis = -1;
        float widest = 0.0f;
        for (int a = 0; a < 3; ++a) {
            const float extent = cmax[a] - cmin[a];
            if (extent > widest) {
                widest = extent;
                axis = a;
            }
        }
        // By centroid, then by triangle index: a total order, so the halves do not depend on
        // the order the partitions left the triangles in. Coincident centroids (no axis) are
        // ordered by index alone; their halves stay sorted, hence the check before sorting.
        PrimRef* refs = job.refs;
        const auto before = [axis](const PrimRef& x, const PrimRef& y) {
            if (axis >= 0) {
                const float cx = 0.5f * x.lo[axis] + 0.5f * x.hi[axis];
                const float cy = 0.5f * y.lo[axis] + 0.5f * y.hi[axis];
                if (cx != cy) return cx < cy;
            }
            return prim_of(x) < prim_of(y);
        };
        if (!std::is_sorted(refs + job.begin, refs + job.end, before))
            std::sort(refs + job.begin, refs + job.end, before);
        const std::uint32_t mid = job.begin + (job.end - job.begin) / 2;
        for (std::uint32_t i = job.begin; i < job.end; ++i) {
            Vec4 lo;
            Vec4 hi;
            load(refs[i], lo, hi);
            grow(i < mid ? left : right, lo, hi, centroid(lo, hi));
        }
        return mid;
    }

    BigArray<PrimRef>& m_refs;
    BigArray<PrimRef> m_scratch;
    BvhTree& m_tree;
    const BvhBuildOptions& m_options;
    TaskPool& m_pool;
    std::vector<Arena> m_arenas;
    std::atomic<std::uint32_t> m_next_block{1}; // slot 0 is the root
    std::uint32_t m_min_task_prims = kMinTaskCeiling;
    std::uint32_t m_parallel_bin_prims = kParallelBinCeiling;
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

// The arrays that the bounds pass, flatten and the device upload index per triangle, which a
// Scene made in code (not by a loader) might lack: sizes only here; flatten checks each
// material index.
void check_per_triangle_arrays(const Scene& scene)
{
    const std::size_t count = scene.triangle_count();
    auto expect = [&](const char* what, std::size_t size, std::size_t per_triangle, bool may_be_empty) {
        if (size != per_triangle * count && !(may_be_empty && size == 0))
            throw InputError(scene.name_for_messages() + ": scene has " + std::to_string(count) + " triangles but " +
                             std::to_string(size) + " " + what + " (expected " + std::to_string(per_triangle) +
                             " per triangle" + (may_be_empty ? ", or none)" : ")"));
    };
    expect("vertex positions", scene.positions.size(), 3, false);
    expect("vertex normals", scene.normals.size(), 3, false);
    expect("texture coordinates", scene.uvs.size(), 3, true);
    expect("tangents", scene.tangents.size(), 3, true);
    expect("vertex-normal flags", scene.has_vertex_normals.size(), 1, true);
    if (count > 0 && scene.materials.empty())
        throw InputError(scene.name_for_messages() + ": scene has " + std::to_string(count) +
                         " triangles but no materials");
}

// One chunk of the bounds pass: references for triangles [begin, end), their joint bounds,
// and the first triangle with a non-finite vertex (count if none).
struct PrimChunk {
    Box4 box;
    Box4 cbox;
    std::size_t first_bad;
};

PrimChunk make_refs(const Scene& scene, PrimRef* refs, std::size_t begin, std::size_t end, std::size_t count)
{
    PrimChunk chunk{{}, {}, count};
    for (std::size_t t = begin; t < end; ++t) {
        const Point3 v0 = scene.vertex(t, 0);
        const Point3 v1 = scene.vertex(t, 1);
        const Point3 v2 = scene.vertex(t, 2);
        if (!is_finite(v0) || !is_finite(v1) || !is_finite(v2)) {
            chunk.first_bad = t;
            return chunk;
        }
        const Vec4 a = simd::make(v0.x, v0.y, v0.z, 0.0f);
        const Vec4 b = simd::make(v1.x, v1.y, v1.z, 0.0f);
        const Vec4 c = simd::make(v2.x, v2.y, v2.z, 0.0f);
        const Vec4 lo = simd::min(simd::min(a, b), c);
        const Vec4 hi = simd::max(simd::max(a, b), c);
        PrimRef& r = refs[t];
        simd::store(r.lo, lo);
        simd::store(r.hi, hi);
        const auto prim = static_cast<std::uint32_t>(t);
        std::memcpy(&r.lo[3], &prim, sizeof prim); // bits, not a number: no float move on the way
        chunk.box.grow(lo, hi);
        chunk.cbox.grow_point(centroid(lo, hi));
    }
    return chunk;
}

}  // namespace

BvhTree build_bvh_tree(const Scene& scene, const BvhBuildOptions& options)
{
    check_options(options);
    const std::size_t count = scene.triangle_count();
    check_per_triangle_arrays(scene);
    // Node indices are 32-bit and a tree has up to 2n - 1 nodes.
    if (count >= (std::size_t{1} << 31))
        throw InputError(scene.name_for_messages() + ": " + std::to_string(count) +
                         " triangles are more than the BVH's 32-bit indices can address (2^31 - 1)");

    BvhTree tree;
    if (count == 0) return tree;

    int threads = options.threads;
    if (threads == 0) threads = host_thread_count();
    // Threads beyond what the scene can keep busy would only cost their start.
    threads = static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(threads), 1 + count / kMinTaskFloor));
    TaskPool pool(threads);

    // Triangle bounds in chunks; the chunks' results are joined in order, so the error names
    // the first bad triangle whatever the thread count.
    using Clock = std::chrono::steady_clock;
    const auto bounds_start = Clock::now();
    BigArray<PrimRef> refs(count);
    const std::size_t chunks = (count + kPrimChunk - 1) / kPrimChunk;
    std::vector<PrimChunk> parts(chunks);
    pool.for_each(chunks, [&](std::size_t c) {
        parts[c] = make_refs(scene, refs.data(), c * kPrimChunk, std::min<std::size_t>(count, (c + 1) * kPrimChunk), count);
    });
    Box4 box;
    Box4 cbox;
    for (const PrimChunk& p : parts) {
        if (p.first_bad < count)
            throw InputError(scene.name_for_messages() + ": triangle " + std::to_string(p.first_bad) +
                             " has a non-finite vertex coordinate (NaN or infinity)");
        box.grow(p.box);
        cbox.grow(p.cbox);
    }
    tree.bounds_seconds = std::chrono::duration<double>(Clock::now() - bounds_start).count();

    Builder builder(refs, tree, options, pool);
    builder.build_root(box, cbox);
    return tree;
}

}  // namespace gc
