// `geocold-cl --consistency SCENE`: renders the scene on every OpenCL device present (and on
// Vulkan, when this build has it and a Vulkan device exists) with one seed, spp and
// resolution, and compares every pair (host/app/consistency_report.h says how). Prints the
// table; `--json FILE` writes it as JSON, `--heatmap DIR` a difference heat map per pair
// (PNG with OpenImageIO, else PPM).
//
// Defaults for a consistency run: 64 spp and 128x128 unless --spp / --res say otherwise.
// Exit status: 0 when every pair passes, 6 (ExitCode::Mismatch) when one fails. With fewer
// than two devices nothing can be compared: the report says "consistency: SKIPPED" and the
// exit status is 0 (a machine with one device is not an error); scripts and ctest that must
// not pass vacuously look for that line (tests/consistency does, with
// SKIP_REGULAR_EXPRESSION).
#pragma once

#include "host/app/options.h"
#include "host/util/error.h"

namespace gc {

ExitCode run_consistency(const Options& options);

}  // namespace gc
