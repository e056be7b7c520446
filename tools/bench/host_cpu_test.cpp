// What geocold-bench records of the CPU it ran on, from /proc/cpuinfo texts of the two
// machines the project measures on and of an Arm server.
#include <cstdio>
#include <sstream>

#include <gtest/gtest.h>

#include "tools/bench/host_cpu.h"

namespace gc::bench {
namespace {

HostCpu parsed(const std::string& text)
{
    std::istringstream in(text);
    return parse_cpuinfo(in);
}

TEST(HostCpu, ZenThreeVmWithItsNameShortened)
{
    const std::string block = "processor\t: %d\nvendor_id\t: AuthenticAMD\ncpu family\t: 25\nmodel\t\t: 1\n"
                              "model name\t: AMD EPYC\nflags\t\t: fpu sse4_2 avx avx2 fma bmi2\n\n";
    std::string text;
    for (int i = 0; i < 2; ++i) {
        char b[256];
        std::snprintf(b, sizeof b, block.c_str(), i);
        text += b;
    }
    const HostCpu cpu = parsed(text);
    std::printf("[ host cpu ] %s\n", cpu.summary().c_str());
    EXPECT_EQ(cpu.model, "AMD EPYC");
    EXPECT_EQ(cpu.family, 25);
    EXPECT_EQ(cpu.model_number, 1);
    EXPECT_EQ(cpu.widest_simd, "avx2");
    EXPECT_EQ(cpu.logical_cpus, 2);
    EXPECT_EQ(cpu.summary(), "AMD EPYC (family 25 model 1), avx2, 2 logical CPUs");
}

TEST(HostCpu, AvxFiveTwelveOutranksTheFlagsBeforeIt)
{
    const HostCpu cpu = parsed("processor : 0\ncpu family : 6\nmodel : 143\n"
                               "model name : Intel(R) Xeon(R) Platinum 8480C\n"
                               "flags : sse4_2 avx avx2 avx512f avx512bw avx512_fp16 amx_tile\n");
    EXPECT_EQ(cpu.widest_simd, "avx512f");
    EXPECT_EQ(cpu.summary(), "Intel(R) Xeon(R) Platinum 8480C (family 6 model 143), avx512f, 1 logical CPUs");
}

TEST(HostCpu, ArmFeaturesAndMissingFields)
{
    // Arm lists "Features" and no model name or x86 family; nothing is made up for them.
    const HostCpu cpu = parsed("processor : 0\nBogoMIPS : 50.00\nFeatures : fp asimd crc32 sve\n"
                               "CPU implementer : 0x41\n\nprocessor : 1\nFeatures : fp asimd\n");
    EXPECT_EQ(cpu.widest_simd, "sve");
    EXPECT_EQ(cpu.family, -1);
    EXPECT_EQ(cpu.logical_cpus, 2);
    EXPECT_EQ(cpu.summary(), "unknown CPU, sve, 2 logical CPUs");
    EXPECT_EQ(parsed("").summary(), "unknown CPU");
    EXPECT_EQ(parsed("model : x1\ncpu family : -3\n").model_number, -1) << "not a number";
}

}  // namespace
}  // namespace gc::bench
