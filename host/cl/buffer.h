// RAII device buffer of `count` elements of T, with a name used in every error message.
//
// Zero-size buffers are allowed: an empty scene still launches kernels, and OpenCL rejects a
// zero-byte clCreateBuffer, so one element is allocated to give kernels a valid pointer.
// count() and bytes() still say 0; kernels must not read past their own count arguments.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "host/cl/context.h"
#include "host/cl/error.h"
#include "host/cl/guarded_memory.h"

namespace gc::cl {

template <class T>
class Buffer {
    static_assert(std::is_trivially_copyable_v<T>, "device buffers hold plain data");

public:
    Buffer() = default;
    ~Buffer() { release(); }
    Buffer(Buffer&& other) noexcept { *this = std::move(other); }
    Buffer& operator=(Buffer&& other) noexcept
    {
        if (this != &other) {
            release();
            m_mem = std::exchange(other.m_mem, nullptr);
            m_queue = std::exchange(other.m_queue, nullptr);
            m_count = std::exchange(other.m_count, 0);
            m_name = std::move(other.m_name);
            m_device_name = std::move(other.m_device_name);
            m_guarded = std::move(other.m_guarded);
        }
        return *this;
    }
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    // Allocates count elements (flags: CL_MEM_READ_WRITE etc.). Throws DeviceError when the
    // size exceeds the device's largest single allocation, ClError when the driver refuses.
    static Buffer create(const Context& context, size_t count, cl_mem_flags flags, std::string name)
    {
        const size_t bytes = checked_bytes(context.device(), count, name);
        return make(context, count, flags, bytes, nullptr, std::move(name));
    }

    // A read-only buffer over `data` itself (CL_MEM_USE_HOST_PTR) where the device shares the
    // host's memory (CPUs), so kernels read the host array in place: no second copy of it, and
    // the array's pages are the ones the kernels walk (BigArray puts large arrays on 2 MiB
    // pages, which a copy into the driver's 4 KiB pages would lose), so a large scene traces
    // faster (docs/decisions/host-memory-in-place.md). The caller keeps `data` alive and
    // unchanged for the buffer's lifetime. Anywhere else (a GPU, an empty array, a base the
    // device would not accept) it is an ordinary copy, as read_only_buffer makes.
    static Buffer over_host(const Context& context, std::span<const T> data, std::string name)
    {
        const DeviceInfo& device = context.device();
        const auto base = reinterpret_cast<std::uintptr_t>(data.data());
        const bool in_place = device.is_cpu && !data.empty() && device.base_addr_align > 0 &&
                              base % device.base_addr_align == 0 && !guarded_buffers_enabled();
        if (!in_place) {
            Buffer buffer = create(context, data.size(), CL_MEM_READ_ONLY, std::move(name));
            buffer.write(data);
            return buffer;
        }
        const size_t bytes = checked_bytes(device, data.size(), name);
        // OpenCL's host_ptr is not const, but a CL_MEM_READ_ONLY buffer is never written.
        return make(context, data.size(), CL_MEM_READ_ONLY | CL_MEM_USE_HOST_PTR, bytes,
                    const_cast<T*>(data.data()), std::move(name));
    }

    // Blocking copies of data.size() elements starting at element `first`.
    void write(std::span<const T> data, size_t first = 0)
    {
        check_range(data.size(), first, "write");
        if (data.empty()) return;
        GC_CL_WHAT("writing '" + m_name + "' on " + m_device_name, clEnqueueWriteBuffer, m_queue,
                   m_mem, CL_TRUE, first * sizeof(T), data.size_bytes(), data.data(), 0, nullptr,
                   nullptr);
    }
    void read(std::span<T> data, size_t first = 0) const
    {
        check_range(data.size(), first, "read");
        if (data.empty()) return;
        GC_CL_WHAT("reading '" + m_name + "' on " + m_device_name, clEnqueueReadBuffer, m_queue,
                   m_mem, CL_TRUE, first * sizeof(T), data.size_bytes(), data.data(), 0, nullptr,
                   nullptr);
    }

    size_t count() const { return m_count; }
    size_t bytes() const { return m_count * sizeof(T); }
    const std::string& name() const { return m_name; }
    cl_mem mem() const { return m_mem; }
    explicit operator bool() const { return m_mem != nullptr; }

private:
    // count * sizeof(T), or DeviceError when that exceeds the device's largest allocation.
    static size_t checked_bytes(const DeviceInfo& device, size_t count, const std::string& name)
    {
        const size_t max_count = std::numeric_limits<size_t>::max() / sizeof(T);
        const cl_ulong bytes = count <= max_count ? static_cast<cl_ulong>(count) * sizeof(T)
                                                  : std::numeric_limits<cl_ulong>::max();
        if (bytes > device.max_alloc) {
            throw DeviceError(
                "cannot allocate buffer '" + name + "': " + format_bytes(bytes) + " (" +
                std::to_string(count) + " elements of " + std::to_string(sizeof(T)) +
                " bytes) exceeds the largest single allocation of " +
                format_bytes(device.max_alloc) + " (" + std::to_string(device.max_alloc) +
                " bytes) on " + device.device_name);
        }
        return static_cast<size_t>(bytes);
    }

    // The buffer itself; `bytes` of 0 allocate one element (see the top of this file).
    static Buffer make(const Context& context, size_t count, cl_mem_flags flags, size_t bytes, void* host,
                       std::string name)
    {
        const DeviceInfo& device = context.device();
        Buffer buffer;
        if (host == nullptr && device.is_cpu && guarded_buffers_enabled()) {
            buffer.m_guarded = guarded_allocation(bytes == 0 ? sizeof(T) : bytes);
            host = buffer.m_guarded.get();
            flags |= CL_MEM_USE_HOST_PTR;
        }
        buffer.m_mem = GC_CL_CREATE(
            "allocating '" + name + "' (" + format_bytes(bytes) + ") on " + device.device_name,
            clCreateBuffer, context.context(), flags, bytes == 0 ? sizeof(T) : bytes, host);
        GC_CL(clRetainCommandQueue, context.queue());
        buffer.m_queue = context.queue();
        buffer.m_count = count;
        buffer.m_name = std::move(name);
        buffer.m_device_name = device.device_name;
        return buffer;
    }

    void check_range(size_t n, size_t first, const char* what) const
    {
        if (!m_mem) throw DeviceError(std::string("cannot ") + what + " an unallocated buffer");
        if (first > m_count || n > m_count - first) {
            throw DeviceError(std::string("cannot ") + what + " elements [" +
                              std::to_string(first) + ", " + std::to_string(first + n) +
                              ") of buffer '" + m_name + "' (" + std::to_string(m_count) +
                              " elements)");
        }
    }
    void release() noexcept
    {
        // Guarded memory goes back to the system: nothing queued may still use it.
        if (m_guarded && m_queue) clFinish(m_queue);
        if (m_mem) clReleaseMemObject(m_mem);
        if (m_queue) clReleaseCommandQueue(m_queue);
        m_mem = nullptr;
        m_queue = nullptr;
        m_guarded.reset();
    }

    cl_mem m_mem = nullptr;
    cl_command_queue m_queue = nullptr;  // retained: reads and writes go through it
    size_t m_count = 0;
    std::string m_name;
    std::string m_device_name;
    std::shared_ptr<void> m_guarded;  // GEOCOLD_GUARD_BUFFERS: the host memory the buffer lives in
};

// A read-only device copy of `data`: scene data the kernels only read.
template <class T, class Allocator>
Buffer<T> read_only_buffer(const Context& context, const std::vector<T, Allocator>& data, std::string name)
{
    Buffer<T> buffer = Buffer<T>::create(context, data.size(), CL_MEM_READ_ONLY, std::move(name));
    buffer.write(std::span<const T>(data));
    return buffer;
}

}  // namespace gc::cl
