#include "host/cl/error.h"

#include <cstdio>

namespace gc::cl {

const char* cl_error_name(cl_int code)
{
    switch (code) {
#define GC_CASE(c) \
    case c:        \
        return #c;
        GC_CASE(CL_SUCCESS)
        GC_CASE(CL_DEVICE_NOT_FOUND)
        GC_CASE(CL_DEVICE_NOT_AVAILABLE)
        GC_CASE(CL_COMPILER_NOT_AVAILABLE)
        GC_CASE(CL_MEM_OBJECT_ALLOCATION_FAILURE)
        GC_CASE(CL_OUT_OF_RESOURCES)
        GC_CASE(CL_OUT_OF_HOST_MEMORY)
        GC_CASE(CL_PROFILING_INFO_NOT_AVAILABLE)
        GC_CASE(CL_MEM_COPY_OVERLAP)
        GC_CASE(CL_IMAGE_FORMAT_MISMATCH)
        GC_CASE(CL_IMAGE_FORMAT_NOT_SUPPORTED)
        GC_CASE(CL_BUILD_PROGRAM_FAILURE)
        GC_CASE(CL_MAP_FAILURE)
        GC_CASE(CL_MISALIGNED_SUB_BUFFER_OFFSET)
        GC_CASE(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
        GC_CASE(CL_COMPILE_PROGRAM_FAILURE)
        GC_CASE(CL_LINKER_NOT_AVAILABLE)
        GC_CASE(CL_LINK_PROGRAM_FAILURE)
        GC_CASE(CL_DEVICE_PARTITION_FAILED)
        GC_CASE(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
        GC_CASE(CL_INVALID_VALUE)
        GC_CASE(CL_INVALID_DEVICE_TYPE)
        GC_CASE(CL_INVALID_PLATFORM)
        GC_CASE(CL_INVALID_DEVICE)
        GC_CASE(CL_INVALID_CONTEXT)
        GC_CASE(CL_INVALID_QUEUE_PROPERTIES)
        GC_CASE(CL_INVALID_COMMAND_QUEUE)
        GC_CASE(CL_INVALID_HOST_PTR)
        GC_CASE(CL_INVALID_MEM_OBJECT)
        GC_CASE(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
        GC_CASE(CL_INVALID_IMAGE_SIZE)
        GC_CASE(CL_INVALID_SAMPLER)
        GC_CASE(CL_INVALID_BINARY)
        GC_CASE(CL_INVALID_BUILD_OPTIONS)
        GC_CASE(CL_INVALID_PROGRAM)
        GC_CASE(CL_INVALID_PROGRAM_EXECUTABLE)
        GC_CASE(CL_INVALID_KERNEL_NAME)
        GC_CASE(CL_INVALID_KERNEL_DEFINITION)
        GC_CASE(CL_INVALID_KERNEL)
        GC_CASE(CL_INVALID_ARG_INDEX)
        GC_CASE(CL_INVALID_ARG_VALUE)
        GC_CASE(CL_INVALID_ARG_SIZE)
        GC_CASE(CL_INVALID_KERNEL_ARGS)
        GC_CASE(CL_INVALID_WORK_DIMENSION)
        GC_CASE(CL_INVALID_WORK_GROUP_SIZE)
        GC_CASE(CL_INVALID_WORK_ITEM_SIZE)
        GC_CASE(CL_INVALID_GLOBAL_OFFSET)
        GC_CASE(CL_INVALID_EVENT_WAIT_LIST)
        GC_CASE(CL_INVALID_EVENT)
        GC_CASE(CL_INVALID_OPERATION)
        GC_CASE(CL_INVALID_GL_OBJECT)
        GC_CASE(CL_INVALID_BUFFER_SIZE)
        GC_CASE(CL_INVALID_MIP_LEVEL)
        GC_CASE(CL_INVALID_GLOBAL_WORK_SIZE)
        GC_CASE(CL_INVALID_PROPERTY)
        GC_CASE(CL_INVALID_IMAGE_DESCRIPTOR)
        GC_CASE(CL_INVALID_COMPILER_OPTIONS)
        GC_CASE(CL_INVALID_LINKER_OPTIONS)
        GC_CASE(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef GC_CASE
        // OpenCL 2.x and extensions: spelled as numbers because the 1.2 headers do not define them.
        case -69:
            return "CL_INVALID_PIPE_SIZE";
        case -70:
            return "CL_INVALID_DEVICE_QUEUE";
        case -71:
            return "CL_INVALID_SPEC_ID";
        case -72:
            return "CL_MAX_SIZE_RESTRICTION_EXCEEDED";
        case -1000:
            return "CL_INVALID_GL_SHAREGROUP_REFERENCE_KHR";
        case -1001:
            return "CL_PLATFORM_NOT_FOUND_KHR";
        case -1002:
            return "CL_INVALID_D3D10_DEVICE_KHR";
        case -1057:
            return "CL_DEVICE_PARTITION_FAILED_EXT";
        // Not in any header, but NVIDIA's driver returns it after an out-of-bounds access.
        case -9999:
            return "NVIDIA_ILLEGAL_MEMORY_ACCESS";
        default:
            return "unknown OpenCL error";
    }
}

std::string format_bytes(std::uint64_t bytes)
{
    static const char* const units[] = {"KiB", "MiB", "GiB", "TiB"};
    if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
    double value = static_cast<double>(bytes) / 1024.0;
    int unit = 0;
    while (value >= 1024.0 && unit < 3) {
        value /= 1024.0;
        ++unit;
    }
    char text[32];
    std::snprintf(text, sizeof text, value < 10.0 ? "%.1f %s" : "%.0f %s", value, units[unit]);
    return text;
}

std::string format_cl_failure(std::string_view call, cl_int code, std::string_view context)
{
    std::string message(call);
    message += " failed: ";
    message += cl_error_name(code);
    message += " (" + std::to_string(code) + ")";
    if (!context.empty()) {
        message += " while ";
        message += context;
    }
    return message;
}

ClError::ClError(std::string call, cl_int code, std::string context)
    : ClError(call, code, context, format_cl_failure(call, code, context))
{
}

ClError::ClError(std::string call, cl_int code, std::string context, const std::string& message)
    : DeviceError(message), m_call(std::move(call)), m_code(code), m_context(std::move(context))
{
}

ClBuildError::ClBuildError(cl_int code, std::string context, std::string log)
    : ClError("clBuildProgram", code, context,
              format_cl_failure("clBuildProgram", code, context) + "\nbuild log:\n" +
                  (log.empty() ? std::string("(the driver gave no log)") : log)),
      m_log(std::move(log))
{
}

}  // namespace gc::cl
