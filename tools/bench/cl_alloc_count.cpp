// The device bytes this process holds in OpenCL buffers, now and at most: clCreateBuffer and
// clReleaseMemObject are defined here, in the executable, and pass each call on to the
// OpenCL library's own (dlsym RTLD_NEXT). Linked into geocold-grad-bench alone, so every
// buffer host/cl makes (cl::Buffer) is counted without a counter in host/cl itself; the
// renderer makes no images, sub-buffers or SVM allocations (none are counted).
#include "tools/bench/cl_alloc_count.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <unordered_map>

#include "host/cl/cl_api.h"

namespace {

using CreateBufferFn = cl_mem(CL_API_CALL*)(cl_context, cl_mem_flags, size_t, void*, cl_int*);
using ReleaseFn = cl_int(CL_API_CALL*)(cl_mem);

struct Counter {
    std::mutex mutex;
    std::unordered_map<cl_mem, std::size_t> sizes;
    std::size_t live = 0;
    std::size_t peak = 0;
};

Counter& counter()
{
    static Counter c;
    return c;
}

template <class Fn>
Fn next_symbol(const char* name)
{
    void* f = dlsym(RTLD_NEXT, name);
    if (!f) {
        std::fprintf(stderr, "geocold-grad-bench: the OpenCL library has no %s\n", name);
        std::abort();
    }
    return reinterpret_cast<Fn>(f);
}

}  // namespace

extern "C" CL_API_ENTRY cl_mem CL_API_CALL clCreateBuffer(cl_context context, cl_mem_flags flags, size_t size,
                                                          void* host_ptr, cl_int* errcode_ret)
{
    static const CreateBufferFn real = next_symbol<CreateBufferFn>("clCreateBuffer");
    cl_mem mem = real(context, flags, size, host_ptr, errcode_ret);
    if (mem) {
        Counter& c = counter();
        std::lock_guard<std::mutex> lock(c.mutex);
        c.sizes[mem] = size;
        c.live += size;
        if (c.live > c.peak) c.peak = c.live;
    }
    return mem;
}

extern "C" CL_API_ENTRY cl_int CL_API_CALL clReleaseMemObject(cl_mem mem)
{
    static const ReleaseFn real = next_symbol<ReleaseFn>("clReleaseMemObject");
    cl_uint refs = 0;
    const bool last = mem && clGetMemObjectInfo(mem, CL_MEM_REFERENCE_COUNT, sizeof refs, &refs, nullptr) ==
                                 CL_SUCCESS && refs == 1;
    const cl_int status = real(mem);
    if (status == CL_SUCCESS && last) {
        Counter& c = counter();
        std::lock_guard<std::mutex> lock(c.mutex);
        auto it = c.sizes.find(mem);
        if (it != c.sizes.end()) {
            c.live -= it->second;
            c.sizes.erase(it);
        }
    }
    return status;
}

namespace gc::bench {

AllocCount alloc_count()
{
    Counter& c = counter();
    std::lock_guard<std::mutex> lock(c.mutex);
    return {c.live, c.peak, c.sizes.size()};
}

void reset_alloc_peak()
{
    Counter& c = counter();
    std::lock_guard<std::mutex> lock(c.mutex);
    c.peak = c.live;
}

}  // namespace gc::bench
