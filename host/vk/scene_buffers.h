// A scene resident on a Vulkan device: the same device layouts the OpenCL renderer uploads
// (host/render/scene_convert.h, kernels/shared/gc_types.h), one storage buffer each, bound
// at the slots of kernels/vk/bindings.h. Both Vulkan passes read this.
#pragma once

#include <cstdint>

#include "gc_types.h"
#include "host/bvh/bvh.h"
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

    dev::GcRenderParams host_params{};

    // `bvh` may be null for passes that trace no rays (the raster pass): the node and
    // triangle buffers are then left empty.
    static SceneBuffers upload(const Context& context, const Scene& scene, const FlatBvh* bvh, const Camera& camera,
                               const RenderSettings& settings);

    // Binds every scene buffer of `set` (all but the film).
    void bind(StorageBufferSet& set) const;
};

}  // namespace gc::vk
