// geocold-bench's BVH build figures for one scene: our binned-SAH tree against Embree's
// rtcBuildBVH with the same constants (speed and SAH cost), and what a CPU render builds
// before it traces on each side (our tree, device layout and BVH8 collapse; Embree's scene
// commit).
#pragma once

#include <memory>

#include <nlohmann/json.hpp>

#include "host/bvh/bvh.h"
#include "tools/bench/bench_options.h"
#include "tools/bench/bench_scenes.h"
#include "tools/bench/embree_bench.h"

namespace gc::bench {

// What the scene's later figures trace: our BVH, and Embree's committed scene (null without
// Embree).
struct BuiltScene {
    FlatBvh bvh;
    std::unique_ptr<EmbreeTracer> embree;
};

// Prints the build lines and fills out["build"].
BuiltScene measure_build(const BenchScene& s, const Options& o, nlohmann::json& out);

}  // namespace gc::bench
