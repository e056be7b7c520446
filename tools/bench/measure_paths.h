// geocold-bench's path-tracing figures for one scene: samples per second on every device at
// the settings (max depth 8, no Russian roulette), with the device bytes per
// triangle and the fixed Mitsuba 3 anchors; and the view they render, which
// tools/bench/mitsuba_yardstick.py reads to time Mitsuba 3 on it in the same run.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "host/bvh/bvh.h"
#include "tools/bench/bench_devices.h"
#include "tools/bench/bench_options.h"
#include "tools/bench/bench_scenes.h"

namespace gc::bench {

// The scene file, camera, resolution and path settings of the path figures. "source" is
// empty for a generated scene.
nlohmann::json path_view(const BenchScene& s);

// Prints one path line per device and fills out["path"]; the Cornell box's samples per
// second also go to summary["cornell_path"]["gpu" or "cpu"].
void measure_paths(const BenchScene& s, const Options& o, std::vector<DeviceSlot>& devices, const FlatBvh& bvh,
                   nlohmann::json& out, nlohmann::json& summary);

}  // namespace gc::bench
