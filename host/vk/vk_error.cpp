#include "host/vk/vk_error.h"

namespace gc::vk {

std::string result_name(VkResult result)
{
    switch (result) {
#define GC_VK_NAME(x) \
    case x: return #x;
    GC_VK_NAME(VK_SUCCESS)
    GC_VK_NAME(VK_NOT_READY)
    GC_VK_NAME(VK_TIMEOUT)
    GC_VK_NAME(VK_EVENT_SET)
    GC_VK_NAME(VK_EVENT_RESET)
    GC_VK_NAME(VK_INCOMPLETE)
    GC_VK_NAME(VK_ERROR_OUT_OF_HOST_MEMORY)
    GC_VK_NAME(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    GC_VK_NAME(VK_ERROR_INITIALIZATION_FAILED)
    GC_VK_NAME(VK_ERROR_DEVICE_LOST)
    GC_VK_NAME(VK_ERROR_MEMORY_MAP_FAILED)
    GC_VK_NAME(VK_ERROR_LAYER_NOT_PRESENT)
    GC_VK_NAME(VK_ERROR_EXTENSION_NOT_PRESENT)
    GC_VK_NAME(VK_ERROR_FEATURE_NOT_PRESENT)
    GC_VK_NAME(VK_ERROR_INCOMPATIBLE_DRIVER)
    GC_VK_NAME(VK_ERROR_TOO_MANY_OBJECTS)
    GC_VK_NAME(VK_ERROR_FORMAT_NOT_SUPPORTED)
    GC_VK_NAME(VK_ERROR_FRAGMENTED_POOL)
    GC_VK_NAME(VK_ERROR_UNKNOWN)
    GC_VK_NAME(VK_ERROR_OUT_OF_POOL_MEMORY)
    GC_VK_NAME(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    GC_VK_NAME(VK_ERROR_FRAGMENTATION)
    GC_VK_NAME(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    GC_VK_NAME(VK_ERROR_INVALID_SHADER_NV)
#undef GC_VK_NAME
    default: break;
    }
    return "VK_RESULT(" + std::to_string(static_cast<int>(result)) + ")";
}

std::string format_failure(std::string_view call, VkResult result, std::string_view context)
{
    std::string message = std::string(call) + " failed: " + result_name(result);
    if (!context.empty()) message += " while " + std::string(context);
    return message;
}

void check(VkResult result, std::string_view call, std::string_view context)
{
    if (result != VK_SUCCESS) throw DeviceError(format_failure(call, result, context));
}

}  // namespace gc::vk
