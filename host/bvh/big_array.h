// Storage for the BVH module's large arrays (a 5M-triangle scene's references, build nodes,
// device nodes and triangles: hundreds of MB each), which are sized once up front and then
// written, every element exactly once, by the builder or flatten().
//
//     BigArray<PrimRef> refs(count);   // uninitialised, on transparent huge pages if large
//
// Three things differ from std::vector's default allocator:
// - resize() leaves trivial elements uninitialised: zero-filling first would be a wasted pass
//   over the memory, and the first touch of each page would fall to it.
// - An allocation of kHugePageMinBytes or more is aligned to 2 MiB and advised as a candidate
//   for transparent huge pages (madvise MADV_HUGEPAGE, Linux), as Embree does for its own
//   large allocations: on 4 KiB pages, the first touch of a large scene's flat nodes and
//   triangles is a page fault every 4 KiB, a large share of flatten()'s time
//   (docs/decisions/host-memory-in-place.md). The advice is a hint: where it is refused, the
//   memory is used on small pages.
// - Smaller allocations are aligned to kSmallArrayAlign (128 bytes).
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace gc {

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
inline constexpr std::size_t kHugePageMinBytes = std::size_t{8} << 20;
// Smaller arrays are aligned to 128 bytes: what CPU OpenCL devices (PoCL) ask of host memory
// they read in place (cl::Buffer::over_host), so a small scene's wide BVH is traced in place
// too, and no element straddles two cache lines more than its size forces.
inline constexpr std::size_t kSmallArrayAlign = 128;

// Asks the kernel to back [data, data + bytes) with transparent huge pages. No-op where
// madvise or MADV_HUGEPAGE is missing.
void advise_huge_pages(void* data, std::size_t bytes) noexcept;

template <class T>
struct BigArrayAllocator {
    using value_type = T;

    BigArrayAllocator() = default;
    template <class U>
    BigArrayAllocator(const BigArrayAllocator<U>&) noexcept
    {
    }

    T* allocate(std::size_t n)
    {
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kHugePageMinBytes) return static_cast<T*>(::operator new(bytes, std::align_val_t{kSmallArrayAlign}));
        void* p = ::operator new(rounded(bytes), std::align_val_t{kHugePageBytes});
        advise_huge_pages(p, rounded(bytes));
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept
    {
        const std::size_t bytes = n * sizeof(T);
        if (bytes < kHugePageMinBytes) return ::operator delete(p, bytes, std::align_val_t{kSmallArrayAlign});
        ::operator delete(p, rounded(bytes), std::align_val_t{kHugePageBytes});
    }

    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>)
    {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args)
    {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    friend bool operator==(const BigArrayAllocator&, const BigArrayAllocator&) noexcept { return true; }

private:
    static std::size_t rounded(std::size_t bytes) { return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes; }
};

template <class T>
using BigArray = std::vector<T, BigArrayAllocator<T>>;

}  // namespace gc
