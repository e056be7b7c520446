// A Vulkan buffer with its own host-visible, coherent memory, mapped for its whole life.
// The Vulkan path is a cross-check, not the fast path: one allocation per buffer and host
// memory everywhere keep it simple (on lavapipe all memory is host memory anyway).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "host/vk/context.h"
#include "host/vk/handle.h"

namespace gc::vk {

class Buffer {
public:
    Buffer() = default;
    // `name` appears in error messages ("... while allocating 'bvh nodes'"). A zero size is
    // rounded up to 16 bytes: Vulkan has no empty buffers, and shaders never read past the
    // counts they are given.
    Buffer(const Context& context, VkDeviceSize bytes, VkBufferUsageFlags usage, std::string name);

    template <typename T>
    static Buffer with_data(const Context& context, std::span<const T> data, VkBufferUsageFlags usage, std::string name)
    {
        Buffer b(context, data.size_bytes(), usage, std::move(name));
        b.write(data.data(), data.size_bytes());
        return b;
    }
    template <typename T, typename Allocator>
    static Buffer with_data(const Context& context, const std::vector<T, Allocator>& data, VkBufferUsageFlags usage,
                            std::string name)
    {
        return with_data(context, std::span<const T>(data), usage, std::move(name));
    }

    void write(const void* data, std::size_t bytes, std::size_t offset = 0);
    void read(void* data, std::size_t bytes, std::size_t offset = 0) const;
    void fill_zero();

    VkBuffer get() const { return m_buffer.get(); }
    VkDeviceSize size() const { return m_size; }
    const std::string& name() const { return m_name; }

private:
    BufferHandle m_buffer;
    Memory m_memory;
    void* m_mapped = nullptr;
    VkDeviceSize m_size = 0;
    std::string m_name;
};

}  // namespace gc::vk
