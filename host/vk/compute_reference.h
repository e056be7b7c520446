// The Vulkan compute reference of the OpenCL integrators: GLSL compute shaders traverse the
// same flat BVH, or an instanced scene's two-level BVH, and call the same shared shading code
// (kernels/shared/gc_path_vertex.h, gc_whitted_tree.h, gc_aov.h) with the same random-number
// keying, one pixel per invocation and one sample per dispatch. Same interface as the OpenCL
// Renderer, so a cross-check drives both alike.
#pragma once

#include <cstdint>

#include "host/bvh/bvh.h"
#include "host/bvh/instance_bvh.h"
#include "host/image/film.h"
#include "host/render/render_settings.h"
#include "host/scene/instances.h"
#include "host/scene/scene.h"
#include "host/vk/buffer.h"
#include "host/vk/context.h"
#include "host/vk/handle.h"
#include "host/vk/pipeline.h"
#include "host/vk/scene_buffers.h"

namespace gc::vk {

class ComputeReference {
public:
    // settings.integrator: Path (path.comp), Whitted (whitted.comp) or Aov (aov.comp,
    // settings.aov); settings.env_map_path is loaded as the OpenCL renderer loads it.
    // settings.wavefront_size is ignored: a megakernel holds no per-path queues.
    ComputeReference(const Context& context, const Scene& scene, const FlatBvh& bvh, const Camera& camera,
                     const RenderSettings& settings);
    // An instanced scene: its meshes' trees and the top level (`bvh`, assemble_binary), lit by
    // every instance's emitters in world space as the OpenCL renderer's upload_instanced is.
    ComputeReference(const Context& context, const InstancedScene& scene, const InstancedBvh& bvh,
                     const Camera& camera, const RenderSettings& settings);

    // Adds sample number samples_done() to every pixel and waits for it.
    void render_sample();
    std::uint32_t samples_done() const { return m_samples; }

    // The mean of the samples so far, linear RGB, alpha 1 (as Renderer::film()).
    Film film() const;

private:
    // Binds the film and `shader`'s pipeline once m_scene (and, instanced, the top level) are up.
    void make_pipeline(std::span<const std::uint32_t> shader, const std::string& name);

    const Context& m_context;
    std::uint32_t m_width;
    std::uint32_t m_height;
    std::uint32_t m_samples = 0;
    SceneBuffers m_scene;
    Buffer m_tlas;       // instanced scenes: the top level's nodes
    Buffer m_instances;  // and the instances
    Buffer m_film;
    StorageBufferSet m_set;
    PipelineLayout m_layout;
    Pipeline m_pipeline;
};

}  // namespace gc::vk
