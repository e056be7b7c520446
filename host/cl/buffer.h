// RAII device buffer of `count` elements of T, with a name used in every error message.
//
// Zero-size buffers are allowed: an empty scene still launches kernels, and OpenCL rejects a
// zero-byte clCreateBuffer, so one element is allocated to give kernels a valid pointer.
// count() and bytes() still say 0; kernels must not read past their own count arguments.
#pragma once

#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "host/cl/context.h"
#include "host/cl/error.h"

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
        }
        return *this;
    }
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;

    // Allocates count elements (flags: CL_MEM_READ_WRITE etc.). Throws DeviceError when the
    // size exceeds the device's largest single allocation, ClError when the driver refuses.
    static Buffer create(const Context& context, size_t count, cl_mem_flags flags, std::string name)
    {
        const DeviceInfo& device = context.device();
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
        Buffer buffer;
        const size_t alloc_bytes = count == 0 ? sizeof(T) : static_cast<size_t>(bytes);
        buffer.m_mem = GC_CL_CREATE(
            "allocating '" + name + "' (" + format_bytes(bytes) + ") on " + device.device_name,
            clCreateBuffer, context.context(), flags, alloc_bytes, nullptr);
        GC_CL(clRetainCommandQueue, context.queue());
        buffer.m_queue = context.queue();
        buffer.m_count = count;
        buffer.m_name = std::move(name);
        buffer.m_device_name = device.device_name;
        return buffer;
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
        if (m_mem) clReleaseMemObject(m_mem);
        if (m_queue) clReleaseCommandQueue(m_queue);
        m_mem = nullptr;
        m_queue = nullptr;
    }

    cl_mem m_mem = nullptr;
    cl_command_queue m_queue = nullptr;  // retained: reads and writes go through it
    size_t m_count = 0;
    std::string m_name;
    std::string m_device_name;
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
