#include "host/vk/context.h"

#include <algorithm>
#include <cctype>
#include <limits>

#include "host/util/error.h"
#include "host/vk/vk_error.h"

namespace gc::vk {
namespace {

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

// Lower is better for "any": real GPUs first, the CPU rasteriser last.
int preference(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_OTHER: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 4;
    default: return 5;
    }
}

std::string version_text(std::uint32_t v)
{
    return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
           std::to_string(VK_API_VERSION_PATCH(v));
}

std::string device_list(const std::vector<PhysicalDeviceInfo>& devices)
{
    if (devices.empty()) return "no Vulkan devices";
    std::string out = "Vulkan devices:";
    for (const PhysicalDeviceInfo& d : devices) out += " '" + d.name + "' (" + device_type_name(d.type) + ")";
    return out;
}

std::vector<PhysicalDeviceInfo> enumerate(VkInstance instance)
{
    std::uint32_t count = 0;
    check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices", "counting devices");
    std::vector<VkPhysicalDevice> handles(count);
    check(vkEnumeratePhysicalDevices(instance, &count, handles.data()), "vkEnumeratePhysicalDevices",
          "listing devices");
    std::vector<PhysicalDeviceInfo> out;
    for (VkPhysicalDevice h : handles) {
        VkPhysicalDeviceProperties props{};
        vkGetPhysicalDeviceProperties(h, &props);
        PhysicalDeviceInfo info;
        info.handle = h;
        info.name = props.deviceName;
        info.type = props.deviceType;
        info.api_version = props.apiVersion;
        std::uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(h, &families, nullptr);
        std::vector<VkQueueFamilyProperties> fam(families);
        vkGetPhysicalDeviceQueueFamilyProperties(h, &families, fam.data());
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        info.has_graphics_compute_queue =
            std::any_of(fam.begin(), fam.end(), [&](const VkQueueFamilyProperties& f) { return (f.queueFlags & need) == need; });
        out.push_back(info);
    }
    return out;
}

}  // namespace

const char* device_type_name(VkPhysicalDeviceType type)
{
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

std::size_t choose_device(const std::vector<PhysicalDeviceInfo>& devices, const std::string& spec)
{
    const std::string want = lower(spec);
    std::size_t best = devices.size();
    for (std::size_t i = 0; i < devices.size(); ++i) {
        const PhysicalDeviceInfo& d = devices[i];
        if (!d.has_graphics_compute_queue) continue;
        if (want == "any") {
            if (best == devices.size() || preference(d.type) < preference(devices[best].type)) best = i;
        } else if (want == "lavapipe") {
            const bool is_lavapipe = lower(d.name).find("llvmpipe") != std::string::npos;
            // A later llvmpipe beats an earlier generic CPU device.
            if (is_lavapipe && (best == devices.size() || lower(devices[best].name).find("llvmpipe") == std::string::npos))
                best = i;
            else if (best == devices.size() && d.type == VK_PHYSICAL_DEVICE_TYPE_CPU)
                best = i;
        } else if (lower(d.name).find(want) != std::string::npos) {
            return i;
        }
    }
    if (best == devices.size())
        throw DeviceError("no Vulkan device matches --vk-device '" + spec + "' (" + device_list(devices) +
                          "; a device needs a queue with graphics and compute)");
    return best;
}

Context::Context(const std::string& device_spec)
{
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "geocold-cl";
    app.applicationVersion = VK_MAKE_API_VERSION(0, 0, 1, 0);
    app.pEngineName = "geocold-cl";
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    ici.pApplicationInfo = &app;
    // Headless: no surface extensions, no layers (validation is a developer's environment
    // choice: VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation).
    check(vkCreateInstance(&ici, nullptr, &m_instance), "vkCreateInstance",
          "creating the Vulkan instance (is a Vulkan driver such as Mesa's lavapipe installed?)");
    try {
        const std::vector<PhysicalDeviceInfo> devices = enumerate(m_instance);
        m_info = devices[choose_device(devices, device_spec)];
        if (m_info.api_version < VK_API_VERSION_1_1)
            throw DeviceError("Vulkan device '" + m_info.name + "' supports only Vulkan " +
                              version_text(m_info.api_version) + "; geocold-cl needs 1.1 or later");

        std::uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(m_info.handle, &families, nullptr);
        std::vector<VkQueueFamilyProperties> fam(families);
        vkGetPhysicalDeviceQueueFamilyProperties(m_info.handle, &families, fam.data());
        const VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
        for (std::uint32_t i = 0; i < families; ++i)
            if ((fam[i].queueFlags & need) == need) {
                m_queue_family = i;
                break;
            }

        const float priority = 1.0f;
        VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        qci.queueFamilyIndex = m_queue_family;
        qci.queueCount = 1;
        qci.pQueuePriorities = &priority;
        VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        dci.queueCreateInfoCount = 1;
        dci.pQueueCreateInfos = &qci;
        check(vkCreateDevice(m_info.handle, &dci, nullptr, &m_device), "vkCreateDevice",
              "opening Vulkan device '" + m_info.name + "'");
        vkGetDeviceQueue(m_device, m_queue_family, 0, &m_queue);
        vkGetPhysicalDeviceMemoryProperties(m_info.handle, &m_memory);

        VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        pci.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
        pci.queueFamilyIndex = m_queue_family;
        VkCommandPool pool = VK_NULL_HANDLE;
        check(vkCreateCommandPool(m_device, &pci, nullptr, &pool), "vkCreateCommandPool", "creating the command pool");
        m_pool = CommandPool(m_device, pool);
    } catch (...) {
        m_pool.reset();
        if (m_device != VK_NULL_HANDLE) vkDestroyDevice(m_device, nullptr);
        vkDestroyInstance(m_instance, nullptr);
        throw;
    }
}

Context::~Context()
{
    vkDeviceWaitIdle(m_device);
    m_pool.reset();
    vkDestroyDevice(m_device, nullptr);
    vkDestroyInstance(m_instance, nullptr);
}

std::string Context::description() const
{
    return m_info.name + " (Vulkan " + version_text(m_info.api_version) + ", " + device_type_name(m_info.type) + ")";
}

std::uint32_t Context::memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags required, const std::string& what) const
{
    for (std::uint32_t i = 0; i < m_memory.memoryTypeCount; ++i)
        if ((type_bits & (1u << i)) != 0 && (m_memory.memoryTypes[i].propertyFlags & required) == required) return i;
    throw DeviceError("Vulkan device '" + m_info.name + "' has no suitable memory type for " + what);
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record, const std::string& what) const
{
    VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    ai.commandPool = m_pool.get();
    ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    ai.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check(vkAllocateCommandBuffers(m_device, &ai, &cmd), "vkAllocateCommandBuffers", what);
    // The command buffer goes back to the pool however this function is left.
    struct Free {
        VkDevice device;
        VkCommandPool pool;
        VkCommandBuffer cmd;
        ~Free() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
    } free_cmd{m_device, m_pool.get(), cmd};

    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer", what);
    record(cmd);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer", what);

    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence raw_fence = VK_NULL_HANDLE;
    check(vkCreateFence(m_device, &fci, nullptr, &raw_fence), "vkCreateFence", what);
    const Fence fence(m_device, raw_fence);
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    check(vkQueueSubmit(m_queue, 1, &si, fence.get()), "vkQueueSubmit", what);
    check(vkWaitForFences(m_device, 1, &raw_fence, VK_TRUE, std::numeric_limits<std::uint64_t>::max()),
          "vkWaitForFences", what);
}

}  // namespace gc::vk
