// OpenCL failures as exceptions that name the failing call, its error code and what the
// program was doing, e.g.
//   clCreateBuffer failed: CL_INVALID_BUFFER_SIZE (-61) while allocating 'bvh nodes' (3.2 GiB)
//   on NVIDIA H100
//
// Every CL call goes through one of three macros:
//   GC_CL(clFinish, queue);                                 // no context
//   GC_CL_WHAT(what, clSetKernelArg, kernel, i, size, ptr); // `what` is said after "while"
//   cl_mem m = GC_CL_CREATE(what, clCreateBuffer, ctx, flags, bytes, nullptr);  // appends &err
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "host/cl/cl_api.h"
#include "host/util/error.h"

namespace gc::cl {

// "CL_INVALID_VALUE" for -30; every OpenCL 1.2 code, a few 2.x and extension codes, and
// "unknown OpenCL error" otherwise. Never null.
const char* cl_error_name(cl_int code);

// "3.2 GiB", "512 KiB", "17 bytes": sizes in messages and device tables.
std::string format_bytes(std::uint64_t bytes);

class ClError : public DeviceError {
public:
    ClError(std::string call, cl_int code, std::string context);

    const std::string& call() const { return m_call; }
    cl_int code() const { return m_code; }
    const char* code_name() const { return cl_error_name(m_code); }
    const std::string& context() const { return m_context; }

protected:
    // For subclasses that append to the standard message.
    ClError(std::string call, cl_int code, std::string context, const std::string& message);

private:
    std::string m_call;
    cl_int m_code;
    std::string m_context;
};

// clBuildProgram failed: the message carries the device's whole build log, which names the
// file and line of the first error.
class ClBuildError : public ClError {
public:
    ClBuildError(cl_int code, std::string context, std::string log);
    const std::string& log() const { return m_log; }

private:
    std::string m_log;
};

// "clFoo failed: NAME (code)[ while <context>]".
std::string format_cl_failure(std::string_view call, cl_int code, std::string_view context);

// Throws ClError unless code == CL_SUCCESS.
inline void check(cl_int code, const char* call, std::string_view context = {})
{
    if (code != CL_SUCCESS) throw ClError(call, code, std::string(context));
}

// Runs a creator (a call whose last argument is cl_int* errcode_ret) and checks it.
template <class Create>
auto check_create(Create&& create, const char* call, std::string_view context = {})
{
    cl_int err = CL_SUCCESS;
    auto handle = create(&err);
    check(err, call, context);
    return handle;
}

}  // namespace gc::cl

#define GC_CL(fn, ...) ::gc::cl::check(fn(__VA_ARGS__), #fn)
#define GC_CL_WHAT(what, fn, ...) ::gc::cl::check(fn(__VA_ARGS__), #fn, (what))
#define GC_CL_CREATE(what, fn, ...) \
    ::gc::cl::check_create([&](cl_int* gc_err_) { return fn(__VA_ARGS__, gc_err_); }, #fn, (what))
