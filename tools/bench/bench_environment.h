// geocold-bench's render setup: geocold-cl's documented variables (host/app/environment.h), so
// that tools/bench/kernel-ab.sh and A/B runs set them the same way, plus two of its own for
// A/B runs of the wavefront's scheduling (tools/bench/gpu.sh):
//   GEOCOLD_WAVEFRONT_GRID=N   0, 1, 64, ... 8192 work-items per compute unit on every launch
//                              after the first bounce (DeviceTuning::wavefront_items_per_unit)
//   GEOCOLD_WAVEFRONT_SYNC=0|1 whether the host reads each bounce's queue lengths back
//                              (DeviceTuning::wavefront_sync_counts)
#pragma once

#include "host/render/render_setup.h"

namespace gc::bench {

// Read once per process; a value outside a variable's choices is a UsageError naming it.
const RenderSetup& bench_render_setup();

}  // namespace gc::bench
