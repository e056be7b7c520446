// Checks a binary glTF (.glb) container before tinygltf parses it. tinygltf 2.7 checks the
// BIN chunk's length without its own 8-byte header, so a truncated file can make it read
// past the end of the buffer; this check is exact.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace gc {

// GLB layout (glTF 2.0 spec, "Binary glTF Layout"): a 12-byte header (magic "glTF",
// version 2, total length), then chunks of (uint32 length, uint32 type, data[length]): first
// JSON, then optionally BIN. Throws InputError naming `file_name` and the inconsistency.
void check_glb_container(const unsigned char* bytes, std::size_t size, const std::string& file_name);

// The JSON chunk's text, of a container check_glb_container accepted.
std::string_view glb_json_chunk(const unsigned char* bytes, std::size_t size);

}  // namespace gc
