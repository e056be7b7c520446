#include "tools/bench/host_cpu.h"

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

namespace gc::bench {
namespace {

std::string trimmed(const std::string& s)
{
    const std::size_t first = s.find_first_not_of(" \t");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t") - first + 1);
}

int parsed_int(const std::string& s)
{
    char* end = nullptr;
    const long v = std::strtol(s.c_str(), &end, 10);
    return end != s.c_str() && *end == '\0' && v >= 0 && v < 1000000 ? int(v) : -1;
}

// The widest of the ISAs the bench's figures depend on, from a flags line's words.
std::string widest_simd(const std::string& flags)
{
    std::istringstream in(flags);
    const std::set<std::string> words{std::istream_iterator<std::string>(in), std::istream_iterator<std::string>()};
    for (const char* isa : {"avx512f", "avx2", "avx", "sse4_2", "sve", "asimd"})
        if (words.count(isa)) return isa;
    return {};
}

}  // namespace

std::string HostCpu::summary() const
{
    std::string s = model.empty() ? "unknown CPU" : model;
    if (family >= 0 && model_number >= 0)
        s += " (family " + std::to_string(family) + " model " + std::to_string(model_number) + ")";
    if (!widest_simd.empty()) s += ", " + widest_simd;
    if (logical_cpus > 0) s += ", " + std::to_string(logical_cpus) + " logical CPUs";
    return s;
}

HostCpu parse_cpuinfo(std::istream& text)
{
    HostCpu cpu;
    bool flags_seen = false;
    for (std::string line; std::getline(text, line);) {
        const std::size_t colon = line.find(':');
        if (colon == std::string::npos) continue;
        const std::string key = trimmed(line.substr(0, colon));
        const std::string value = trimmed(line.substr(colon + 1));
        // Every processor repeats its block; the first one describes the rest.
        if (key == "processor") ++cpu.logical_cpus;
        else if (key == "model name" && cpu.model.empty()) cpu.model = value;
        else if (key == "cpu family" && cpu.family < 0) cpu.family = parsed_int(value);
        else if (key == "model" && cpu.model_number < 0) cpu.model_number = parsed_int(value);
        else if ((key == "flags" || key == "Features") && !flags_seen) {
            cpu.widest_simd = widest_simd(value);
            flags_seen = true;
        }
    }
    return cpu;
}

HostCpu read_host_cpu()
{
    std::ifstream file("/proc/cpuinfo");
    if (!file) return {};
    return parse_cpuinfo(file);
}

}  // namespace gc::bench
