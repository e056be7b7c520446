// Entry point of the scene module: a file in, a Scene out.
#pragma once

#include <filesystem>
#include <variant>

#include "host/scene/instances.h"
#include "host/scene/load_options.h"
#include "host/scene/scene.h"

namespace gc {

// Loads .obj (with its .mtl files and textures), .gltf or .glb, chosen by the extension
// (case-insensitive). Throws InputError naming the file for anything unreadable or malformed;
// a file with another extension is an InputError listing the supported ones, and so is a
// scene whose triangles all have zero area (scene_checks.h).
Scene load_scene(const std::filesystem::path& path, const LoadOptions& options = {});

// As load_scene, but a glTF whose nodes draw some mesh more than once comes back as an
// InstancedScene, each mesh stored once (load_gltf_instanced); the checks then apply to the
// meshes.
std::variant<Scene, InstancedScene> load_scene_keeping_instances(const std::filesystem::path& path,
                                                                 const LoadOptions& options = {});

}  // namespace gc
