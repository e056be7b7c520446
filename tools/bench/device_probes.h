// geocold-bench's figures measured once per device rather than per scene: the explicit-SIMD
// probe behind the CPU shading design (packet_probe.h), and the GPU issue rate with the
// instructions each unit of traversal compiles to (issue_roofline.h).
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

#include "tools/bench/bench_devices.h"
#include "tools/bench/bench_options.h"

namespace gc::bench {

// One line per device; fills doc["packet_probe"].
void measure_packet_probe(const Options& o, std::vector<DeviceSlot>& devices, nlohmann::json& doc);

// Sets d.issue, which the ray lines then give each figure's share of, prints it and fills
// j["issue"]. A probe that fails to build leaves d.issue unavailable, with why.
void report_issue_model(DeviceSlot& d, nlohmann::json& j);

}  // namespace gc::bench
