#include "host/scene/scene_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "host/util/error.h"

namespace gc {

std::string why_not_regular_file(const std::filesystem::path& path)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    switch (status.type()) {
    case fs::file_type::regular: return {};
    case fs::file_type::not_found: return "file not found";
    case fs::file_type::directory: return "is a directory, not a file";
    case fs::file_type::none:
    case fs::file_type::unknown: return "cannot be examined (" + ec.message() + ")";
    default: return "is not a regular file (a device, pipe or socket)";
    }
}

std::vector<unsigned char> read_regular_file(const std::filesystem::path& path)
{
    if (const std::string why = why_not_regular_file(path); !why.empty()) throw InputError(path.string() + ": " + why);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path.string() + ": cannot open file (" + std::strerror(errno) + ")");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(path.string() + ": read error");
    return bytes;
}

}  // namespace gc
