// The built-in PNG writer: 8-bit sRGB RGB, the same pixels the OpenImageIO module writes, with
// the metadata as tEXt chunks ("Software", "geocold:device", ...). Built in because PNG is the
// default output: writing it through the module would cost every render ~0.35 s of loading
// OpenImageIO. Reading PNG still goes through the module.
#pragma once

#include <string>

#include "host/image/film.h"

namespace gc::detail {

// The whole file as bytes. Throws OutputError (naming `target`) when the image is too large
// for the encoder (width * height * 3 must fit in an int).
std::string encode_png(const Film& film, const ImageMetadata& meta, const std::string& target);

}  // namespace gc::detail
