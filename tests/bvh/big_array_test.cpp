// BigArray (host/bvh/big_array.h): what the BVH module relies on when it stores its large
// arrays there. Arrays of 8 MiB or more start on a 2 MiB boundary (the precondition for the
// kernel to back them with huge pages), smaller ones come from the ordinary allocator, and
// both behave as std::vector for every value written.
#include <cstdint>
#include <cstdio>
#include <numeric>

#include <gtest/gtest.h>

#include "host/bvh/big_array.h"

namespace gc::test {
namespace {

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

TEST(BigArray, LargeArraysStartOnAHugePageBoundary)
{
    const std::size_t count = kHugePageMinBytes / sizeof(std::uint32_t) + 12345; // just over the threshold
    BigArray<std::uint32_t> big(count);
    std::iota(big.begin(), big.end(), 0u);
    std::printf("BigArray: %zu bytes at offset %zu within a 2 MiB page\n", count * sizeof(std::uint32_t),
                static_cast<std::size_t>(address(big.data()) % kHugePageBytes));
    EXPECT_EQ(address(big.data()) % kHugePageBytes, 0u);
    EXPECT_EQ(big.front(), 0u);
    EXPECT_EQ(big.back(), count - 1);

    // Growing past the reservation moves the elements to a new large block.
    big.push_back(7u);
    EXPECT_EQ(address(big.data()) % kHugePageBytes, 0u);
    EXPECT_EQ(big[count - 1], count - 1);
    EXPECT_EQ(big.back(), 7u);
}

TEST(BigArray, SmallArraysAndCopiesBehaveAsVectors)
{
    BigArray<int> small = {3, 1, 4, 1, 5};
    BigArray<int> copy = small;
    EXPECT_EQ(copy, small);
    copy.resize(3);
    copy.push_back(9);
    EXPECT_EQ(copy, (BigArray<int>{3, 1, 4, 9}));

    // A copy of a large array is large too, and equal element for element.
    BigArray<float> large(kHugePageMinBytes / sizeof(float));
    for (std::size_t i = 0; i < large.size(); ++i) large[i] = static_cast<float>(i % 977);
    const BigArray<float> large_copy = large;
    EXPECT_EQ(address(large_copy.data()) % kHugePageBytes, 0u);
    EXPECT_EQ(large_copy, large);
}

}  // namespace
}  // namespace gc::test
