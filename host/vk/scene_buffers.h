// A scene resident on a Vulkan device: the same device layouts the OpenCL renderer uploads
// (host/render/scene_convert.h, kernels/shared/gc_types.h), one storage buffer each, bound
// at the slots of kernels/vk/bindings.h. Both Vulkan passes read this.
#pragma once

#include <cstdint>

#include "gc_types.h"
#include "host/bvh/bvh.h"
#include "host/render/environment.h"
#include "host/render/render_settings.h"
#include "host/scene/scene.h"
#include "host/vk/buffer.h"
#include "host/vk/context.h"
#include "host/vk/pipeline.h"

namespace gc::vk {

struct SceneBuffers {
    Buffer params;     // GcRenderParams
    Buffer nodes;
    Buffer triangles;
    Buffer attribs;
    Buffer materials;
    Buffer textures;
    Buffer texels;
    Buffer emitters;
    Buffer positions;  // three vec4 per scene triangle, for the raster pass
    Buffer srgb_table; // gc_srgb_to_linear_table, read by gc_texture.h in GLSL
    Buffer sheen_table; // gc_sheen_albedo_table, read by gc_bsdf.h in GLSL
    Buffer point_lights;
    Buffer env_pixels;      // the environment map and its sampling cdfs (host/render/environment.h)
    Buffer env_marginal;
    Buffer env_conditional;

    dev::GcRenderParams host_params{};

    // `bvh` and `environment` may be null for passes that trace no rays (the raster pass): the
    // node, triangle and environment buffers are then left empty, and the parameters keep the
    // constant env_radiance. `environment` is the map of settings.env_map_path
    // (load_environment_map), set in the parameters as the OpenCL renderer sets it. Emitters
    // are the scene's triangles from `first_emitter` on (an instanced scene's world emitters
    // follow its meshes: with_world_emitters), as DeviceScene lists them.
    static SceneBuffers upload(const Context& context, const Scene& scene, const FlatBvh* bvh, const Camera& camera,
                               const RenderSettings& settings, const EnvironmentMap* environment = nullptr,
                               std::uint32_t first_emitter = 0);

    // Binds every scene buffer of `set` (all but the film).
    void bind(StorageBufferSet& set) const;
};

}  // namespace gc::vk
