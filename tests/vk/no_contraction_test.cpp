// host/vk/no_contraction: every floating-point result of the embedded shaders gets a
// NoContraction decoration, placed where SPIR-V allows annotations, and broken modules are
// refused. (That lavapipe then renders the same bits as PoCL is what the cross-check and
// consistency tests measure.)
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <stdexcept>
#include <vector>

#include "host/vk/no_contraction.h"
#include "host/vk/shaders.h"

namespace gc::vk {
namespace {

struct Census {
    std::set<std::uint32_t> float_results;  // results of FAdd, FSub, FMul, FDiv, VectorTimesScalar, Dot, ...
    std::set<std::uint32_t> no_contraction; // ids decorated NoContraction
    bool decoration_after_types = false;    // an OpDecorate after the first type declaration
};

Census census(const std::vector<std::uint32_t>& m)
{
    Census c;
    bool types_seen = false;
    for (std::size_t i = 5; i < m.size(); i += m[i] >> 16) {
        const std::uint32_t op = m[i] & 0xffffu;
        if (op >= 19 && op <= 39) types_seen = true;  // OpTypeVoid .. OpTypeForwardPointer
        if (op == 71) {
            if (types_seen) c.decoration_after_types = true;
            if (m[i + 2] == 42) c.no_contraction.insert(m[i + 1]);
        }
        if (op == 129 || op == 131 || op == 133 || op == 136 || op == 142 || op == 148) c.float_results.insert(m[i + 2]);
    }
    return c;
}

TEST(NoContraction, EveryFloatResultOfThePathShaderIsDecorated)
{
    const std::span<const std::uint32_t> original = shaders::path_comp();
    const Census before = census({original.begin(), original.end()});
    const Census after = census(without_contraction(original));
    std::printf("path.comp: %zu float arithmetic results; NoContraction on %zu before, %zu after\n",
                after.float_results.size(), before.no_contraction.size(), after.no_contraction.size());
    ASSERT_GT(after.float_results.size(), 100u);
    EXPECT_LT(before.no_contraction.size(), before.float_results.size());
    for (const std::uint32_t id : after.float_results) EXPECT_TRUE(after.no_contraction.count(id)) << "id " << id;
    EXPECT_FALSE(after.decoration_after_types);
}

TEST(NoContraction, IsIdempotent)
{
    const std::vector<std::uint32_t> once = without_contraction(shaders::whitted_comp());
    EXPECT_EQ(without_contraction(once), once);
}

TEST(NoContraction, RefusesWhatIsNotSpirv)
{
    const std::vector<std::uint32_t> not_spirv = {1, 2, 3, 4, 5, 6};
    EXPECT_THROW(without_contraction(not_spirv), std::invalid_argument);
    std::vector<std::uint32_t> truncated(shaders::aov_comp().begin(), shaders::aov_comp().end());
    truncated.resize(truncated.size() - 1);
    truncated.back() = (200u << 16) | 5u;  // an OpName claiming 200 words near the end
    EXPECT_THROW(without_contraction(truncated), std::invalid_argument);
}

}  // namespace
}  // namespace gc::vk
