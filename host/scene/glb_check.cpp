#include "host/scene/glb_check.h"

#include <algorithm>
#include <cstdint>

#include "host/util/error.h"

namespace gc {

namespace {

std::uint32_t read_u32_le(const unsigned char* p)
{
    return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
           (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

constexpr std::uint32_t k_magic = 0x46546C67;      // "glTF"
constexpr std::uint32_t k_chunk_json = 0x4E4F534A; // "JSON"
constexpr std::uint32_t k_chunk_bin = 0x004E4942;  // "BIN\0"

}  // namespace

void check_glb_container(const unsigned char* bytes, std::size_t size, const std::string& file_name)
{
    const std::string prefix = file_name + ": invalid .glb: ";
    if (size < 12) throw InputError(prefix + "file is " + std::to_string(size) + " bytes, shorter than the 12-byte header");
    if (read_u32_le(bytes) != k_magic) throw InputError(prefix + "missing the 'glTF' magic (not a binary glTF file)");
    const std::uint32_t version = read_u32_le(bytes + 4);
    if (version != 2) throw InputError(prefix + "container version " + std::to_string(version) + " (only 2 is supported)");
    const std::uint64_t length = read_u32_le(bytes + 8);
    if (length > size)
        throw InputError(prefix + "header says " + std::to_string(length) + " bytes but the file has " +
                         std::to_string(size) + " (truncated?)");

    std::uint64_t offset = 12;
    int chunk = 0;
    while (offset < length) {
        if (offset + 8 > length)
            throw InputError(prefix + "chunk " + std::to_string(chunk) + " header at byte " + std::to_string(offset) +
                             " runs past the end (" + std::to_string(length) + " bytes)");
        const std::uint64_t chunk_length = read_u32_le(bytes + offset);
        const std::uint32_t type = read_u32_le(bytes + offset + 4);
        if (offset + 8 + chunk_length > length)
            throw InputError(prefix + "chunk " + std::to_string(chunk) + " (" + std::to_string(chunk_length) +
                             " bytes at byte " + std::to_string(offset + 8) + ") runs past the end (" +
                             std::to_string(length) + " bytes; truncated?)");
        if (chunk == 0 && type != k_chunk_json) throw InputError(prefix + "the first chunk is not JSON");
        if (chunk == 0 && chunk_length == 0) throw InputError(prefix + "the JSON chunk is empty");
        if (chunk == 1 && type != k_chunk_bin) throw InputError(prefix + "the second chunk is not BIN");
        offset += 8 + chunk_length;
        ++chunk;
    }
    if (chunk == 0) throw InputError(prefix + "no JSON chunk");
}

std::string_view glb_json_chunk(const unsigned char* bytes, std::size_t size)
{
    // Header (12 bytes), then the JSON chunk's length and type (8), then its data.
    const std::size_t length = read_u32_le(bytes + 12);
    return {reinterpret_cast<const char*>(bytes) + 20, std::min(length, size - 20)};
}

}  // namespace gc
