#include "host/bvh/big_array.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace gc {

void advise_huge_pages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) noexcept
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    // A hint only: a kernel without THP, or with THP "never", refuses it and small pages
    // serve, so the result is not checked.
    (void)madvise(data, bytes, MADV_HUGEPAGE);
#endif
}

}  // namespace gc
