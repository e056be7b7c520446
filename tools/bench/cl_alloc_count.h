// Our own count of OpenCL buffer bytes (cl_alloc_count.cpp): what the process holds now and
// the most it held since the last reset_alloc_peak. Independent of what the driver reserves
// beside them (nvidia-smi's figure in tools/device/gradients.sh shows that).
#pragma once

#include <cstddef>

namespace gc::bench {

struct AllocCount {
    std::size_t live = 0;     // bytes in buffers not yet released
    std::size_t peak = 0;     // the most live bytes since the last reset_alloc_peak
    std::size_t buffers = 0;  // buffers not yet released
};

AllocCount alloc_count();
void reset_alloc_peak();  // peak = live

}  // namespace gc::bench
