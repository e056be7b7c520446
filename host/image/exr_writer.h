// The project's own OpenEXR writer: uncompressed scan-line images of 32-bit UINT and FLOAT
// channels, single-part or multi-part (OpenEXR 2), written atomically (atomic_file.h). It needs
// no OpenImageIO, so the bare GPU build writes partial images (partial_image.h) and AOV layers
// (aov_layers.h) too; any EXR reader opens its files.
//
// One unnamed part is written as a plain single-part file; named parts (one or more) as a
// multi-part file, in the order given, so a layer keeps its name even when it is alone.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace gc {

enum class ExrPixelType : std::int32_t { Uint = 0, Float = 2 };  // EXR's codes

struct ExrChannel {
    std::string name;
    ExrPixelType type = ExrPixelType::Float;
    // width * height values, row 0 at the top: UINT values, or FLOAT values' bit patterns.
    std::vector<std::uint32_t> bits;
};

struct ExrPart {
    std::string name;                 // "albedo", "depth", ...; empty: a single-part file
    std::vector<ExrChannel> channels; // any order: EXR stores them sorted by name
    std::vector<std::pair<std::string, std::string>> text;  // string attributes, in this order
};

// The file's bytes. Throws UsageError for no parts, channel data of the wrong size, or
// several parts with an empty or repeated name.
std::string encode_exr(std::uint32_t width, std::uint32_t height, const std::vector<ExrPart>& parts);

// encode_exr, written atomically; OutputError naming the file on failure.
void write_exr(const std::filesystem::path& path, std::uint32_t width, std::uint32_t height,
               const std::vector<ExrPart>& parts);

// A FLOAT channel's bits from floats.
std::vector<std::uint32_t> float_bits(const std::vector<float>& values);

}  // namespace gc
