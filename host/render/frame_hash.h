// The hashes that say whether two partial images belong to one frame: the content of the
// scene (what its files loaded into: geometry, materials, textures, lights) and the options
// that change the image (size, camera, integrator, depth, environment and the environment
// map's bytes, chunk size, adaptive sampling's noise threshold). Not the seed (recorded on its own), the sample count or range,
// nor what only changes the speed (device, wavefront size, samples per pass).
#pragma once

#include <cstdint>
#include <string>

#include "host/render/render_settings.h"
#include "host/scene/instances.h"
#include "host/scene/scene.h"

namespace gc {

// 64-bit FNV-1a over the loaded scene. Two loads of the same files give the same hash.
std::uint64_t scene_content_hash(const Scene& scene);
// The same for an instanced scene: its meshes, their ranges and the instances' transforms.
std::uint64_t scene_content_hash(const InstancedScene& scene);

// 64-bit FNV-1a over the image-changing settings, the camera and the chunk size; reads the
// environment map's file (InputError naming it when it cannot be read).
std::uint64_t render_options_hash(const RenderSettings& settings, const Camera& camera, std::uint32_t chunk_samples);

// 16 lowercase hex digits.
std::string hash_text(std::uint64_t hash);

}  // namespace gc
