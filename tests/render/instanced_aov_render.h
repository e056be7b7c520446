// One sample of an AOV of an instanced scene through the library (DeviceScene::upload_instanced,
// kernels/aov.cl built with GC_SCENE_INSTANCED), for the tests that compare its images.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "host/bvh/instance_bvh.h"
#include "host/cl/context.h"
#include "host/render/device_scene.h"
#include "host/render/renderer.h"

namespace gc::test {

// The per-pixel values of settings.aov (one sample, alpha 1), in the BVH layout the device
// uses; `layout` names it.
inline std::vector<glm::vec4> render_instanced_aov(const cl::Context& context, const InstancedScene& scene,
                                                   const InstanceBvhParts& parts, const Camera& camera,
                                                   RenderSettings settings, BvhLayout* layout = nullptr)
{
    settings.integrator = IntegratorKind::Aov;
    settings.spp = 1;
    auto device_scene = std::make_shared<const DeviceScene>(DeviceScene::upload_instanced(context, scene, parts));
    if (layout) *layout = device_scene->bvh.layout();
    Renderer renderer(context, device_scene, camera, settings, {});
    renderer.render(0, 1);
    return renderer.sums(false).sums;
}

}  // namespace gc::test
