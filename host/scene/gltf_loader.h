// glTF 2.0 (.gltf with external or embedded data, .glb) -> Scene, through tinygltf, with every
// accessor, index and node checked before use.
#pragma once

#include <filesystem>
#include <variant>

#include "host/scene/instances.h"
#include "host/scene/load_options.h"
#include "host/scene/scene.h"

namespace gc {

// Takes every TRIANGLES primitive of every mesh instance in the chosen scene
// (options.gltf_scene, else the file's default scene, else scene 0), in world space: node
// transforms compose down the hierarchy, normals go through the inverse transpose, and
// mirroring transforms flip the winding so front faces stay front. Materials become
// MaterialType::Pbr (metallic-roughness); primitives without one get the scene's "default"
// Lambert 0.5 material, as OBJ faces do. The first perspective camera met in the hierarchy
// becomes Scene::camera; KHR_lights_punctual point lights become Scene::point_lights.
Scene load_gltf(const std::filesystem::path& path, const LoadOptions& options = {});

// The same file with its node tree kept as instances: every mesh a node draws is stored once,
// in object space (InstancedScene::meshes, in the order nodes first draw them), and each such
// node becomes an instance with its world transform; materials, camera and lights as above.
// flatten_instances(result, MirroredWinding::FrontStaysFront) is load_gltf's scene up to the
// transforms' rounding.
InstancedScene load_gltf_instanced(const std::filesystem::path& path, const LoadOptions& options = {});

// load_gltf_instanced where the scene's nodes draw some mesh more than once, else load_gltf's
// scene, from one read of the file.
std::variant<Scene, InstancedScene> load_gltf_instanced_where_reused(const std::filesystem::path& path,
                                                                     const LoadOptions& options = {});

}  // namespace gc
