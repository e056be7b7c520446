// A debugging aid for kernels on CPU devices: with GEOCOLD_GUARD_BUFFERS=1, every device
// buffer lives in host memory that ends where an inaccessible page begins, so a kernel that
// reads or writes past a buffer's end faults there and then, as it would on a GPU, instead of
// reading a neighbouring allocation's bytes (a CPU driver's allocations lie side by side, and
// even valgrind does not see a kernel's reads between them).
#pragma once

#include <cstddef>
#include <memory>

namespace gc::cl {

// Whether GEOCOLD_GUARD_BUFFERS=1 (read once per process).
bool guarded_buffers_enabled();

// `bytes` (at least 1) of zeroed memory, 16-byte aligned, whose end lies less than 16 bytes
// before an inaccessible page; freed when the last owner lets go. Throws std::bad_alloc.
std::shared_ptr<void> guarded_allocation(std::size_t bytes);

}  // namespace gc::cl
