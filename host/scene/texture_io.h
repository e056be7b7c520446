// Image files and decoded pixel buffers -> Texture (RGBA8, R in the low byte, row 0 on top).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "host/scene/scene.h"

namespace gc {

// Decodes an image file (PNG, JPEG, TGA, BMP, ... whatever stb_image reads). A missing or
// unreadable file throws InputError naming the texture and `referenced_by` (the scene file).
Texture load_texture_file(const std::filesystem::path& path, bool srgb, const std::string& referenced_by);

// Converts interleaved pixels with 1-4 channels of 8 or 16 bits (16-bit in host byte order,
// as stb_image returns them) to packed RGBA8: grey expands to RGB, missing alpha is opaque.
std::vector<std::uint32_t> pack_rgba8(const unsigned char* data, int width, int height, int channels, int bits);

}  // namespace gc
