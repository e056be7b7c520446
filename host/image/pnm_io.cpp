#include "host/image/pnm_io.h"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "host/image/image_io.h"
#include "host/util/error.h"

namespace gc::detail {
namespace {

uint32_t byteswap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

void append_float_le(std::string& out, float f)
{
    uint32_t bits = std::bit_cast<uint32_t>(f);
    if constexpr (std::endian::native == std::endian::big) bits = byteswap32(bits);
    char b[4];
    std::memcpy(b, &bits, 4);
    out.append(b, 4);
}

// A netpbm-style header reader: whitespace-separated tokens, '#' comments (PPM only).
class HeaderReader {
public:
    HeaderReader(std::string_view bytes, const std::filesystem::path& name, bool comments)
        : m_bytes(bytes), m_name(name), m_comments(comments)
    {
    }

    std::string token()
    {
        skip_space();
        const size_t start = m_pos;
        while (m_pos < m_bytes.size() && !std::isspace(static_cast<unsigned char>(m_bytes[m_pos]))) ++m_pos;
        if (start == m_pos) fail("truncated header");
        return std::string(m_bytes.substr(start, m_pos - start));
    }

    uint32_t positive(const char* what)
    {
        const std::string t = token();
        char* end = nullptr;
        const unsigned long v = std::strtoul(t.c_str(), &end, 10);
        if (*end != '\0' || t[0] == '-' || v == 0 || v > 1u << 20)
            fail(std::string("bad ") + what + " '" + t + "'");
        return uint32_t(v);
    }

    // Exactly one whitespace byte separates the header from the raster in both formats.
    std::string_view raster()
    {
        if (m_pos >= m_bytes.size() || !std::isspace(static_cast<unsigned char>(m_bytes[m_pos])))
            fail("missing whitespace after the header");
        return m_bytes.substr(m_pos + 1);
    }

    [[noreturn]] void fail(const std::string& what) const
    {
        throw InputError("cannot read image '" + m_name.string() + "': " + what);
    }

private:
    void skip_space()
    {
        while (m_pos < m_bytes.size()) {
            const char c = m_bytes[m_pos];
            if (m_comments && c == '#') {
                while (m_pos < m_bytes.size() && m_bytes[m_pos] != '\n') ++m_pos;
            } else if (std::isspace(static_cast<unsigned char>(c))) {
                ++m_pos;
            } else {
                break;
            }
        }
    }

    std::string_view m_bytes;
    const std::filesystem::path& m_name;
    bool m_comments;
    size_t m_pos = 0;
};

}  // namespace

std::string encode_pfm(const Film& film)
{
    std::string out = "PF\n" + std::to_string(film.width()) + " " + std::to_string(film.height()) + "\n-1.0\n";
    out.reserve(out.size() + film.pixel_count() * 12);
    for (uint32_t row = 0; row < film.height(); ++row) {
        const uint32_t y = film.height() - 1 - row;
        for (uint32_t x = 0; x < film.width(); ++x) {
            const float* p = film.pixel(x, y);
            for (int c = 0; c < 3; ++c) append_float_le(out, p[c]);
        }
    }
    return out;
}

std::string encode_ppm(const Film& film)
{
    std::string out = "P6\n" + std::to_string(film.width()) + " " + std::to_string(film.height()) + "\n255\n";
    out.reserve(out.size() + film.pixel_count() * 3);
    for (uint32_t y = 0; y < film.height(); ++y)
        for (uint32_t x = 0; x < film.width(); ++x) {
            const float* p = film.pixel(x, y);
            for (int c = 0; c < 3; ++c) out.push_back(static_cast<char>(linear_to_srgb8(p[c])));
        }
    return out;
}

Film decode_pfm(std::string_view bytes, const std::filesystem::path& name)
{
    HeaderReader h(bytes, name, false);
    const std::string magic = h.token();
    if (magic != "PF" && magic != "Pf") h.fail("not a PFM file (magic '" + magic.substr(0, 8) + "')");
    const int channels = magic == "PF" ? 3 : 1;
    const uint32_t w = h.positive("width"), hgt = h.positive("height");
    const std::string scale_text = h.token();
    char* end = nullptr;
    const double scale = std::strtod(scale_text.c_str(), &end);
    if (*end != '\0' || scale == 0.0 || !std::isfinite(scale)) h.fail("bad scale '" + scale_text + "'");
    const bool little = scale < 0;
    const std::string_view raster = h.raster();
    const size_t need = size_t(w) * hgt * channels * 4;
    if (raster.size() < need)
        h.fail("truncated: " + std::to_string(raster.size()) + " bytes of pixels, need " + std::to_string(need));

    Film film(w, hgt);
    const bool swap = little != (std::endian::native == std::endian::little);
    size_t at = 0;
    for (uint32_t row = 0; row < hgt; ++row) {
        const uint32_t y = hgt - 1 - row;
        for (uint32_t x = 0; x < w; ++x) {
            float v[3];
            for (int c = 0; c < channels; ++c, at += 4) {
                uint32_t bits;
                std::memcpy(&bits, raster.data() + at, 4);
                v[c] = std::bit_cast<float>(swap ? byteswap32(bits) : bits);
            }
            if (channels == 1) v[1] = v[2] = v[0];
            film.set(x, y, {v[0], v[1], v[2], 1.0f});
        }
    }
    return film;
}

Film decode_ppm(std::string_view bytes, const std::filesystem::path& name)
{
    HeaderReader h(bytes, name, true);
    const std::string magic = h.token();
    if (magic != "P6") h.fail("only binary PPM (P6) is supported, found '" + magic.substr(0, 8) + "'");
    const uint32_t w = h.positive("width"), hgt = h.positive("height");
    const uint32_t maxval = h.positive("maxval");
    if (maxval > 65535) h.fail("bad maxval " + std::to_string(maxval));
    const size_t bpc = maxval < 256 ? 1 : 2;  // 16-bit samples are big-endian (netpbm)
    const std::string_view raster = h.raster();
    const size_t need = size_t(w) * hgt * 3 * bpc;
    if (raster.size() < need)
        h.fail("truncated: " + std::to_string(raster.size()) + " bytes of pixels, need " + std::to_string(need));

    Film film(w, hgt);
    const auto* p = reinterpret_cast<const unsigned char*>(raster.data());
    for (uint32_t y = 0; y < hgt; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float v[3];
            for (int c = 0; c < 3; ++c) {
                const uint32_t s = bpc == 1 ? p[0] : (uint32_t(p[0]) << 8 | p[1]);
                p += bpc;
                v[c] = srgb_decode(float(s) / float(maxval));
            }
            film.set(x, y, {v[0], v[1], v[2], 1.0f});
        }
    return film;
}

}  // namespace gc::detail
