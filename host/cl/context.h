// An OpenCL context on one device with one in-order command queue. In-order is part of the
// determinism story: stages run in enqueue order, so no events are needed between them.
#pragma once

#include "host/cl/cl_api.h"
#include "host/cl/device.h"

namespace gc::cl {

class Context {
public:
    explicit Context(const DeviceInfo& device);
    ~Context();
    Context(Context&& other) noexcept;
    Context& operator=(Context&& other) noexcept;
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    const DeviceInfo& device() const { return m_device; }
    cl_context context() const { return m_context; }
    cl_command_queue queue() const { return m_queue; }

    // Work-group size used when a launch asks for local = 0 (see Kernel::launch).
    size_t default_local_size() const { return m_default_local; }

    // Blocks until everything enqueued has run; surfaces asynchronous kernel failures.
    void finish() const;

private:
    void release() noexcept;

    DeviceInfo m_device;
    cl_context m_context = nullptr;
    cl_command_queue m_queue = nullptr;
    size_t m_default_local = 1;
};

}  // namespace gc::cl
