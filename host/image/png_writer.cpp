#include "host/image/png_writer.h"

#include <climits>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <vector>

#include "host/image/atomic_file.h"
#include "host/image/srgb.h"
#include "host/util/error.h"

// stb's encoder for the pixel data (filtering + deflate): header-only, already a dependency.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#ifndef GC_VERSION
#define GC_VERSION "unknown"
#endif

namespace gc::detail {
namespace {

// CRC-32 as PNG defines it (ISO 3309, polynomial 0xedb88320), over chunk type and data.
uint32_t crc32(const std::string& bytes)
{
    static const auto table = [] {
        std::vector<uint32_t> t(256);
        for (uint32_t n = 0; n < 256; ++n) {
            uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xedb88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    uint32_t c = 0xffffffffu;
    for (unsigned char b : bytes) c = table[(c ^ b) & 0xff] ^ (c >> 8);
    return c ^ 0xffffffffu;
}

void put_u32(std::string& out, uint32_t v)
{
    for (int shift = 24; shift >= 0; shift -= 8) out += char((v >> shift) & 0xff);
}

std::string chunk(const char type[5], const std::string& data)
{
    std::string out;
    put_u32(out, uint32_t(data.size()));
    const std::string body = std::string(type, 4) + data;
    out += body;
    put_u32(out, crc32(body));
    return out;
}

// tEXt holds Latin-1; anything else (a UTF-8 scene path) goes in iTXt, which holds UTF-8.
std::string text_chunk(const std::string& key, const std::string& value)
{
    bool ascii = true;
    for (unsigned char c : value) ascii = ascii && c != 0 && c < 0x80;
    if (ascii) return chunk("tEXt", key + '\0' + value);
    std::string clean;
    for (char c : value)
        if (c != '\0') clean += c;
    // keyword, NUL, compression flag 0, method 0, empty language tag + NUL, empty translated
    // keyword + NUL, text.
    return chunk("iTXt", key + '\0' + '\0' + '\0' + '\0' + '\0' + clean);
}

// What comes between IHDR and the image data: the colour space, then the metadata.
std::string ancillary_chunks(const ImageMetadata& meta)
{
    std::string out = chunk("sRGB", std::string(1, '\0'));  // perceptual rendering intent
    std::string gamma;
    put_u32(gamma, 45455);  // 1/2.2 * 100000: what the PNG spec says to pair with sRGB
    out += chunk("gAMA", gamma);
    std::string chrm;
    for (uint32_t v : {31270u, 32900u, 64000u, 33000u, 30000u, 60000u, 15000u, 6000u}) put_u32(chrm, v);
    out += chunk("cHRM", chrm);
    out += text_chunk("Software", "geocold-cl " GC_VERSION);
    out += text_chunk("geocold:device", meta.device);
    out += text_chunk("geocold:integrator", meta.integrator);
    out += text_chunk("geocold:scene", meta.scene);
    out += text_chunk("geocold:spp", std::to_string(meta.spp));
    out += text_chunk("geocold:seconds", std::to_string(meta.seconds));
    out += text_chunk("geocold:seed", std::to_string(meta.seed));
    return out;
}

}  // namespace

std::string encode_png(const Film& film, const ImageMetadata& meta, const std::string& target)
{
    const size_t row = size_t(film.width()) * 3;
    if (film.width() > uint32_t(INT_MAX) || row * film.height() > size_t(INT_MAX) - film.height())
        throw OutputError(cannot_write(target) + "the image is too large for PNG (" + std::to_string(film.width()) + "x" +
                          std::to_string(film.height()) + "); use .exr or .pfm");
    std::vector<unsigned char> rgb(row * film.height());
    const float* src = film.data().data();
    for (size_t i = 0, n = film.pixel_count(); i < n; ++i)
        for (int c = 0; c < 3; ++c) rgb[i * 3 + size_t(c)] = linear_to_srgb8(src[i * 4 + size_t(c)]);

    int size = 0;
    const std::unique_ptr<unsigned char, void (*)(void*)> png(
        stbi_write_png_to_mem(rgb.data(), int(row), int(film.width()), int(film.height()), 3, &size), std::free);
    // stb writes signature (8 bytes), IHDR (25), IDAT, IEND; the ancillary chunks go after IHDR.
    const size_t header = 8 + 25;
    if (!png || size_t(size) < header) throw OutputError(cannot_write(target) + "the PNG encoder failed (out of memory?)");
    const char* bytes = reinterpret_cast<const char*>(png.get());
    return std::string(bytes, header) + ancillary_chunks(meta) + std::string(bytes + header, size_t(size) - header);
}

}  // namespace gc::detail
