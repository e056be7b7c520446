// OpenCL device discovery and the `--device` selector.
#pragma once

#include <string>
#include <vector>

#include "host/cl/cl_api.h"
#include "host/util/error.h"

namespace gc::cl {

struct DeviceInfo {
    cl_platform_id platform = nullptr;
    cl_device_id id = nullptr;
    std::string platform_name;
    std::string platform_version;  // "OpenCL 3.0 PoCL 5.0 ..." (part of the binary cache key)
    std::string device_name;
    std::string vendor;
    std::string driver_version;
    std::string device_version;    // "OpenCL 3.0 ..."
    std::string opencl_c_version;  // "OpenCL C 1.2 ..."
    bool is_gpu = false;
    bool is_cpu = false;
    cl_uint compute_units = 0;
    cl_ulong global_mem = 0;
    cl_ulong max_alloc = 0;  // largest single buffer (CL_DEVICE_MAX_MEM_ALLOC_SIZE)
    cl_uint base_addr_align = 0;  // bytes a buffer's base must be aligned to (CL_DEVICE_MEM_BASE_ADDR_ALIGN / 8)
    cl_ulong local_mem = 0;
    size_t max_work_group_size = 0;
    cl_uint preferred_vector_width_float = 1;  // picks the default work-group size on CPUs
    bool correctly_rounded_div_sqrt = false;   // CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT

    // "gpu", "cpu" or "other".
    const char* type_name() const;
};

// One property of a device (clGetDeviceInfo): text without its terminator and trailing
// spaces, or a cl_uint. Both throw ClError naming the query when the driver refuses it.
std::string device_string(cl_device_id device, cl_device_info what);
cl_uint device_uint(cl_device_id device, cl_device_info what);

// Every available device with a compiler, on every platform, in platform then device order
// (the order `--device <index>` counts in). No ICD loader, no platform or no device gives an
// empty list, not an exception; `why_empty` (if given) then says why, for the error message.
std::vector<DeviceInfo> list_devices(std::string* why_empty = nullptr);

// Picks a device by spec:
//   any       the first GPU, else the first CPU, else the first device
//   gpu, cpu  the first device of that type
//   <N>       the N-th device of list_devices() (0-based)
//   <text>    the first device whose name, vendor or platform name contains text (any case)
// Throws gc::DeviceError listing the available devices when nothing matches.
DeviceInfo select_device(const std::string& spec);
DeviceInfo select_device(const std::string& spec, const std::vector<DeviceInfo>& devices);

// The table `geocold-cl --list-devices` prints: index, type, name, platform, driver, compute
// units, global memory, max single allocation. One line per device plus a header.
std::string format_device_list(const std::vector<DeviceInfo>& devices);

// Caps the worker threads of PoCL's CPU device at `threads` (POCL_CPU_MAX_CU_COUNT, and
// POCL_MAX_PTHREAD_COUNT for PoCL before 4.0). PoCL reads them once, when the ICD loader
// first loads it, so call this before any other OpenCL call. Other drivers ignore them.
void limit_cpu_device_threads(int threads);

}  // namespace gc::cl
