#include "host/cl/context.h"

#include <algorithm>
#include <string>
#include <utility>

#include "host/cl/error.h"

namespace gc::cl {
namespace {

// A fixed work-group size per device, so the same launch has the same shape every run.
// GPUs: 64 = two NVIDIA warps or one AMD wave64; enough to hide latency, small enough for
// the register-heavy traversal kernels. CPUs (PoCL): PoCL vectorizes a work-group across SIMD
// lanes and runs whole work-groups per thread, so a group of 8 vectors of the preferred float
// width (128 on AVX-512, 64 on AVX2) fills the lanes and amortizes the per-group overhead.
// Results never depend on this choice (kernels are order-independent); speed does.
size_t pick_local_size(const DeviceInfo& device)
{
    size_t local = 64;
    if (device.is_cpu && !device.is_gpu)
        local = 8 * static_cast<size_t>(device.preferred_vector_width_float);
    local = std::max<size_t>(1, std::min(local, device.max_work_group_size));
    // Round down to a power of two so global sizes stay friendly.
    size_t pow2 = 1;
    while (pow2 * 2 <= local) pow2 *= 2;
    return pow2;
}

}  // namespace

Context::Context(const DeviceInfo& device)
    : m_device(device), m_default_local(pick_local_size(device))
{
    const std::string where = "creating a context on " + device.device_name;
    const cl_context_properties props[] = {
        CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(device.platform), 0};
    m_context = GC_CL_CREATE(where, clCreateContext, props, 1, &device.id, nullptr, nullptr);
    try {
        m_queue = GC_CL_CREATE(where, clCreateCommandQueue, m_context, device.id, 0);
    } catch (...) {
        release();
        throw;
    }
}

Context::~Context()
{
    release();
}

Context::Context(Context&& other) noexcept
    : m_device(std::move(other.m_device)),
      m_context(std::exchange(other.m_context, nullptr)),
      m_queue(std::exchange(other.m_queue, nullptr)),
      m_default_local(other.m_default_local)
{
}

Context& Context::operator=(Context&& other) noexcept
{
    if (this != &other) {
        release();
        m_device = std::move(other.m_device);
        m_context = std::exchange(other.m_context, nullptr);
        m_queue = std::exchange(other.m_queue, nullptr);
        m_default_local = other.m_default_local;
    }
    return *this;
}

void Context::release() noexcept
{
    if (m_queue) clReleaseCommandQueue(m_queue);
    if (m_context) clReleaseContext(m_context);
    m_queue = nullptr;
    m_context = nullptr;
}

void Context::finish() const
{
    GC_CL_WHAT("waiting for the device (" + m_device.device_name + ")", clFinish, m_queue);
}

}  // namespace gc::cl
