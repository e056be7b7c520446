#include "host/scene/load.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "host/scene/gltf_loader.h"
#include "host/scene/obj_loader.h"
#include "host/scene/scene_checks.h"
#include "host/util/error.h"

namespace gc {

namespace {

// The file's extension, lower case (".obj", ".glb", ...).
std::string extension_of(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

bool is_gltf(const std::filesystem::path& path)
{
    const std::string ext = extension_of(path);
    return ext == ".gltf" || ext == ".glb";
}

Scene load_by_extension(const std::filesystem::path& path, const LoadOptions& options)
{
    const std::string ext = extension_of(path);
    if (ext == ".obj") return load_obj(path, options);
    if (is_gltf(path)) return load_gltf(path, options);
    throw InputError(path.string() + ": unsupported scene format '" + (ext.empty() ? std::string("(none)") : ext) +
                     "' (supported: .obj, .gltf, .glb)");
}

}  // namespace

Scene load_scene(const std::filesystem::path& path, const LoadOptions& options)
{
    Scene scene = load_by_extension(path, options);
    check_some_triangle_has_area(scene);
    check_renderable_scale(scene);
    return scene;
}

std::variant<Scene, InstancedScene> load_scene_keeping_instances(const std::filesystem::path& path,
                                                                 const LoadOptions& options)
{
    if (!is_gltf(path)) return load_scene(path, options);
    std::variant<Scene, InstancedScene> loaded = load_gltf_instanced_where_reused(path, options);
    Scene& checked = loaded.index() == 0 ? std::get<Scene>(loaded) : std::get<InstancedScene>(loaded).meshes;
    check_some_triangle_has_area(checked);
    check_renderable_scale(checked);
    return loaded;
}

}  // namespace gc
