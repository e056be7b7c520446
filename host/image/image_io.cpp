#include "host/image/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <iterator>
#include <system_error>

#include <fcntl.h>
#include <unistd.h>

#include "host/image/atomic_file.h"
#include "host/image/pnm_io.h"
#include "host/util/error.h"
#ifdef GC_HAVE_OIIO
#include "host/image/oiio_io.h"
#endif

namespace gc {
namespace {

std::string lower_extension(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

bool is_builtin(const std::string& ext) { return ext == ".pfm" || ext == ".ppm"; }

// Empty when `path`'s extension can be written by this build, else why not.
std::string format_problem(const std::filesystem::path& path)
{
    const std::string ext = lower_extension(path);
    if (ext.empty()) return "the file name has no extension to choose the format by (use .exr, .png, .pfm or .ppm)";
    if (is_builtin(ext)) return {};
#ifdef GC_HAVE_OIIO
    return detail::oiio_cannot_write(path);
#else
    return "writing '" + ext + "' needs OpenImageIO, which this build does not include (configured with "
           "GEOCOLD_WITH_OIIO=OFF); use .pfm or .ppm";
#endif
}

std::string read_all(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int e = errno;
        throw InputError("cannot read image '" + path.string() + "': " +
                         std::error_code(e, std::generic_category()).message());
    }
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError("cannot read image '" + path.string() + "': read error");
    return bytes;
}

}  // namespace

bool image_io_has_oiio()
{
#ifdef GC_HAVE_OIIO
    return true;
#else
    return false;
#endif
}

float srgb_encode(float linear)
{
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded)
{
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

uint8_t linear_to_srgb8(float linear)
{
    // NaN fails both comparisons: map it to black rather than to an arbitrary byte.
    const float c = linear > 0.0f ? std::fmin(linear, 1.0f) : 0.0f;
    return uint8_t(std::lround(srgb_encode(c) * 255.0f));
}

void check_output_path(const std::filesystem::path& path)
{
    const std::string prefix = detail::cannot_write(path);
    if (path.empty()) throw OutputError("cannot write image: the output path is empty");
    if (const std::string why = format_problem(path); !why.empty()) throw OutputError(prefix + why);

    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw OutputError(prefix + "it is a directory");
    std::filesystem::path dir = path.parent_path();
    if (dir.empty()) dir = ".";
    if (!std::filesystem::exists(dir, ec)) throw OutputError(prefix + "directory '" + dir.string() + "' does not exist");
    if (!std::filesystem::is_directory(dir, ec)) throw OutputError(prefix + "'" + dir.string() + "' is not a directory");

    // access(W_OK) says yes to root on a read-only filesystem: create the temp file
    // write_image will use, which is the real question.
    const std::filesystem::path probe = detail::temp_path_for(path);
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        const int e = errno;
        throw OutputError(prefix + "cannot create files in '" + dir.string() + "': " +
                          std::error_code(e, std::generic_category()).message());
    }
    ::close(fd);
    ::unlink(probe.c_str());
}

void write_image(const std::filesystem::path& path, const Film& film, const ImageMetadata& meta)
{
    if (film.empty()) throw OutputError(detail::cannot_write(path) + "the image is empty (0 pixels)");
    const std::string ext = lower_extension(path);
    if (!is_builtin(ext)) {
        if (const std::string why = format_problem(path); !why.empty())
            throw OutputError(detail::cannot_write(path) + why);
    }
    detail::replace_file_atomically(path, [&](const std::filesystem::path& tmp) {
        if (ext == ".pfm") {
            detail::write_bytes(tmp, detail::encode_pfm(film), path);
        } else if (ext == ".ppm") {
            detail::write_bytes(tmp, detail::encode_ppm(film), path);
        } else {
#ifdef GC_HAVE_OIIO
            detail::oiio_write(tmp, path, film, meta);
#endif
        }
    });
    (void)meta;  // only the OIIO formats carry metadata
}

Film read_image(const std::filesystem::path& path)
{
    const std::string ext = lower_extension(path);
    if (ext == ".pfm") return detail::decode_pfm(read_all(path), path);
    if (ext == ".ppm") return detail::decode_ppm(read_all(path), path);
#ifdef GC_HAVE_OIIO
    return detail::oiio_read(path);
#else
    throw InputError("cannot read image '" + path.string() + "': reading '" + ext +
                     "' needs OpenImageIO, which this build does not include; use .pfm or .ppm");
#endif
}

}  // namespace gc
