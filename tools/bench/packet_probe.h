// Explicit SIMD across paths, measured: kernels/test/packet_probe.cl's Lambert vertex with one
// vertex per work-item (as the renderer's kernels work) against 8 and 16 per work-item in
// OpenCL vector lanes, on one device, in interleaved rounds.
#pragma once

#include <cstddef>
#include <string>

#include "host/cl/context.h"
#include "host/cl/program.h"

namespace gc::bench {

struct PacketProbeFigures {
    double x1_mvertices = 0.0;   // one vertex per work-item, Mvertices/s (median)
    double x8_mvertices = 0.0;   // eight per work-item in float8 lanes
    double x16_mvertices = 0.0;  // sixteen per work-item in float16 lanes
    double x8_ratio = 0.0;       // median of the per-round ratios to x1
    double x16_ratio = 0.0;
    std::size_t outputs = 0;     // output floats compared per form
    std::size_t differing = 0;   // of those, how many differ from x1 in their bits (x8 and x16)
};

// `vertices` is rounded up to a multiple of 16; `rounds` >= 1.
PacketProbeFigures run_packet_probe(const cl::Context& context, std::size_t vertices, int rounds,
                                    const cl::BuildConfig& build = {});

}  // namespace gc::bench
