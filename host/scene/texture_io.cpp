#include "host/scene/texture_io.h"

#include <cstring>
#include <memory>

#include <stb_image.h>

#include "host/scene/scene_file.h"
#include "host/util/error.h"

namespace gc {

namespace {

std::uint32_t pack(unsigned r, unsigned g, unsigned b, unsigned a)
{
    return (r & 0xffu) | ((g & 0xffu) << 8) | ((b & 0xffu) << 16) | ((a & 0xffu) << 24);
}

// 16-bit -> 8-bit with rounding, so 65535 stays 255 and mid-grey stays mid-grey.
unsigned to8(std::uint16_t v) { return (static_cast<unsigned>(v) * 255u + 32767u) / 65535u; }

}  // namespace

std::vector<std::uint32_t> pack_rgba8(const unsigned char* data, int width, int height, int channels, int bits)
{
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<std::uint32_t> out(count);
    const std::size_t bytes_per_channel = bits == 16 ? 2 : 1;
    for (std::size_t i = 0; i < count; ++i) {
        unsigned c[4] = {0, 0, 0, 255};
        for (int k = 0; k < channels; ++k) {
            const unsigned char* p = data + (i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(k)) * bytes_per_channel;
            if (bits == 16) {
                std::uint16_t v;
                std::memcpy(&v, p, 2);
                c[k] = to8(v);
            } else {
                c[k] = *p;
            }
        }
        switch (channels) {
        case 1: out[i] = pack(c[0], c[0], c[0], 255); break;
        case 2: out[i] = pack(c[0], c[0], c[0], c[1]); break;
        case 3: out[i] = pack(c[0], c[1], c[2], 255); break;
        default: out[i] = pack(c[0], c[1], c[2], c[3]); break;
        }
    }
    return out;
}

Texture load_texture_file(const std::filesystem::path& path, bool srgb, const std::string& referenced_by)
{
    if (const std::string why = why_not_regular_file(path); !why.empty())
        throw InputError(referenced_by + ": texture '" + path.string() + "' " + (why == "file not found" ? "not found" : why));
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<unsigned char, void (*)(void*)> pixels(
        stbi_load(path.string().c_str(), &width, &height, &channels, 4), stbi_image_free);
    if (!pixels || width <= 0 || height <= 0) {
        const char* why = stbi_failure_reason();
        throw InputError(referenced_by + ": cannot read texture '" + path.string() + "': " +
                         (why ? why : "unknown image format"));
    }
    Texture t;
    t.name = path.string();
    t.width = width;
    t.height = height;
    t.srgb = srgb;
    t.texels = pack_rgba8(pixels.get(), width, height, 4, 8);
    return t;
}

}  // namespace gc
