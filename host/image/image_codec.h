// The interface between image_io and the OpenImageIO image module (geocold-image-oiio.so).
//
// Linking OpenImageIO costs every run of a program ~0.35 s of dynamic linking before main()
// (libOpenImageIO pulls ~260 shared libraries), even runs that never touch an image. So the
// OIIO code lives in a module that image_module.cpp dlopen()s on first use, and this header
// is all the two sides share. The module and the program come from the same build (same
// compiler, same Film layout); the versioned entry point name guards against an old module.
//
// Failures are returned as text, never thrown: nothing unwinds across the dlopen boundary,
// and the program side turns the text into InputError / OutputError naming the file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "host/image/film.h"

namespace gc {

// What a reader hands back: width * height * 4 floats, linear RGBA, top row first (Film's
// layout), so the program side can move it into a Film.
struct DecodedImage {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<float> rgba;
};

class ImageCodec {
public:
    virtual ~ImageCodec() = default;

    // Empty when the codec has a writer for `target`'s extension, else why not.
    virtual std::string cannot_write(const std::filesystem::path& target) const = 0;

    // Writes `film` to `tmp` in the format `target`'s extension names (the caller renames
    // tmp over target). Empty on success, else the reason (without the file name).
    virtual std::string write(const std::filesystem::path& tmp, const std::filesystem::path& target,
                              const Film& film, const ImageMetadata& meta) const = 0;

    // Reads `path` into `image`. Empty on success, else the reason (without the file name).
    virtual std::string read(const std::filesystem::path& path, DecodedImage& image) const = 0;
};

}  // namespace gc

// The module's one exported symbol: returns its codec (a static object that lives as long as
// the module is loaded). Bump the version when ImageCodec, Film or ImageMetadata change.
#define GC_IMAGE_MODULE_ENTRY "gc_image_module_v1"
extern "C" {
using GcImageModuleEntry = const gc::ImageCodec* (*)();
}
