#include "host/scene/gltf_files.h"

#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "host/scene/scene_file.h"
#include "host/util/error.h"

namespace gc {

namespace {

// "Exists" is answered for anything on disk, so a uri naming a pipe reaches read_file and
// gets its real reason instead of tinygltf's "File not found".
bool path_exists(const std::string& path, void* log)
{
    std::error_code ec;
    if (std::filesystem::exists(path, ec)) return true;
    static_cast<GltfFileLog*>(log)->add(path, "file not found");
    return false;
}

// glTF uris are relative to the file or absolute; no ~ or $VAR expansion (as tinygltf 2.7).
std::string path_as_is(const std::string& path, void* /*user*/) { return path; }

bool read_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* log)
{
    std::string why = why_not_regular_file(path);
    if (why.empty()) {
        try {
            *out = read_regular_file(path);
            if (out->empty()) why = "empty file";
        } catch (const InputError& e) {
            why = e.what();  // "<path>: <why>"; the path is added back below
            if (why.rfind(path + ": ", 0) == 0) why.erase(0, path.size() + 2);
        }
    }
    if (why.empty()) return true;
    static_cast<GltfFileLog*>(log)->add(path, why);
    if (err) *err += path + ": " + why + "\n";
    return false;
}

bool refuse_write(std::string* err, const std::string& path, const std::vector<unsigned char>& /*bytes*/, void* /*user*/)
{
    if (err) *err += path + ": geocold-cl never writes glTF files\n";
    return false;
}

}  // namespace

std::string GltfFileLog::why_not_read(const std::string& uri) const
{
    for (const auto& [path, why] : m_failures)
        if (path == uri || (path.size() > uri.size() && path.compare(path.size() - uri.size(), uri.size(), uri) == 0 &&
                            path[path.size() - uri.size() - 1] == '/'))
            return why;
    return {};
}

void install_regular_file_access(tinygltf::TinyGLTF& loader, GltfFileLog& log)
{
    tinygltf::FsCallbacks callbacks{};
    callbacks.FileExists = path_exists;
    callbacks.ExpandFilePath = path_as_is;
    callbacks.ReadWholeFile = read_file;
    callbacks.WriteWholeFile = refuse_write;
    callbacks.user_data = &log;
    loader.SetFsCallbacks(callbacks);
}

}  // namespace gc
