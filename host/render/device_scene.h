// A scene resident on one OpenCL device: the BVH in the device's layout, shading attributes,
// materials, textures and lights, in the layouts of kernels/shared/gc_types.h.
#pragma once

#include <cstdint>

#include "gc_types.h"
#include "host/bvh/bvh.h"
#include "host/cl/buffer.h"
#include "host/render/device_bvh.h"
#include "host/render/environment.h"
#include "host/scene/scene.h"

namespace gc {

struct DeviceScene {
    DeviceBvh bvh;  // BVH2 or BVH4, as bvh_layout_for(device) chose
    cl::Buffer<dev::GcTriangleAttribs> attribs;
    cl::Buffer<dev::GcMaterial> materials;
    cl::Buffer<dev::GcTexture> textures;
    cl::Buffer<std::uint32_t> texels;
    cl::Buffer<dev::GcEmitter> emitters;
    cl::Buffer<dev::GcPointLight> point_lights;
    cl::Buffer<glm::vec4> env_pixels;
    cl::Buffer<float> env_marginal;
    cl::Buffer<float> env_conditional;

    std::uint32_t triangle_count = 0;
    std::uint32_t emitter_count = 0;
    std::uint32_t point_light_count = 0;
    std::uint32_t texture_count = 0;
    std::uint32_t env_width = 0;  // 0: no environment map
    std::uint32_t env_height = 0;

    // Bytes of device memory the scene occupies (reported by --verbose and the benchmark).
    std::uint64_t bytes() const;

    static DeviceScene upload(const cl::Context& context, const Scene& scene, const FlatBvh& bvh,
                              const EnvironmentMap& environment = {});
};

}  // namespace gc
