#include "tools/bench/measure_build.h"

#include <algorithm>
#include <vector>

#include "host/bvh/widen.h"
#include "host/util/host_threads.h"
#include "tools/bench/bench_output.h"
#include "tools/bench/timing.h"

namespace gc::bench {

BuiltScene measure_build(const BenchScene& s, const Options& o, nlohmann::json& out)
{
    const std::size_t tris = s.scene.triangle_count();
    const int threads = host_thread_count();
    // Ours vs Embree's binned SAH BVH2 (rtcBuildBVH) with the same constants, in interleaved
    // rounds (ours, then Embree's) so that a change in the machine's load hits both alike:
    // the speed ratio is the median of the per-round ratios. Builds under 0.1 s get at least
    // 9 rounds; one build is too short to time on a shared machine. Each round
    // also times what a CPU render builds before it traces, on both sides: our BVH2 plus its
    // collapse into the BVH8 the CPU kernels trace (widen8, done at upload), and Embree's
    // scene commit (its BVH4/8); the last round's Embree scene traces the rays below.
    const BvhBuildOptions build_options;
    const bool with_embree = embree_available();
    int build_repeats = tris > 1000000 ? std::min(o.repeats, 3) : o.repeats;
    std::vector<double> ours_build, ours_layout, embree_build, build_ratios, collapse, commit, pipeline_ratios;
    std::vector<double> ours_bounds, embree_prims; // the bounds pass each side's time starts with
    FlatBvh bvh;
    EmbreeBuildFigures embree_fig;
    std::unique_ptr<EmbreeTracer> embree;
    for (int r = 0; r < build_repeats; ++r) {
        // The tree (triangle bounds, binned SAH) is what rtcBuildBVH makes; the device layout
        // (flatten: depth-first nodes and the triangles' vertices gathered in leaf order) is
        // timed apart and counted in the CPU start below.
        bvh = build_bvh(s.scene, build_options);
        ours_build.push_back(bvh.tree_seconds);
        ours_bounds.push_back(bvh.bounds_seconds);
        ours_layout.push_back(bvh.build_seconds - bvh.tree_seconds);
        const auto collapse_start = Clock::now();
        const Wide8Bvh wide = widen8(bvh);
        collapse.push_back(seconds_since(collapse_start));
        if (with_embree) {
            embree_fig = embree_build_bvh2(s.scene, build_options);
            embree_build.push_back(embree_fig.bvh2_seconds);
            embree_prims.push_back(embree_fig.prims_seconds);
            build_ratios.push_back(embree_fig.bvh2_seconds / ours_build.back());
            embree.reset();  // one Embree scene at a time: the large one takes gigabytes
            embree = std::make_unique<EmbreeTracer>(s.scene);
            commit.push_back(embree->commit_seconds());
            pipeline_ratios.push_back(commit.back() / (bvh.build_seconds + collapse.back()));
        }
        if (r == 0 && bvh.build_seconds < 0.1 && !o.quick) build_repeats = std::max(build_repeats, 9);
    }
    const BvhStats stats = bvh_stats(bvh, build_options.traversal_cost, build_options.intersection_cost);
    const double ours_build_s = median(ours_build);
    const double ours_mtris = double(tris) / ours_build_s / 1e6;
    const double layout_s = median(ours_layout);
    const double collapse_s = median(collapse);
    // The bounds pass is timed apart on both sides: it is memory-bound and scales unlike the
    // binning below it, so the two parts of a gap are told apart.
    const double bounds_s = median(ours_bounds);
    say("BVH build  ours: %.3f s = %.2f Mtris/s (bounds pass %.3f s), SAH %.2f, %zu nodes, depth %zu (%d threads, "
        "median of %d); device layout %.3f s, BVH8 collapse %.3f s\n",
        ours_build_s, ours_mtris, bounds_s, stats.sah_cost, stats.nodes, stats.max_depth, threads, build_repeats,
        layout_s, collapse_s);
    out["build"] = {{"seconds", ours_build_s}, {"mtris_per_s", ours_mtris}, {"bounds_seconds", bounds_s},
                    {"sah", stats.sah_cost}, {"nodes", stats.nodes}, {"depth", stats.max_depth}, {"rounds", build_repeats},
                    {"layout_seconds", layout_s}, {"bvh8_collapse_seconds", collapse_s}};

    if (with_embree) {
        const double e_s = median(embree_build);
        const double e_mtris = double(tris) / e_s / 1e6;
        const double speed_ratio = median(build_ratios);
        const double commit_s = median(commit);
        const double pipeline_ratio = median(pipeline_ratios);
        const double prims_s = median(embree_prims);
        say("           Embree rtcBuildBVH BVH2: %.3f s = %.2f Mtris/s (primitive array %.3f s), SAH %.2f, %zu nodes | "
            "ours/Embree: speed %.2fx (median of per-round ratios), SAH %s\n",
            e_s, e_mtris, prims_s, embree_fig.bvh2_sah, embree_fig.bvh2_nodes, speed_ratio,
            ratio(stats.sah_cost, embree_fig.bvh2_sah).c_str());
        say("           CPU start: ours BVH2 + device layout + BVH8 collapse %.3f s | Embree scene commit (its BVH4/8) "
            "%.3f s | ours/Embree speed %.2fx (median of per-round ratios)\n",
            ours_build_s + layout_s + collapse_s, commit_s, pipeline_ratio);
        out["build"]["embree_bvh2"] = {{"seconds", e_s}, {"mtris_per_s", e_mtris}, {"prims_seconds", prims_s},
                                       {"sah", embree_fig.bvh2_sah},
                                       {"nodes", embree_fig.bvh2_nodes}};
        out["build"]["embree_commit_seconds"] = commit_s;
        out["build"]["ratio_speed"] = speed_ratio;
        out["build"]["ratio_sah"] = stats.sah_cost / embree_fig.bvh2_sah;
        out["build"]["ratio_cpu_start"] = pipeline_ratio;
    } else {
        say("           Embree: not built in (no yardstick)\n");
    }
    return {std::move(bvh), std::move(embree)};
}

}  // namespace gc::bench
