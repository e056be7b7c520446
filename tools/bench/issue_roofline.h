// The instruction half of the GPU roofline: a ray's traversal work (inner nodes visited,
// triangles tested, from the host's count in rays.h) times what each unit compiles to,
// against the rate at which the GPU issues instructions. With the memory half (bytes per ray
// against copy bandwidth) it says whether a ray figure is bound by bandwidth, by issue, or
// by neither (latency).
//
// Instructions per unit are static PTX counts: kernels/test/roofline_probe.cl does each unit once
// and twice, and the difference of the two kernels' counts is the unit. So:
//   - a triangle test counts all of its instructions, although most tests stop at the
//     inside test (more than issued);
//   - pops, the leaf loop and the node reloads after a pop are not counted (fewer);
//   - PTX is not machine code: ptxas expands a correctly rounded division into several
//     instructions and folds others.
// The result is an estimate for telling issue-bound from not, not an exact ceiling.
#pragma once

#include <string>

#include "host/cl/context.h"
#include "host/cl/program.h"
#include "tools/bench/rays.h"

namespace gc::bench {

struct IssueModel {
    bool available = false;
    std::string why_not;  // when !available: what is missing (not NVIDIA, an old GPU, ...)

    // PTX instructions per unit of BVH2 traversal.
    double setup = 0.0;     // per ray
    double inner = 0.0;     // per inner node visited (both children's boxes)
    double triangle = 0.0;  // per triangle tested

    // Lane instructions per second: SMs x schedulers x warp width x clock.
    double issue_rate = 0.0;
    std::string rate_text;  // how issue_rate was made, e.g. "132 SMs x 4 x 32 lanes x 1980 MHz"

    double instructions_per_ray(const TraversalCost& c) const
    {
        return setup + inner * c.inner_visits + triangle * c.triangle_tests;
    }
    double bound_rays_per_s(const TraversalCost& c) const { return issue_rate / instructions_per_ray(c); }
};

// Builds kernels/test/roofline_probe.cl on the context's device and counts its PTX. Available on
// NVIDIA GPUs of compute capability 7.0 or later (four schedulers per SM, each issuing one
// warp instruction per clock); elsewhere why_not says why not. Throws only on build errors.
IssueModel issue_model(const cl::Context& context, const cl::BuildConfig& build = {});

}  // namespace gc::bench
