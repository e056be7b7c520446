// One sample of first-hit AOVs of an instanced scene in the Vulkan reference (aov.comp built
// with GC_SCENE_INSTANCED), for cross-checking kernels/aov.cl on the same scene.
#pragma once

#include "host/bvh/instance_bvh.h"
#include "host/image/film.h"
#include "host/render/render_settings.h"
#include "host/scene/instances.h"
#include "host/vk/context.h"

namespace gc::vk {

// settings.aov picks the value; the pixel-centre AOVs (depth, normal, primitive id) need one
// sample. `bvh` is the BVH2 layout of `scene` (assemble_binary).
Film render_instanced_aov(const Context& context, const InstancedScene& scene, const InstancedBvh& bvh,
                          const Camera& camera, const RenderSettings& settings);

}  // namespace gc::vk
