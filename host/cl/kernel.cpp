#include "host/cl/kernel.h"

#include <algorithm>
#include <utility>

#include "host/cl/error.h"

namespace gc::cl {

Kernel::Kernel(cl_kernel kernel, std::string name, cl_device_id device)
    : m_kernel(kernel), m_name(std::move(name))
{
    try {
        const std::string where = "querying kernel '" + m_name + "'";
        GC_CL_WHAT(where, clGetKernelInfo, m_kernel, CL_KERNEL_NUM_ARGS, sizeof m_num_args,
                   &m_num_args, nullptr);
        GC_CL_WHAT(where, clGetKernelWorkGroupInfo, m_kernel, device, CL_KERNEL_WORK_GROUP_SIZE,
                   sizeof m_max_work_group, &m_max_work_group, nullptr);
    } catch (...) {
        release();
        throw;
    }
}

Kernel::~Kernel()
{
    release();
}

Kernel::Kernel(Kernel&& other) noexcept
{
    *this = std::move(other);
}

Kernel& Kernel::operator=(Kernel&& other) noexcept
{
    if (this != &other) {
        release();
        m_kernel = std::exchange(other.m_kernel, nullptr);
        m_name = std::move(other.m_name);
        m_num_args = other.m_num_args;
        m_max_work_group = other.m_max_work_group;
    }
    return *this;
}

void Kernel::release() noexcept
{
    if (m_kernel) clReleaseKernel(m_kernel);
    m_kernel = nullptr;
}

void Kernel::check_arg_count(size_t given) const
{
    if (!m_kernel) throw DeviceError("set_args on an empty Kernel");
    if (given != m_num_args) {
        throw DeviceError("kernel '" + m_name + "' takes " + std::to_string(m_num_args) +
                          " arguments but set_args was given " + std::to_string(given));
    }
}

void Kernel::set_arg_bytes(cl_uint index, size_t size, const void* value, const char* buffer_name)
{
    // The context string is built only on failure: launches are on the hot path.
    const cl_int err = clSetKernelArg(m_kernel, index, size, value);
    if (err == CL_SUCCESS) return;
    std::string where = "setting argument " + std::to_string(index) + " of kernel '" + m_name + "'";
    if (buffer_name)
        where += std::string(" to buffer '") + buffer_name + "'";
    else
        where += " (" + std::to_string(size) + " bytes by value)";
    throw ClError("clSetKernelArg", err, where);
}

void Kernel::launch(const Context& context, size_t global, size_t local, const char* what)
{
    if (!m_kernel) throw DeviceError("launch of an empty Kernel");
    if (global == 0) return;  // OpenCL 1.2 rejects empty ranges; there is nothing to do.
    if (local == 0) local = context.default_local_size();
    if (m_max_work_group > 0) local = std::min(local, m_max_work_group);
    const size_t rounded = (global + local - 1) / local * local;
    const cl_int err = clEnqueueNDRangeKernel(context.queue(), m_kernel, 1, nullptr, &rounded,
                                              &local, 0, nullptr, nullptr);
    if (err == CL_SUCCESS) return;
    throw ClError("clEnqueueNDRangeKernel", err,
                  "launching kernel '" + m_name + "'" +
                      (what ? std::string(" (") + what + ")" : "") + " with " +
                      std::to_string(rounded) + " work-items in groups of " +
                      std::to_string(local) + " on " + context.device().device_name);
}

}  // namespace gc::cl
