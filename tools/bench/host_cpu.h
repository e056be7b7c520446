// The CPU a bench run measured on, as the kernel's /proc/cpuinfo describes it. The CPU path
// figures against Mitsuba turn on it (a Zen 3 without AVX-512 and an AVX-512 Xeon
// gave 1.61x and 0.61x for the same build), so every run records it beside its figures.
#pragma once

#include <istream>
#include <string>

namespace gc::bench {

struct HostCpu {
    std::string model;       // "model name"; cloud VMs may shorten it to the vendor's line ("AMD EPYC")
    int family = -1;         // x86 "cpu family" and "model": they tell apart what the name hides
    int model_number = -1;   //   (AMD family 25 model 1: Zen 3 Milan); -1 where not given
    std::string widest_simd; // the widest vector ISA among the flags: avx512f, avx2, avx, sse4_2,
                             // sve or asimd; empty where no flags were listed
    int logical_cpus = 0;    // "processor" entries

    // One line for the bench's header: "AMD EPYC (family 25 model 1), avx2, 2 logical CPUs".
    std::string summary() const;
};

// Reads the text of /proc/cpuinfo (x86 or Arm). Unknown or missing fields stay unset.
HostCpu parse_cpuinfo(std::istream& text);

// This machine's CPU; every field unset where /proc/cpuinfo cannot be read (not Linux).
HostCpu read_host_cpu();

}  // namespace gc::bench
