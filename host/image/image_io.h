// Image files: write a Film (atomically) and read one back.
//
// Formats by extension (case-insensitive):
//   .pfm  float RGB, built in (rows bottom to top, as the PFM spec says), alpha dropped
//   .ppm  8-bit sRGB (binary P6), built in, alpha dropped
//   .png  written built in (png_writer.h): 8-bit sRGB RGB, metadata as tEXt chunks
//         ("Software", "geocold:device", ... as below, all as text); read through OIIO
//   with OpenImageIO (GC_HAVE_OIIO, CMake option GEOCOLD_WITH_OIIO; the OIIO code is the
//   module geocold-image-oiio.so, loaded on first use: see image_codec.h, image_module.h):
//   .exr  linear float RGBA with the metadata as attributes "geocold:device", "geocold:integrator",
//         "geocold:scene" (strings), "geocold:spp" (int), "geocold:seconds" (float),
//         "geocold:seed" (string: EXR has no unsigned attribute) and "Software"
//   .tif/.tiff  linear float RGBA;  .hdr  linear float RGB
//   any other format OIIO writes: 8-bit sRGB RGB, metadata as text where the format has it
// 8-bit outputs are the film through `display` (display_transform.h: exposure and a tone
// curve; the default is a plain clip to [0, 1]), encoded with the sRGB OETF (IEC 61966-2-1).
// Float outputs (.exr, .pfm, .hdr, .tif) are the linear film, whatever `display` says.
//
// Writes never leave a truncated file: the image goes to "<path>.tmp-<pid>" in the same
// directory, is fsync'ed, then renamed over the target; on any failure the temp file is
// removed and OutputError names the path and the reason (errno text), so the previous
// file at <path>, if any, is untouched.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "host/image/display_transform.h"
#include "host/image/film.h"
#include "host/image/srgb.h"

namespace gc {

void write_image(const std::filesystem::path& path, const Film& film, const ImageMetadata& meta,
                 const DisplayTransform& display = {});

// True for the formats written as 8-bit display values (.png, .ppm, ...), false for the
// float ones (.exr, .pfm, .hdr, .tif, .tiff), which stay linear.
bool is_display_referred(const std::filesystem::path& path);

// Fails (OutputError) before any rendering when write_image(path, ...) cannot succeed: an
// unsupported extension (or one that needs OIIO in a build without it, or an image module
// that cannot be loaded), a missing parent directory, a target that is a directory, or a
// directory where no file can be created. The same as check_output_location, then
// check_output_format.
void check_output_path(const std::filesystem::path& path);
// The checks that need no image module: the path, its folder, and an extension to go by.
void check_output_location(const std::filesystem::path& path);
// Whether the format of `path` can be written; waits for the image module when the format
// needs it (start_image_io_for lets that load overlap other work first).
void check_output_format(const std::filesystem::path& path);

// Starts loading, in the background, what reading or writing `path` will need: the image
// module for the formats that are not built in; nothing for .pfm/.ppm (nor for writing
// .png). Returns at once.
enum class ImageAccess { Read, Write };
void start_image_io_for(const std::filesystem::path& path, ImageAccess access);

// .pfm and .ppm are built in; .exr/.png/.hdr/.tif/... need OIIO. Integer-valued files
// (PNG, PPM, 8/16-bit TIFF) are decoded from sRGB to linear unless they say they are linear.
// One channel is read as grey; missing alpha is 1. Throws InputError naming the file.
Film read_image(const std::filesystem::path& path);

// True when this build reads and writes through OpenImageIO.
bool image_io_has_oiio();

namespace image_io_testing {
// Makes the next write_image fail, after the temp file is written and before it is synced,
// as if the system call had failed with errno `error` (e.g. ENOSPC). 0 clears it.
void fail_next_write(int error);
}  // namespace image_io_testing

}  // namespace gc
