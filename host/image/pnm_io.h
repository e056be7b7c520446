// The built-in formats, always available: PFM (float RGB / grey) and binary PPM (P6, 8-bit).
// Encoders return the whole file as bytes; decoders take the bytes and the file name (for
// messages) and throw InputError on anything malformed.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "host/image/film.h"

namespace gc::detail {

// "PF\n<w> <h>\n-1\n" then little-endian float RGB rows, bottom row first (the PFM spec;
// the negative scale marks little-endian data).
std::string encode_pfm(const Film& film);
std::string encode_ppm(const Film& film);  // sRGB-encoded, clamped

Film decode_pfm(std::string_view bytes, const std::filesystem::path& name);
Film decode_ppm(std::string_view bytes, const std::filesystem::path& name);  // P6, maxval <= 65535

}  // namespace gc::detail
