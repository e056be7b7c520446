// Building OpenCL programs from kernels/*.cl, with a per-device binary cache.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "host/cl/cl_api.h"
#include "host/cl/context.h"
#include "host/cl/kernel.h"

namespace gc::cl {

// True when dir holds shared/gc_types.h (what every kernel includes).
bool is_kernel_dir(const std::filesystem::path& dir);

// The kernel source directory: `chosen` when not empty (a DeviceError if it is not a kernel
// dir), else the source tree's kernels/ compiled in, else <exe dir>/../share/geocold-cl/kernels
// (an installed copy). Throws DeviceError naming every place tried.
std::filesystem::path find_kernel_dir(const std::filesystem::path& chosen = {});

struct BuildConfig {
    std::filesystem::path kernel_dir;  // empty: find_kernel_dir()'s search
    std::filesystem::path cache_dir;   // the binary cache; empty: no cache
    bool use_cache = true;             // false: always compile, never read or write the cache
    // Write entries even for a driver that keeps its own build cache (PoCL's kcache), where
    // by default we only read them: see driver_caches_builds() in program.cpp. For the tests
    // of the cache itself, and for users who want ours filled anyway.
    bool store_when_driver_caches = false;
    // The driver's own build cache is switched off (PoCL: POCL_KERNEL_CACHE=0), so ours is the
    // only one and is written on every driver.
    bool driver_cache_disabled = false;
};

// One program built from one top-level .cl file of the kernel directory, for the context's
// device. Options are "-I <dir>/shared -I <dir> -cl-std=CL1.2", then
// -cl-fp32-correctly-rounded-divide-sqrt where the device supports it, then
// "-D GC_SOURCE_HASH=0x<hash of every *.cl/*.h under the kernel dir>", then the caller's.
// A cached binary is used when its key matches (hash of the file name, that option string,
// device name, driver, platform and device version); a cache entry that fails any check or
// that the driver rejects is deleted and the program is rebuilt from source.
class Program {
public:
    Program(const Context& context, const std::string& file, const std::string& options = {},
            const BuildConfig& config = {});
    ~Program();
    Program(Program&& other) noexcept;
    Program& operator=(Program&& other) noexcept;
    Program(const Program&) = delete;
    Program& operator=(const Program&) = delete;

    // Creates a kernel; ClError (CL_INVALID_KERNEL_NAME) names the kernel and file if absent.
    Kernel kernel(const char* name) const;

    cl_program handle() const { return m_program; }
    const std::string& file() const { return m_file; }
    const std::string& options() const { return m_options; }  // the full option string used
    std::uint64_t cache_key() const { return m_key; }
    bool from_cache() const { return m_from_cache; }
    double build_seconds() const { return m_build_seconds; }  // cache load or compile, wall time
    // The driver's binary for the device (CL_PROGRAM_BINARIES): what the cache stores; on
    // NVIDIA's OpenCL, PTX text.
    std::vector<unsigned char> binary() const;

private:
    cl_program build_from_source(const Context& context) const;
    void release() noexcept;

    cl_program m_program = nullptr;
    cl_device_id m_device = nullptr;
    std::string m_device_name;
    std::string m_file;
    std::string m_options;
    std::uint64_t m_key = 0;
    bool m_from_cache = false;
    double m_build_seconds = 0.0;
};

}  // namespace gc::cl
