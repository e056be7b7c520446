#include "host/cl/device.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "host/cl/error.h"
#include "host/util/log.h"

namespace gc::cl {
namespace {

std::string platform_string(cl_platform_id platform, cl_platform_info what)
{
    size_t size = 0;
    if (clGetPlatformInfo(platform, what, 0, nullptr, &size) != CL_SUCCESS || size == 0) return {};
    std::string text(size, '\0');
    if (clGetPlatformInfo(platform, what, size, text.data(), nullptr) != CL_SUCCESS) return {};
    text.resize(text.find('\0') == std::string::npos ? size : text.find('\0'));
    return text;
}

}  // namespace

std::string device_string(cl_device_id device, cl_device_info what)
{
    size_t size = 0;
    GC_CL_WHAT("querying a device", clGetDeviceInfo, device, what, 0, nullptr, &size);
    std::string text(size, '\0');
    GC_CL_WHAT("querying a device", clGetDeviceInfo, device, what, size, text.data(), nullptr);
    text.resize(text.find('\0') == std::string::npos ? size : text.find('\0'));
    // Some drivers pad names with spaces.
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

namespace {

template <class T>
T device_value(cl_device_id device, cl_device_info what)
{
    T value{};
    GC_CL_WHAT("querying a device", clGetDeviceInfo, device, what, sizeof value, &value, nullptr);
    return value;
}

}  // namespace

cl_uint device_uint(cl_device_id device, cl_device_info what) { return device_value<cl_uint>(device, what); }

namespace {

DeviceInfo describe(cl_platform_id platform, cl_device_id device)
{
    DeviceInfo info;
    info.platform = platform;
    info.id = device;
    info.platform_name = platform_string(platform, CL_PLATFORM_NAME);
    info.platform_version = platform_string(platform, CL_PLATFORM_VERSION);
    info.device_name = device_string(device, CL_DEVICE_NAME);
    info.vendor = device_string(device, CL_DEVICE_VENDOR);
    info.driver_version = device_string(device, CL_DRIVER_VERSION);
    info.device_version = device_string(device, CL_DEVICE_VERSION);
    info.opencl_c_version = device_string(device, CL_DEVICE_OPENCL_C_VERSION);
    const auto type = device_value<cl_device_type>(device, CL_DEVICE_TYPE);
    info.is_gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
    info.is_cpu = (type & CL_DEVICE_TYPE_CPU) != 0;
    info.compute_units = device_value<cl_uint>(device, CL_DEVICE_MAX_COMPUTE_UNITS);
    info.global_mem = device_value<cl_ulong>(device, CL_DEVICE_GLOBAL_MEM_SIZE);
    info.max_alloc = device_value<cl_ulong>(device, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
    info.base_addr_align = device_value<cl_uint>(device, CL_DEVICE_MEM_BASE_ADDR_ALIGN) / 8;
    info.local_mem = device_value<cl_ulong>(device, CL_DEVICE_LOCAL_MEM_SIZE);
    info.max_work_group_size = device_value<size_t>(device, CL_DEVICE_MAX_WORK_GROUP_SIZE);
    info.preferred_vector_width_float =
        std::max<cl_uint>(1, device_value<cl_uint>(device, CL_DEVICE_PREFERRED_VECTOR_WIDTH_FLOAT));
    const auto fp = device_value<cl_device_fp_config>(device, CL_DEVICE_SINGLE_FP_CONFIG);
    info.correctly_rounded_div_sqrt = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
    return info;
}

std::string lower(std::string text)
{
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

bool is_index(const std::string& spec)
{
    return !spec.empty() && spec.size() < 6 &&
           std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

const char* DeviceInfo::type_name() const
{
    return is_gpu ? "gpu" : is_cpu ? "cpu" : "other";
}

std::vector<DeviceInfo> list_devices(std::string* why_empty)
{
    std::vector<DeviceInfo> devices;
    auto empty_because = [&](std::string why) {
        log_verbose("no OpenCL devices: " + why);
        if (why_empty) *why_empty = std::move(why);
        return std::vector<DeviceInfo>{};
    };
    cl_uint num_platforms = 0;
    // Without an ICD loader configuration this returns CL_PLATFORM_NOT_FOUND_KHR (-1001).
    const cl_int err = clGetPlatformIDs(0, nullptr, &num_platforms);
    if (err != CL_SUCCESS || num_platforms == 0) {
        return empty_because(
            err != CL_SUCCESS
                ? format_cl_failure("clGetPlatformIDs", err, "looking for OpenCL platforms") +
                      " (is an OpenCL driver installed and registered in /etc/OpenCL/vendors?)"
                : "no OpenCL platform is installed (no .icd file in /etc/OpenCL/vendors?)");
    }
    std::vector<cl_platform_id> platforms(num_platforms);
    GC_CL_WHAT("listing OpenCL platforms", clGetPlatformIDs, num_platforms, platforms.data(),
               nullptr);

    std::string skipped;
    for (cl_platform_id platform : platforms) {
        cl_uint num_devices = 0;
        // A platform without devices answers CL_DEVICE_NOT_FOUND: skip it, not an error.
        if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &num_devices) != CL_SUCCESS ||
            num_devices == 0) {
            skipped +=
                "; platform '" + platform_string(platform, CL_PLATFORM_NAME) + "' has no devices";
            continue;
        }
        std::vector<cl_device_id> ids(num_devices);
        GC_CL_WHAT("listing OpenCL devices", clGetDeviceIDs, platform, CL_DEVICE_TYPE_ALL,
                   num_devices, ids.data(), nullptr);
        for (cl_device_id id : ids) {
            // A device that cannot compile cannot run our kernels (they are built from source).
            if (!device_value<cl_bool>(id, CL_DEVICE_AVAILABLE) ||
                !device_value<cl_bool>(id, CL_DEVICE_COMPILER_AVAILABLE)) {
                skipped += "; device '" + device_string(id, CL_DEVICE_NAME) +
                           "' is unavailable or has no compiler";
                continue;
            }
            devices.push_back(describe(platform, id));
        }
    }
    if (devices.empty()) {
        return empty_because(std::to_string(num_platforms) +
                             " OpenCL platform(s) but no usable device" + skipped);
    }
    return devices;
}

DeviceInfo select_device(const std::string& spec)
{
    std::string why_empty;
    const std::vector<DeviceInfo> devices = list_devices(&why_empty);
    if (devices.empty()) {
        throw DeviceError("no OpenCL device available for --device '" + spec + "': " + why_empty);
    }
    return select_device(spec, devices);
}

DeviceInfo select_device(const std::string& spec, const std::vector<DeviceInfo>& devices)
{
    const std::string key = lower(spec);
    auto first = [&](auto&& pred) -> const DeviceInfo* {
        auto it = std::find_if(devices.begin(), devices.end(), pred);
        return it == devices.end() ? nullptr : &*it;
    };
    const DeviceInfo* found = nullptr;
    if (key == "any") {
        found = first([](const DeviceInfo& d) { return d.is_gpu; });
        if (!found) found = first([](const DeviceInfo& d) { return d.is_cpu; });
        if (!found && !devices.empty()) found = &devices.front();
    } else if (key == "gpu") {
        found = first([](const DeviceInfo& d) { return d.is_gpu; });
    } else if (key == "cpu") {
        found = first([](const DeviceInfo& d) { return d.is_cpu; });
    } else if (is_index(key)) {
        const size_t index = std::stoul(key);
        if (index < devices.size()) found = &devices[index];
    } else if (!key.empty()) {
        found = first([&](const DeviceInfo& d) {
            return lower(d.device_name).find(key) != std::string::npos ||
                   lower(d.vendor).find(key) != std::string::npos ||
                   lower(d.platform_name).find(key) != std::string::npos;
        });
    }
    if (!found) {
        throw DeviceError(
            "no OpenCL device matches --device '" + spec +
            "' (use any, gpu, cpu, an index or part of a name); available devices:\n" +
            format_device_list(devices));
    }
    return *found;
}

std::string format_device_list(const std::vector<DeviceInfo>& devices)
{
    if (devices.empty()) return "  (no OpenCL devices)\n";
    // Column widths adapt to the longest name so long GPU names stay on one line.
    size_t name_w = 4, platform_w = 8, driver_w = 6;
    for (const DeviceInfo& d : devices) {
        name_w = std::max(name_w, d.device_name.size());
        platform_w = std::max(platform_w, d.platform_name.size());
        driver_w = std::max(driver_w, d.driver_version.size());
    }
    auto row = [&](const std::string& index, const std::string& type, const std::string& name,
                   const std::string& platform, const std::string& driver, const std::string& cus,
                   const std::string& mem, const std::string& alloc) {
        char line[1024];
        std::snprintf(line, sizeof line, "  %-5s %-5s %-*s  %-*s  %-*s  %4s  %10s  %10s\n",
                      index.c_str(), type.c_str(), static_cast<int>(name_w), name.c_str(),
                      static_cast<int>(platform_w), platform.c_str(), static_cast<int>(driver_w),
                      driver.c_str(), cus.c_str(), mem.c_str(), alloc.c_str());
        return std::string(line);
    };
    std::string table =
        row("index", "type", "name", "platform", "driver", "CUs", "memory", "max alloc");
    for (size_t i = 0; i < devices.size(); ++i) {
        const DeviceInfo& d = devices[i];
        table += row(std::to_string(i), d.type_name(), d.device_name, d.platform_name,
                     d.driver_version, std::to_string(d.compute_units), format_bytes(d.global_mem),
                     format_bytes(d.max_alloc));
    }
    return table;
}

void limit_cpu_device_threads(int threads)
{
    const std::string value = std::to_string(std::max(1, threads));
    for (const char* name : {"POCL_CPU_MAX_CU_COUNT", "POCL_MAX_PTHREAD_COUNT"}) setenv(name, value.c_str(), 1);
}

}  // namespace gc::cl
