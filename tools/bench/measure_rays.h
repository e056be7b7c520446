// geocold-bench's ray figures for one scene: primary, diffuse and shadow rays (rays.h) traced
// by Embree's single-ray and 16-wide calls and by every device, each device's figure with
// its ratio to Embree's best and, on GPUs, its share of the memory and issue rooflines.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "host/bvh/bvh.h"
#include "tools/bench/bench_devices.h"
#include "tools/bench/bench_options.h"
#include "tools/bench/bench_scenes.h"
#include "tools/bench/embree_bench.h"

namespace gc::bench {

// Prints the scene's ray lines and fills out["rays"]. `embree` may be null (no yardstick).
// Throws when a device's packets of eight disagree with its single rays.
void measure_rays(const BenchScene& s, const Options& o, std::vector<DeviceSlot>& devices, const FlatBvh& bvh,
                  const EmbreeTracer* embree, nlohmann::json& out);

}  // namespace gc::bench
