// GEOCOLD_GUARD_BUFFERS=1 (host/cl/guarded_memory.h): a buffer's memory ends at an inaccessible
// page, so a read past its end faults, on the host and in a kernel on a CPU device, where
// without the guard it reads a neighbour's bytes unnoticed.
#include "host/cl/guarded_memory.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#include "cl_test_util.h"
#include "host/cl/buffer.h"
#include "host/cl/kernel.h"
#include "host/cl/program.h"

namespace gc::cl {
namespace {

constexpr const char* k_read_at_cl = R"(
__kernel void read_at(__global const uint* data, __global uint* out, uint i)
{
    if (get_global_id(0) == 0) out[0] = data[i];
}
)";

TEST(GuardedAllocation, TheFirstByteAfterTheRoundedEndFaults)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    const std::shared_ptr<void> memory = guarded_allocation(100);
    auto* bytes = static_cast<volatile unsigned char*>(memory.get());
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(memory.get()) % 16, 0u);
    for (int i = 0; i < 112; ++i) bytes[i] = static_cast<unsigned char>(i);  // 100 rounded up to 16
    EXPECT_EQ(bytes[0], 0u);
    EXPECT_EQ(bytes[111], 111u);
    EXPECT_EXIT(bytes[112] = 1, testing::KilledBySignal(SIGSEGV), "");
}

// The flag is read once per process: each test of this binary sets it before its first buffer.
class GuardedBufferTest : public test::DeviceTest {
protected:
    void SetUp() override
    {
        ::setenv("GEOCOLD_GUARD_BUFFERS", "1", 1);
        DeviceTest::SetUp();
        if (IsSkipped()) return;
        if (!context->device().is_cpu) GTEST_SKIP() << "the guard applies to CPU devices";
        dir.write("read_at.cl", k_read_at_cl);
        program = std::make_unique<Program>(*context, "read_at.cl", "", BuildConfig{dir.path(), {}, false});
    }

    // What the kernel reads at element i of a 4-element buffer {10, 11, 12, 13}.
    std::uint32_t read_at(std::uint32_t i)
    {
        const std::vector<std::uint32_t> values = {10, 11, 12, 13};
        auto data = read_only_buffer(*context, values, "four values");
        auto out = Buffer<std::uint32_t>::create(*context, 1, CL_MEM_READ_WRITE, "out");
        Kernel kernel = program->kernel("read_at");
        kernel.set_args(data, out, i);
        kernel.launch(*context, 1, 1, "read_at");
        std::uint32_t value = 0;
        out.read(std::span<std::uint32_t>(&value, 1));
        return value;
    }

    test::TempKernelDir dir;
    std::unique_ptr<Program> program;
};

TEST_F(GuardedBufferTest, AKernelReadingPastTheEndFaults)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    ASSERT_TRUE(guarded_buffers_enabled());
    EXPECT_EQ(read_at(3), 13u);
    EXPECT_EXIT(read_at(4), testing::KilledBySignal(SIGSEGV), "");
}

}  // namespace
}  // namespace gc::cl
