// Vulkan failures as gc::DeviceError naming the call, the VkResult and what was being done:
//   vkAllocateMemory failed: VK_ERROR_OUT_OF_DEVICE_MEMORY while allocating 'bvh nodes'
#pragma once

#include <string>
#include <string_view>

#include <vulkan/vulkan.h>

#include "host/util/error.h"

namespace gc::vk {

// "VK_ERROR_DEVICE_LOST" for VK_ERROR_DEVICE_LOST; "VK_RESULT(<n>)" for codes this build does
// not name. Never empty.
std::string result_name(VkResult result);

// "vkFoo failed: NAME[ while <context>]".
std::string format_failure(std::string_view call, VkResult result, std::string_view context);

// Throws DeviceError(format_failure(...)) unless result is VK_SUCCESS. Other non-error codes
// (VK_INCOMPLETE, VK_TIMEOUT, ...) are failures too: no caller here expects them.
void check(VkResult result, std::string_view call, std::string_view context = {});

}  // namespace gc::vk
