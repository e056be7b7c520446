// Small kernel sources the device tests build from a temporary kernel directory.
#pragma once

namespace gc::cl::test {

// data[i] = sqrt(x) / (x + k) * SCALE for i < n (bounds-checked, per the launch contract).
inline constexpr const char* compute_cl = R"(#include "gc_platform.h"
#ifndef SCALE
#define SCALE 1.0f
#endif
__kernel void compute(__global float* data, uint n, float k)
{
    const uint i = get_global_id(0);
    if (i >= n) return;
    const float x = (float)i + 0.5f;
    data[i] = sqrt(x) / (x + k) * SCALE;
}

__kernel void count_items(__global uint* hits, uint n)
{
    const uint i = get_global_id(0);
    if (i >= n) return;
    atomic_inc(hits);
}
)";

}  // namespace gc::cl::test
