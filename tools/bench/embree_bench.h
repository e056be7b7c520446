// Embree 3 as the CPU yardstick: the same triangles, the same rays, all cores. Compiled to
// stubs that report "not available" when CMake did not find Embree (GC_HAVE_EMBREE unset),
// so the benchmark builds on machines without it (the bare GPU preset).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gc_types.h"
#include "host/bvh/builder.h"
#include "host/scene/scene.h"

namespace gc::bench {

bool embree_available();
std::string embree_version(); // "" when not available

// rtcBuildBVH with our own node callbacks: a BVH2 from Embree's binned SAH builder (quality
// MEDIUM), the same leaf size and SAH constants as ours, priced with exactly the formula
// of bvh_stats. Also the time of Embree's own scene commit (its BVH4/8 for tracing).
struct EmbreeBuildFigures {
    double bvh2_seconds = 0.0;
    double prims_seconds = 0.0; // of which the primitive array (the triangles' bounds)
    float bvh2_sah = 0.0f;
    std::size_t bvh2_nodes = 0;
};
EmbreeBuildFigures embree_build_bvh2(const Scene& scene, const BvhBuildOptions& options);

// A committed Embree scene over the scene's triangles, ready to trace.
class EmbreeTracer {
public:
    explicit EmbreeTracer(const Scene& scene);
    ~EmbreeTracer();
    EmbreeTracer(const EmbreeTracer&) = delete;
    EmbreeTracer& operator=(const EmbreeTracer&) = delete;

    double commit_seconds() const;
    // Traces every ray on `threads` std::threads with rtcIntersect1 / rtcOccluded1 (width 1)
    // or rtcIntersect16 / rtcOccluded16 (width 16). Returns wall seconds. prims: the hit
    // triangle (GC_INVALID on a miss) or the occlusion flag, to check agreement with ours.
    double closest(const std::vector<dev::GcRay>& rays, int threads, int width, std::vector<std::uint32_t>& prims) const;
    double occluded(const std::vector<dev::GcRay>& rays, int threads, int width, std::vector<std::uint32_t>& flags) const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

}  // namespace gc::bench
