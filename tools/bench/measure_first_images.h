// geocold-bench's start-up figures: time to first image of each scene on each device, cold
// (empty kernel caches) and warm, each in a fresh child process (first_image.h).
#pragma once

#include <nlohmann/json.hpp>

#include "tools/bench/bench_options.h"

namespace gc::bench {

// Prints the cold and warm lines and fills doc["first_image"]. Must run before this process
// touches OpenCL (see measure_first_images.cpp). Does nothing without o.first_image.
void measure_first_images(const Options& o, nlohmann::json& doc);

// The child that lists the devices for it: one line per selected device, "<label>\t<key>".
int list_device_keys(const Options& o);

}  // namespace gc::bench
