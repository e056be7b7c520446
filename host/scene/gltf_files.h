// The file access tinygltf does for external buffers and images, routed through
// host/scene/scene_file.h.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace tinygltf {
class TinyGLTF;
}

namespace gc {

// Why each file tinygltf asked for could not be read, in order. tinygltf turns a missing image
// into a warning and an empty image; this lets the loader's error say what was wrong with it.
class GltfFileLog {
public:
    void add(std::string path, std::string why) { m_failures.emplace_back(std::move(path), std::move(why)); }
    // The reason recorded for the file a uri resolved to (tinygltf joins the scene's folder
    // and the uri), or "" if none.
    std::string why_not_read(const std::string& uri) const;

private:
    std::vector<std::pair<std::string, std::string>> m_failures;
};

// tinygltf's own reader opens whatever a uri names: a FIFO blocks forever and a device is read
// as far as its reported size. With these callbacks only regular files are read, anything else
// is refused with the reason ("is not a regular file (a device, pipe or socket)"), and every
// failure is recorded in `log`, which must outlive the load call.
void install_regular_file_access(tinygltf::TinyGLTF& loader, GltfFileLog& log);

}  // namespace gc
