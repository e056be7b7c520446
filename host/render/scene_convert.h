// The one place host types become the device layouts of kernels/shared/gc_types.h.
// Pure functions of the scene: no device needed, so tests check them on the host.
#pragma once

#include <cstdint>
#include <vector>

#include "gc_types.h"
#include "host/scene/scene.h"

namespace gc {

struct DeviceTextures {
    std::vector<dev::GcTexture> textures;
    std::vector<std::uint32_t> texels;
};

std::vector<dev::GcTriangleAttribs> make_triangle_attribs(const Scene& scene);
std::vector<dev::GcMaterial> make_materials(const Scene& scene);
DeviceTextures make_textures(const Scene& scene);
std::vector<dev::GcPointLight> make_point_lights(const Scene& scene);

// Emissive triangles with power-proportional selection probabilities (power = area times
// the luminance of the emitted radiance). Zero-area emitters are left out: they can never
// be hit nor sampled. The last cdf is exactly 1.
std::vector<dev::GcEmitter> make_emitters(const Scene& scene);

// Pinhole camera for a width x height image (square pixels, vertical field of view).
dev::GcCamera make_camera(const Camera& camera, int width, int height);

}  // namespace gc
