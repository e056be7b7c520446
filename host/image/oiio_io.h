// The OpenImageIO side of image_io: only compiled when GC_HAVE_OIIO is defined.
#pragma once

#include <filesystem>
#include <string>

#include "host/image/film.h"

namespace gc::detail {

// Writes `film` to `tmp` in the format OIIO picks for `target`'s extension. Throws OutputError.
void oiio_write(const std::filesystem::path& tmp, const std::filesystem::path& target, const Film& film,
                const ImageMetadata& meta);

// Empty when OIIO has a writer for the extension of `target`, else the reason.
std::string oiio_cannot_write(const std::filesystem::path& target);

Film oiio_read(const std::filesystem::path& path);  // throws InputError

}  // namespace gc::detail
