#include "host/vk/buffer.h"

#include <cstring>

#include "host/util/error.h"
#include "host/vk/vk_error.h"

namespace gc::vk {

Buffer::Buffer(const Context& context, VkDeviceSize bytes, VkBufferUsageFlags usage, std::string name)
    : m_size(bytes == 0 ? 16 : bytes), m_name(std::move(name))
{
    const std::string what = "allocating '" + m_name + "' (" + std::to_string(m_size) + " bytes)";
    VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bci.size = m_size;
    bci.usage = usage;
    bci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VkBuffer buffer = VK_NULL_HANDLE;
    check(vkCreateBuffer(context.device(), &bci, nullptr, &buffer), "vkCreateBuffer", what);
    m_buffer = BufferHandle(context.device(), buffer);

    VkMemoryRequirements req{};
    vkGetBufferMemoryRequirements(context.device(), buffer, &req);
    VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    mai.allocationSize = req.size;
    mai.memoryTypeIndex = context.memory_type(
        req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, "'" + m_name + "'");
    VkDeviceMemory memory = VK_NULL_HANDLE;
    check(vkAllocateMemory(context.device(), &mai, nullptr, &memory), "vkAllocateMemory", what);
    m_memory = Memory(context.device(), memory);
    check(vkBindBufferMemory(context.device(), buffer, memory, 0), "vkBindBufferMemory", what);
    check(vkMapMemory(context.device(), memory, 0, VK_WHOLE_SIZE, 0, &m_mapped), "vkMapMemory", what);
}

void Buffer::write(const void* data, std::size_t bytes, std::size_t offset)
{
    if (offset + bytes > m_size)
        throw DeviceError("write of " + std::to_string(bytes) + " bytes at " + std::to_string(offset) +
                          " overflows Vulkan buffer '" + m_name + "' (" + std::to_string(m_size) + " bytes)");
    if (bytes > 0) std::memcpy(static_cast<char*>(m_mapped) + offset, data, bytes);
}

void Buffer::read(void* data, std::size_t bytes, std::size_t offset) const
{
    if (offset + bytes > m_size)
        throw DeviceError("read of " + std::to_string(bytes) + " bytes at " + std::to_string(offset) +
                          " overflows Vulkan buffer '" + m_name + "' (" + std::to_string(m_size) + " bytes)");
    if (bytes > 0) std::memcpy(data, static_cast<const char*>(m_mapped) + offset, bytes);
}

void Buffer::fill_zero() { std::memset(m_mapped, 0, static_cast<std::size_t>(m_size)); }

}  // namespace gc::vk
