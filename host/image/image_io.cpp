#include "host/image/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <fstream>
#include <iterator>
#include <system_error>
#include <utility>

#include <fcntl.h>
#include <unistd.h>

#include "host/image/atomic_file.h"
#include "host/image/png_writer.h"
#include "host/image/pnm_io.h"
#include "host/util/error.h"
#ifdef GC_HAVE_OIIO
#include "host/image/image_module.h"
#endif

namespace gc {
namespace {

std::string lower_extension(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

// The formats read and written without the image module. PNG, the default output, is written
// built in (png_writer.h) but read through the module.
bool reads_builtin(const std::string& ext) { return ext == ".pfm" || ext == ".ppm"; }
bool writes_builtin(const std::string& ext) { return reads_builtin(ext) || ext == ".png"; }

const char* k_no_extension = "the file name has no extension to choose the format by (use .exr, .png, .pfm or .ppm)";

#ifdef GC_HAVE_OIIO
// The module's codec; else throws `Failure` with the message `prefix` + why it cannot be loaded.
template <class Failure>
const ImageCodec& codec_or_throw(const std::string& prefix)
{
    std::string why;
    const ImageCodec* codec = image_module(&why);
    if (!codec) throw Failure(prefix + why);
    return *codec;
}
#endif

// Empty when `path`'s extension can be written by this build, else why not. Throws
// OutputError when that takes the image module and it cannot be loaded.
std::string format_problem(const std::filesystem::path& path)
{
    const std::string ext = lower_extension(path);
    if (ext.empty()) return k_no_extension;
    if (writes_builtin(ext)) return {};
#ifdef GC_HAVE_OIIO
    return codec_or_throw<OutputError>(detail::cannot_write(path)).cannot_write(path);
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

void start_image_io_for(const std::filesystem::path& path, ImageAccess access)
{
#ifdef GC_HAVE_OIIO
    const std::string ext = lower_extension(path);
    const bool builtin = access == ImageAccess::Read ? reads_builtin(ext) : writes_builtin(ext);
    if (!ext.empty() && !builtin) start_loading_image_module();
#else
    (void)path;
    (void)access;
#endif
}

void check_output_path(const std::filesystem::path& path)
{
    check_output_location(path);
    check_output_format(path);
}

void check_output_format(const std::filesystem::path& path)
{
    if (const std::string why = format_problem(path); !why.empty()) throw OutputError(detail::cannot_write(path) + why);
}

void check_output_location(const std::filesystem::path& path)
{
    const std::string prefix = detail::cannot_write(path);
    if (path.empty()) throw OutputError("cannot write image: the output path is empty");
    if (lower_extension(path).empty()) throw OutputError(prefix + k_no_extension);

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

bool is_display_referred(const std::filesystem::path& path)
{
    const std::string ext = lower_extension(path);
    return !(ext == ".exr" || ext == ".pfm" || ext == ".hdr" || ext == ".tif" || ext == ".tiff");
}

void write_image(const std::filesystem::path& path, const Film& linear, const ImageMetadata& meta,
                 const DisplayTransform& display)
{
    if (linear.empty()) throw OutputError(detail::cannot_write(path) + "the image is empty (0 pixels)");
    const std::string ext = lower_extension(path);
    // 8-bit outputs get the display transform; a copy only when it changes something.
    Film transformed;
    const bool transform = is_display_referred(path) && !is_identity(display);
    if (transform) transformed = to_display_linear(linear, display);
    const Film& film = transform ? transformed : linear;
    if (!writes_builtin(ext)) {
        if (const std::string why = format_problem(path); !why.empty())
            throw OutputError(detail::cannot_write(path) + why);
    }
    detail::replace_file_atomically(path, [&](const std::filesystem::path& tmp) {
        if (ext == ".pfm") {
            detail::write_bytes(tmp, detail::encode_pfm(film), path);
        } else if (ext == ".ppm") {
            detail::write_bytes(tmp, detail::encode_ppm(film), path);
        } else if (ext == ".png") {
            detail::write_bytes(tmp, detail::encode_png(film, meta, path.string()), path);
        } else {
#ifdef GC_HAVE_OIIO
            const ImageCodec& codec = codec_or_throw<OutputError>(detail::cannot_write(path));
            if (const std::string why = codec.write(tmp, path, film, meta); !why.empty())
                throw OutputError(detail::cannot_write(path) + why);
#endif
        }
    });
}

Film read_image(const std::filesystem::path& path)
{
    const std::string ext = lower_extension(path);
    if (ext == ".pfm") return detail::decode_pfm(read_all(path), path);
    if (ext == ".ppm") return detail::decode_ppm(read_all(path), path);
#ifdef GC_HAVE_OIIO
    const std::string prefix = "cannot read image '" + path.string() + "': ";
    DecodedImage decoded;
    if (const std::string why = codec_or_throw<InputError>(prefix).read(path, decoded); !why.empty())
        throw InputError(prefix + why);
    Film film(decoded.width, decoded.height);
    film.data() = std::move(decoded.rgba);
    return film;
#else
    throw InputError("cannot read image '" + path.string() + "': reading '" + ext +
                     "' needs OpenImageIO, which this build does not include; use .pfm or .ppm");
#endif
}

}  // namespace gc
