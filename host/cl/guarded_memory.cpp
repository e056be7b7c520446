#include "host/cl/guarded_memory.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>

namespace gc::cl {

bool guarded_buffers_enabled()
{
    static const bool enabled = [] {
        const char* v = std::getenv("GEOCOLD_GUARD_BUFFERS");
        return v != nullptr && std::strcmp(v, "1") == 0;
    }();
    return enabled;
}

std::shared_ptr<void> guarded_allocation(std::size_t bytes)
{
    const std::size_t page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
    // 16 bytes: the widest type a kernel loads (float4, uint4) keeps its alignment.
    const std::size_t used = (std::max<std::size_t>(bytes, 1) + 15) / 16 * 16;
    const std::size_t mapped = (used + page - 1) / page * page + page;
    void* base = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (base == MAP_FAILED) throw std::bad_alloc();
    char* guard = static_cast<char*>(base) + mapped - page;
    if (mprotect(guard, page, PROT_NONE) != 0) {
        munmap(base, mapped);
        throw std::bad_alloc();
    }
    return std::shared_ptr<void>(guard - used, [base, mapped](void*) { munmap(base, mapped); });
}

}  // namespace gc::cl
