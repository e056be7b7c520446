// A named cl_kernel: arguments set in one call with an arity check, and 1-D launches.
//
// Launch contract: the global size is rounded UP to a multiple of the work-group size, so
// every kernel must compare get_global_id(0) with its own element count and return early
// past it. (OpenCL 1.2 requires global to be a multiple of local.)
#pragma once

#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>

#include "host/cl/buffer.h"
#include "host/cl/cl_api.h"
#include "host/cl/context.h"

namespace gc::cl {

// How many kernel arguments one set_args argument stands for: a std::tuple is a group of
// arguments (its elements, groups counted recursively), anything else is one.
template <class T>
inline constexpr std::size_t kernel_arg_count = 1;
template <class... Ts>
inline constexpr std::size_t kernel_arg_count<std::tuple<Ts...>> =
    (kernel_arg_count<std::remove_cvref_t<Ts>> + ... + std::size_t{0});

class Kernel {
public:
    Kernel() = default;
    // Takes ownership of `kernel` (already created for `device`).
    Kernel(cl_kernel kernel, std::string name, cl_device_id device);
    ~Kernel();
    Kernel(Kernel&& other) noexcept;
    Kernel& operator=(Kernel&& other) noexcept;
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;

    // Sets every argument, in order: a Buffer<T> passes its cl_mem, a std::tuple stands for
    // its elements in its place (a group such as DeviceScene::bvh_args(), the host's twin of a
    // parameter macro in kernels/shared, so the list is written once on each side), anything
    // else trivially copyable (uint, float, a GcRenderParams, a raw cl_mem) is passed by value.
    // Throws DeviceError unless the count, groups expanded, equals CL_KERNEL_NUM_ARGS.
    template <class... Args>
    void set_args(const Args&... args)
    {
        check_arg_count((kernel_arg_count<Args> + ... + std::size_t{0}));
        cl_uint index = 0;
        (set_arg(index, args), ...);
    }

    // Enqueues a 1-D range of `global` work-items (nothing if 0) in groups of `local`
    // (0: the context's fixed per-device size, see Context::default_local_size), capped by the
    // kernel's own work-group limit. `what` names the launch in errors ("shade pass 3").
    void launch(const Context& context, size_t global, size_t local = 0,
                const char* what = nullptr);

    const std::string& name() const { return m_name; }
    cl_kernel handle() const { return m_kernel; }
    cl_uint num_args() const { return m_num_args; }
    size_t max_work_group_size() const { return m_max_work_group; }

private:
    // Each set_arg sets the argument(s) at `index` and advances it past them.
    template <class T>
    void set_arg(cl_uint& index, const Buffer<T>& buffer)
    {
        const cl_mem mem = buffer.mem();
        set_arg_bytes(index++, sizeof mem, &mem, buffer.name().c_str());
    }
    template <class... Ts>
    void set_arg(cl_uint& index, const std::tuple<Ts...>& group)
    {
        std::apply([&](const auto&... each) { (set_arg(index, each), ...); }, group);
    }
    template <class T>
    void set_arg(cl_uint& index, const T& value)
    {
        static_assert(std::is_trivially_copyable_v<T>,
                      "kernel arguments are Buffers or plain values");
        static_assert(!std::is_pointer_v<T> || std::is_same_v<T, cl_mem>,
                      "pass a Buffer (or cl_mem), not a host pointer");
        set_arg_bytes(index++, sizeof value, &value, nullptr);
    }
    void set_arg_bytes(cl_uint index, size_t size, const void* value, const char* buffer_name);
    void check_arg_count(size_t given) const;
    void release() noexcept;

    cl_kernel m_kernel = nullptr;
    std::string m_name;
    cl_uint m_num_args = 0;
    size_t m_max_work_group = 0;  // CL_KERNEL_WORK_GROUP_SIZE on the program's device
};

}  // namespace gc::cl
