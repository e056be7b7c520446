#include "host/scene/gltf_images.h"

#include <climits>
#include <cstdint>
#include <memory>
#include <string>

#include <stb_image.h>
#include <tiny_gltf.h>

namespace gc {

namespace {

std::string image_label(const tinygltf::Image& image, int index)
{
    return "image " + std::to_string(index) + (image.name.empty() ? "" : " '" + image.name + "'");
}

// The error for an embedded image whose bytes do not lie inside their buffer, or "" when they
// do (or the image is not embedded).
std::string check_embedded_range(const tinygltf::Image& image, int index, const tinygltf::Model& model)
{
    if (image.bufferView < 0) return {};
    // tinygltf checked both indices before calling us; check again rather than trust it.
    if (static_cast<std::size_t>(image.bufferView) >= model.bufferViews.size())
        return image_label(image, index) + ": bufferView " + std::to_string(image.bufferView) + " out of range";
    const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(image.bufferView)];
    if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
        return image_label(image, index) + ": bufferView " + std::to_string(image.bufferView) + " names buffer " +
               std::to_string(view.buffer) + ", out of range";
    const std::size_t size = model.buffers[static_cast<std::size_t>(view.buffer)].data.size();
    if (view.byteOffset > size || view.byteLength > size - view.byteOffset || view.byteLength > INT_MAX)
        return image_label(image, index) + ": bufferView " + std::to_string(image.bufferView) + " (bytes " +
               std::to_string(view.byteOffset) + " + " + std::to_string(view.byteLength) +
               ") runs past the end of buffer " + std::to_string(view.buffer) + " (" + std::to_string(size) + " bytes)";
    return {};
}

// Decodes with stb_image, keeping the file's channels and 16-bit depth as tinygltf's default
// decoder does, after checking the claimed size against the limits above.
std::string decode(tinygltf::Image& image, int index, const unsigned char* bytes, int size)
{
    const std::string label = image_label(image, index);
    if (!bytes || size <= 0) return label + ": no image data";
    // The claimed size first, so a header claiming gigapixels is refused before stb_image
    // allocates for it. When the header cannot be read, the decoder below gives the reason (the
    // probe tries every format and reports the last one's complaint, not the real one).
    int width = 0, height = 0, channels = 0;
    const auto too_large = [&] {
        return width > k_max_image_side || height > k_max_image_side ||
               static_cast<long long>(width) * height > k_max_image_texels;
    };
    const auto too_large_message = [&] {
        return label + ": " + std::to_string(width) + "x" + std::to_string(height) + " texels is too large (at most " +
               std::to_string(k_max_image_side) + " on a side and " + std::to_string(k_max_image_texels) + " in all)";
    };
    if (stbi_info_from_memory(bytes, size, &width, &height, &channels) && too_large()) return too_large_message();

    const bool sixteen_bit = stbi_is_16_bit_from_memory(bytes, size) != 0;
    std::unique_ptr<void, void (*)(void*)> pixels(
        sixteen_bit ? static_cast<void*>(stbi_load_16_from_memory(bytes, size, &width, &height, &channels, 0))
                    : static_cast<void*>(stbi_load_from_memory(bytes, size, &width, &height, &channels, 0)),
        stbi_image_free);
    if (!pixels || width <= 0 || height <= 0 || channels < 1 || channels > 4) {
        const char* why = stbi_failure_reason();
        return label + ": cannot decode (" + (why ? why : "unknown image format") + ")";
    }
    if (too_large()) return too_large_message();
    const int bytes_per_channel = sixteen_bit ? 2 : 1;
    const std::size_t total = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                              static_cast<std::size_t>(channels) * static_cast<std::size_t>(bytes_per_channel);
    const auto* first = static_cast<const unsigned char*>(pixels.get());
    image.image.assign(first, first + total);
    image.width = width;
    image.height = height;
    image.component = channels;
    image.bits = 8 * bytes_per_channel;
    image.pixel_type = sixteen_bit ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    return {};
}

bool decode_image_callback(tinygltf::Image* image, int index, std::string* err, std::string* /*warn*/,
                           int /*req_width*/, int /*req_height*/, const unsigned char* bytes, int size, void* user)
{
    const auto& model = *static_cast<const tinygltf::Model*>(user);
    std::string why = check_embedded_range(*image, index, model);
    if (why.empty()) why = decode(*image, index, bytes, size);
    if (why.empty()) return true;
    if (err) *err += why + "\n";
    return false;
}

}  // namespace

void install_checked_image_decoder(tinygltf::TinyGLTF& loader, const tinygltf::Model& model)
{
    // tinygltf's user pointer is non-const; the callback only reads through it.
    loader.SetImageLoader(decode_image_callback, const_cast<tinygltf::Model*>(&model));
}

}  // namespace gc
