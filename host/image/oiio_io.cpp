// The OpenImageIO image module (geocold-image-oiio.so): ImageCodec on top of OIIO. Built only
// when GEOCOLD_WITH_OIIO is on, and loaded by image_module.cpp on first use; see image_codec.h.
#include <algorithm>
#include <climits>
#include <exception>
#include <string_view>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include "host/image/image_codec.h"
#include "host/image/srgb.h"

#ifndef GC_VERSION
#define GC_VERSION "unknown"
#endif

namespace gc {
namespace {

// Formats that store linear float: everything else gets 8-bit sRGB.
bool stores_float(std::string_view format) { return format == "openexr" || format == "tiff" || format == "hdr"; }
// Formats whose writer takes an alpha channel we want to keep.
bool stores_alpha(std::string_view format) { return format == "openexr" || format == "tiff"; }

std::string oiio_error(const std::string& primary)
{
    std::string e = primary.empty() ? OIIO::geterror() : primary;
    return e.empty() ? std::string("OpenImageIO reported no reason") : e;
}

std::string no_writer(const std::filesystem::path& target)
{
    const std::string why = OIIO::geterror();
    return "OpenImageIO has no writer for '" + target.extension().string() + "'" + (why.empty() ? "" : " (" + why + ")");
}

std::string write_oiio(const std::filesystem::path& tmp, const std::filesystem::path& target, const Film& film,
                       const ImageMetadata& meta)
{
    auto out = OIIO::ImageOutput::create(target.string());
    if (!out) return no_writer(target);
    const std::string format = out->format_name();
    const bool as_float = stores_float(format);
    const int channels = stores_alpha(format) ? 4 : 3;

    OIIO::ImageSpec spec(int(film.width()), int(film.height()), channels,
                         as_float ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8);
    spec.attribute("Software", "geocold-cl " GC_VERSION);
    spec.attribute("oiio:ColorSpace", as_float ? "Linear" : "sRGB");
    spec.attribute("geocold:device", meta.device);
    spec.attribute("geocold:integrator", meta.integrator);
    spec.attribute("geocold:scene", meta.scene);
    spec.attribute("geocold:spp", int(std::min<uint32_t>(meta.spp, INT_MAX)));
    spec.attribute("geocold:seconds", float(meta.seconds));
    spec.attribute("geocold:seed", std::to_string(meta.seed));
    if (format == "openexr") spec.attribute("compression", "zip");  // lossless

    // Pack the film into what the format stores.
    std::vector<float> f;
    std::vector<uint8_t> u8;
    const size_t n = film.pixel_count();
    if (as_float) f.resize(n * channels);
    else u8.resize(n * channels);
    const float* src = film.data().data();
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < channels; ++c) {
            if (as_float) f[i * channels + c] = src[i * 4 + c];
            else u8[i * channels + c] = linear_to_srgb8(src[i * 4 + c]);
        }

    if (!out->open(tmp.string(), spec)) return oiio_error(out->geterror());
    const bool ok = as_float ? out->write_image(OIIO::TypeDesc::FLOAT, f.data())
                             : out->write_image(OIIO::TypeDesc::UINT8, u8.data());
    if (!ok) {
        const std::string why = oiio_error(out->geterror());
        out->close();
        return why;
    }
    if (!out->close()) return oiio_error(out->geterror());
    return {};
}

std::string read_oiio(const std::filesystem::path& path, DecodedImage& image)
{
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return oiio_error({});
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) return "it has no pixels";
    const int nch = std::min(spec.nchannels, 4);
    std::vector<float> buf(size_t(spec.width) * spec.height * nch);
    if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, buf.data())) return oiio_error(in->geterror());

    // Integer files hold display-referred sRGB unless they say otherwise.
    const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
    const bool decode = !spec.format.is_floating_point() && !OIIO::Strutil::iequals(cs, "linear");
    // Alpha sits where the file says, else last of 2 (grey + alpha) or 4 channels.
    const bool grey = nch < 3;
    int alpha = spec.alpha_channel >= 0 && spec.alpha_channel < nch ? spec.alpha_channel : -1;
    if (alpha < 0 && (nch == 2 || nch == 4)) alpha = nch - 1;

    image.width = uint32_t(spec.width);
    image.height = uint32_t(spec.height);
    const size_t pixels = size_t(image.width) * image.height;
    image.rgba.assign(pixels * 4, 0.0f);
    float* dst = image.rgba.data();
    for (size_t i = 0; i < pixels; ++i) {
        const float* p = buf.data() + i * nch;
        for (int c = 0; c < 3; ++c) {
            const float v = p[grey ? 0 : c];
            dst[i * 4 + c] = decode ? srgb_decode(v) : v;
        }
        dst[i * 4 + 3] = alpha >= 0 ? p[alpha] : 1.0f;
    }
    return {};
}

// Runs `body`, turning anything it throws (OIIO, std::bad_alloc) into the returned reason.
template <class Body>
std::string guarded(Body&& body)
{
    try {
        return body();
    } catch (const std::bad_alloc&) {
        return "out of host memory";
    } catch (const std::exception& e) {
        return std::string("OpenImageIO failed: ") + e.what();
    } catch (...) {
        return "OpenImageIO failed with an unknown exception";
    }
}

class OiioCodec final : public ImageCodec {
public:
    std::string cannot_write(const std::filesystem::path& target) const override
    {
        return guarded([&]() -> std::string { return OIIO::ImageOutput::create(target.string()) ? "" : no_writer(target); });
    }

    std::string write(const std::filesystem::path& tmp, const std::filesystem::path& target, const Film& film,
                      const ImageMetadata& meta) const override
    {
        return guarded([&] { return write_oiio(tmp, target, film, meta); });
    }

    std::string read(const std::filesystem::path& path, DecodedImage& image) const override
    {
        return guarded([&] { return read_oiio(path, image); });
    }
};

}  // namespace
}  // namespace gc

extern "C" __attribute__((visibility("default"))) const gc::ImageCodec* gc_image_module_v1()
{
    static const gc::OiioCodec codec;
    return &codec;
}
